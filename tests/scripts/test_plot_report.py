#!/usr/bin/python3
"""The figure rules of scripts/plot_report.py (docs/cli.md, "`contactrb report`"), checked on the
matplotlib figures themselves: every axis labelled, sizes with integer ticks, zeros on a log axis
counted in the panel instead of vanishing, a panel without data saying so, 300-dpi PNG and PDF.

Usage: test_plot_report.py SCRIPTS_DIR   (run by ctest as plot_report_rules)
"""
import csv
import json
import os
import sys
import tempfile

sys.path.insert(0, sys.argv[1])
import plot_report  # noqa: E402  (the script, imported as a module: main() does not run)
from matplotlib.ticker import MaxNLocator  # noqa: E402

captured = {}
real_save = plot_report.save


def capture(fig, directory, name):
    captured[name] = fig
    real_save(fig, directory, name)


plot_report.save = capture


def write_csv(directory, name, header, rows):
    with open(os.path.join(directory, name), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)


def texts(fig):
    return [t.get_text() for ax in fig.axes for t in ax.texts]


failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


with tempfile.TemporaryDirectory() as d:
    study = {"case": "synthetic", "tolerances": {"eps_du": 1e-2, "eps_eim_g": 1e-5, "eps_eim_k": 1e-4},
             "models": [{"key": "cpg", "R": 3}], "parameter": "delta"}
    # Dual cone errors: the CPG history reaches an exact 0 at R = 3 (every snapshot in the cone).
    write_csv(d, "dual_cone_error.csv", ["method", "R", "error"],
              [["cpg", 0, 1.0], ["cpg", 1, 0.1], ["cpg", 2, 0.01], ["cpg", 3, 0.0],
               ["nmf", 0, 1.0], ["nmf", 1, 0.5], ["nmf", 2, 0.2], ["nmf", 3, 0.1]])
    plot_report.plot_dual(d, study)
    fig = captured["dual_cone_error"]
    ax = fig.axes[0]
    check("1 zero value not drawn (log axis)" in texts(fig), "dual: the zero is not noted: %s" % texts(fig))
    check(ax.get_yscale() == "log", "dual: y axis is not logarithmic")
    check(ax.get_xlabel() != "" and ax.get_ylabel() != "", "dual: an axis has no label")
    loc = ax.xaxis.get_major_locator()
    check(isinstance(loc, MaxNLocator) and loc._integer, "dual: R has no integer ticks")

    # Errors: the one model's pairs did not converge, so the panels have no data and say so.
    write_csv(d, "errors_training.csv",
              ["model", "mu", "hf_converged", "rb_converged", "e_ener", "e_displ", "e_inter", "e_press"],
              [["cpg", 0.2, 1, 0, 1e-3, 1e-3, 0.0, 1e-2], ["cpg", 0.3, 1, 0, 1e-3, 1e-3, 0.0, 1e-2]])
    plot_report.plot_errors(d, study, "training")
    fig = captured["errors_training"]
    check(len(fig.axes) == 4, "errors: %d panels" % len(fig.axes))
    for a in fig.axes:
        check(a.get_ylabel() != "", "errors: a panel has no y label")
        check(any(t.get_text().startswith("no data") for t in a.texts), "errors: an empty panel is silent")
    check("(64)" in fig.axes[0].get_ylabel(), "errors: e_ener without its equation number")
    check("$" in fig.axes[0].get_xlabel(), "errors: the parameter axis is not in mathtext")

    # Both files of every figure: a 300-dpi PNG and a PDF.
    for name in ("dual_cone_error", "errors_training"):
        png = os.path.join(d, name + ".png")
        pdf = os.path.join(d, name + ".pdf")
        with open(png, "rb") as f:
            data = f.read()
        i = data.find(b"pHYs")
        check(i > 0 and int.from_bytes(data[i + 4:i + 8], "big") == 11811, "%s: not 300 dpi" % png)
        with open(pdf, "rb") as f:
            check(f.read(5) == b"%PDF-", "%s is not a PDF" % pdf)

    check(plot_report.count_zeros([0.0, 1e-3, 0.0, -0.0, 2.0]) == 3, "count_zeros")

if failures:
    for m in failures:
        print("FAIL: " + m)
    sys.exit(1)
print("plot_report rules: all checks passed")
