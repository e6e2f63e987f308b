#!/usr/bin/env python3
"""A parameter sweep with the contactrb Python module (docs/python.md), plotted with matplotlib.

Builds a reduced model of a one-parameter case from HF snapshots at a few training values (or
loads one with --model), answers a fine sweep of the parameter with one solve_many call, checks
a few points against HF solves, and plots the energy, the contact force and the error estimate
against the parameter to DIR/sweep.png (DIR/sweep.csv holds the numbers).

    PYTHONPATH=build/python python3 examples/python/sweep.py --case hertz-a --out sweep
"""

import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import contactrb  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="hertz-a", help="built-in case name or TOML case file (one parameter)")
    parser.add_argument("--model", help="a model file to sweep instead of building one")
    parser.add_argument("--training", type=int, default=7, help="training values (equispaced over the domain)")
    parser.add_argument("--points", type=int, default=200, help="sweep points")
    parser.add_argument("--check", type=int, default=4,
                        help="HF solves to check the sweep against, at the midpoints of --check equal intervals")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", default="sweep", help="output directory")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    if args.model:
        model = contactrb.Model.load(args.model)
        case = contactrb.Case(args.case)
    else:
        case = contactrb.Case(args.case)
        if case.num_parameters != 1:
            sys.exit(f"{case.name} has {case.num_parameters} parameters: this sweep is for one")
        p = case.parameters[0]
        training = np.linspace(p.min, p.max, args.training)
        snaps = contactrb.snapshots(case, training, jobs=args.jobs)
        model = contactrb.offline(snaps)
    p = model.parameters[0]
    print(f"{model!r}: sweeping {p.name} over [{p.min}, {p.max}] with {args.points} points")

    mu = np.linspace(p.min, p.max, args.points)
    sweep = model.solve_many(mu)
    failed = ~sweep["converged"]
    if failed.any():
        names = [contactrb.STATUS[c] for c in sweep["status"][failed]]
        print(f"warning: {failed.sum()} online solves did not converge: {sorted(set(names))}")
    per_query_us = 1e6 * np.median(sweep["time_s"])
    print(f"online: median {per_query_us:.1f} us per query")

    # Between training values (with the defaults: none of the 7 is checked).
    check = p.min + (p.max - p.min) * (np.arange(args.check) + 0.5) / args.check
    hf = [case.solve(float(m)) for m in check]
    worst = 0.0
    for m, h in zip(check, hf):
        r = model.solve(float(m))
        worst = max(worst, abs(r.force - h.force) / abs(h.force))
        print(f"  {p.name} = {m:.6g}: energy HF {h.energy:.8g}, RB {r.energy:.8g}; "
              f"force HF {h.force:.8g}, RB {r.force:.8g}; estimate {r.estimate:.3g}")
    print(f"max relative contact-force difference RB / HF at the checked points: {worst:.2e}")

    np.savetxt(os.path.join(args.out, "sweep.csv"),
               np.column_stack([mu, sweep["energy"], sweep["force"], sweep["estimate"], sweep["converged"]]),
               delimiter=",", header=f"{p.name},energy,force,estimate,converged", comments="")

    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(6, 8))
    label = f"{p.name}" + (f" [{p.units}]" if p.units else "")
    axes[0].plot(mu, sweep["energy"], label="reduced")
    axes[0].plot(check, [h.energy for h in hf], "o", label="HF")
    axes[0].set_ylabel("energy")
    axes[0].legend()
    axes[1].plot(mu, sweep["force"], label="reduced")
    axes[1].plot(check, [h.force for h in hf], "o", label="HF")
    axes[1].set_ylabel("contact force")
    axes[2].semilogy(mu, sweep["estimate"])
    axes[2].set_ylabel("error estimate")
    axes[2].set_xlabel(label)
    axes[0].set_title(f"{model.case_name}: {args.points} online solves")
    fig.tight_layout()
    png = os.path.join(args.out, "sweep.png")
    fig.savefig(png, dpi=100)
    print(f"wrote {png}")
    if failed.any():
        return 3
    if worst > 1e-2:  # a model this far from HF between its training values is a failure here
        print(f"error: the sweep is {worst:.2e} from HF (more than 1e-2)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
