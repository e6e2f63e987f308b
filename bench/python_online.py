#!/usr/bin/env python3
"""Per-query time of the Python module's online solves (docs/python.md, "Performance").

On one model file, at n equispaced points of the first parameter's domain (the points of
bench_online_loop), reports the wall time per query of
  solve_many   one Model.solve_many call (the loop in C++, GIL released), with --jobs threads
               (default 1; 0: every hardware thread; several: also checked bitwise against jobs=1),
  solve loop   a Python loop of Model.solve,
  in-solver    the median of the solver's own time_s (what the C++ solve costs inside the loop),
each the best of --repeats runs, wall clock and CPU time of the calling thread. Compare with bench_online_loop on the same model file:
    PYTHONPATH=build/python python3 bench/python_online.py --model model.h5 [--jobs 2] [--no-loop]
    CONTACTRB_BENCH_MODEL=model.h5 build/bench/bench_online_loop
"""

import argparse
import time

import numpy as np

import contactrb


def best_of(repeats, f, clock=time.thread_time):
    """Best wall and best CPU time (`clock`: of the calling thread, or of the process for
    solve_many on threads) of `repeats` calls (the CPU time is the one to compare on a loaded
    machine, as bench_online_loop's CPU column)."""
    best, best_cpu = float("inf"), float("inf")
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), clock()
        out = f()
        best = min(best, time.perf_counter() - t0)
        best_cpu = min(best_cpu, clock() - c0)
    return best, best_cpu, out


def main():
    parser = argparse.ArgumentParser(description="per-query time of Model.solve_many and Model.solve")
    parser.add_argument("--model", required=True)
    parser.add_argument("--points", type=int, default=1000)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--jobs", type=int, default=1, help="threads of solve_many (0: every hardware thread)")
    parser.add_argument("--no-loop", action="store_true", help="skip the Python loop of Model.solve")
    args = parser.parse_args()
    model = contactrb.Model.load(args.model)
    p = model.parameters[0]
    n = args.points
    mu = np.tile(np.array([q.reference for q in model.parameters]), (n, 1))
    mu[:, 0] = [p.min + (p.max - p.min) * i / (n - 1) for i in range(n)]  # as bench_online_loop
    model.solve(mu[0])  # the solver is set up once, outside the timings
    # With threads the calling thread only waits: the CPU time is then the process's (all threads).
    clock = time.thread_time if args.jobs == 1 else time.process_time
    t_many, c_many, many = best_of(args.repeats, lambda: model.solve_many(mu, jobs=args.jobs), clock)
    print(f"model {args.model}: {model!r}, {n} points, best of {args.repeats}")
    cpu = "thread" if args.jobs == 1 else "process"
    print(f"solve_many:  {1e6 * t_many / n:8.1f} us per query wall, {1e6 * c_many / n:8.1f} us {cpu} CPU, "
          f"jobs={args.jobs}")
    if args.jobs != 1:
        one = model.solve_many(mu, jobs=1)
        same = all(np.array_equal(one[k], many[k], equal_nan=True) for k in one if k != "time_s")
        print(f"bitwise equal to jobs=1: {same}")
    if not args.no_loop:
        t_loop, c_loop, _ = best_of(args.repeats, lambda: [model.solve(m) for m in mu])
        print(f"solve loop:  {1e6 * t_loop / n:8.1f} us per query wall, {1e6 * c_loop / n:8.1f} us CPU")
    print(f"in-solver:   {1e6 * np.median(many['time_s']):8.1f} us per query (median time_s), "
          f"{1e6 * np.sum(many['time_s']) / n:.1f} us mean")
    print(f"converged:   {int(many['converged'].sum())} of {n}")


if __name__ == "__main__":
    main()
