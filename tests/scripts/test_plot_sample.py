#!/usr/bin/python3
"""The figure of scripts/plot_sample.py (`contactrb sample`), checked on the matplotlib figure:
every panel has its quantity and unit on the x axis and the count on the y axis, and the title
states the input distribution.

Usage: test_plot_sample.py SCRIPTS_DIR   (run by ctest as plot_sample_labels)
"""
import csv
import os
import sys
import tempfile

sys.path.insert(0, sys.argv[1])
import plot_sample  # noqa: E402  (the script, imported as a module: main() does not run)
import matplotlib.pyplot as plt  # noqa: E402

OUTPUTS = ["contact_force", "peak_pressure", "max_gap", "min_gap", "energy", "estimate", "iterations"]

with tempfile.TemporaryDirectory() as d:
    stats, hist, png = (os.path.join(d, n) for n in ("s.csv", "s_histograms.csv", "s.png"))
    with open(stats, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["output", "count", "mean", "sd", "min", "max", "q05", "q50", "q95"])
        for name in OUTPUTS:
            w.writerow([name, 10, 1.5, 0.1, 1.0, 2.0, 1.1, 1.5, 1.9])
    with open(hist, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["output", "bin", "lo", "hi", "count"])
        for name in OUTPUTS:
            w.writerow([name, 0, 1.0, 1.5, 4])
            w.writerow([name, 1, 1.5, 2.0, 6])
    title = "10 points (seed 1): mu uniform on [0.15, 0.45]"
    plot_sample.main(["plot_sample.py", stats, hist, png, title])
    assert os.path.getsize(png) > 1000
    fig = plt.gcf()
    panels = [ax for ax in fig.axes if ax.axison]
    assert len(panels) == len(OUTPUTS), len(panels)
    for ax, name in zip(panels, OUTPUTS):
        label = ax.get_xlabel()
        assert label == plot_sample.AXIS_LABELS[name], (name, label)
        assert "[" in label and "]" in label, (name, label)  # the unit
        assert ax.get_ylabel() == "number of points"
    assert fig._suptitle is not None and fig._suptitle.get_text() == title
print("plot_sample_labels: ok")
