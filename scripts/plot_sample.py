#!/usr/bin/python3
"""Figure of `contactrb sample` (docs/parallel.md, "Sampling").

Usage: /usr/bin/python3 scripts/plot_sample.py STATS_CSV HISTOGRAMS_CSV OUT_PNG [INPUT]

One panel per output (contact force, peak pressure, max gap, min gap, energy, estimate,
iterations): its histogram, with the mean and the 5 % and 95 % quantiles marked, the
quantity and its unit on the x axis. INPUT (the parameter distribution and the number of
points, as `contactrb sample` describes them) is the figure's title.

Units: contactrb has none of its own; every output is in the units of the case's data (the
Young's moduli E, the lengths of the mesh), per unit thickness in plane strain.

Exit status: 0 on success, 1 with one line "plot_sample: error: ..." on stderr for a missing
or malformed input, 2 when matplotlib or numpy cannot be imported.
"""
import csv
import math
import sys


def fail(message, code=1):
    sys.stderr.write("plot_sample: error: %s\n" % message)
    sys.exit(code)


try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as exc:  # pragma: no cover - depends on the installation
    fail("cannot import matplotlib (%s); install python3-matplotlib" % exc, 2)


def read_rows(path, columns):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as exc:
        fail("cannot read %s: %s" % (path, exc))
    for row in rows:
        if any(c not in row for c in columns):
            fail("%s lacks one of the columns %s" % (path, ", ".join(columns)))
    return rows


# The x-axis label of each output of `contactrb sample` (docs/cli.md, "sample").
AXIS_LABELS = {
    "contact_force": "contact force [E x length] (per unit thickness)",
    "peak_pressure": "peak contact pressure [E]",
    "max_gap": "largest normal gap [length]",
    "min_gap": "smallest normal gap [length]",
    "energy": "energy 1/2 u'Au - f'u [E x length^2] (per unit thickness)",
    "estimate": "error estimate of |u - u_rb|_A [sqrt(E) x length]",
    "iterations": "online iterations [count]",
}


def main(argv):
    if len(argv) not in (4, 5):
        fail("usage: plot_sample.py STATS_CSV HISTOGRAMS_CSV OUT_PNG [INPUT]")
    stats = read_rows(argv[1], ["output", "count", "mean", "q05", "q95"])
    hist = read_rows(argv[2], ["output", "lo", "hi", "count"])
    if not stats:
        fail("%s holds no output" % argv[1])
    cols = 2
    rows = (len(stats) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.5 * cols, 3.6 * rows), squeeze=False)
    try:
        for ax, s in zip(axes.flat, stats):
            name = s["output"]
            bins = [h for h in hist if h["output"] == name]
            lo = [float(h["lo"]) for h in bins]
            hi = [float(h["hi"]) for h in bins]
            counts = [int(h["count"]) for h in bins]
            widths = [max(b - a, 0.0) for a, b in zip(lo, hi)]
            if widths and all(w == 0.0 for w in widths):
                widths = [abs(lo[0]) * 1e-3 or 1.0]
            ax.bar(lo, counts, width=widths, align="edge", color="#4c72b0", edgecolor="none")
            for key, style in (("mean", "-"), ("q05", "--"), ("q95", "--")):
                value = float(s[key])
                if math.isfinite(value) and int(s["count"]) > 0:
                    ax.axvline(value, color="#c44e52", linestyle=style, linewidth=1, label=key)
            ax.set_title("%s (%s values)" % (name.replace("_", " "), s["count"]))
            ax.set_xlabel(AXIS_LABELS.get(name, name.replace("_", " ")))
            ax.set_ylabel("number of points")
            ax.legend(fontsize=7)
    except ValueError as exc:
        fail("malformed number in the CSV files: %s" % exc)
    for ax in list(axes.flat)[len(stats):]:
        ax.axis("off")
    if len(argv) == 5:
        fig.suptitle(argv[4], fontsize=10)
    fig.tight_layout()
    try:
        fig.savefig(argv[3], dpi=100, format="png")  # the name may be a temporary without .png
    except OSError as exc:
        fail("cannot write %s: %s" % (argv[3], exc))


if __name__ == "__main__":
    main(sys.argv)
