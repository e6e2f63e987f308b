#!/usr/bin/env python3
"""Process time of a command: the median wall clock and CPU time (user + system) over n runs.

A bench figure (docs/performance.md, "Online query"), never a timed test:
    bench/process_time.py [-n 20] -- contactrb online --model m.h5 --mu 0.3
The CPU time is the better figure on a loaded machine (the wall clock includes waiting for a
core); os.times() counts it in clock ticks (10 ms on Linux), so the median over many runs.
"""
import argparse
import os
import statistics
import subprocess
import time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-n", type=int, default=20, help="runs (default 20)")
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    cmd = a.command[1:] if a.command[:1] == ["--"] else a.command
    wall, cpu = [], []
    for _ in range(a.n):
        t0, r0 = time.perf_counter(), os.times()
        subprocess.run(cmd, stdout=subprocess.DEVNULL, check=True)
        t1, r1 = time.perf_counter(), os.times()
        wall.append(t1 - t0)
        cpu.append(r1.children_user - r0.children_user + r1.children_system - r0.children_system)
    print(f"{' '.join(cmd)}: {a.n} runs, median wall {statistics.median(wall) * 1e3:.1f} ms "
          f"(min {min(wall) * 1e3:.1f}), median CPU {statistics.median(cpu) * 1e3:.0f} ms")


if __name__ == "__main__":
    main()
