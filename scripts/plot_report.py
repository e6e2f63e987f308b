#!/usr/bin/python3
"""Figures of a `contactrb report` directory (docs/user-guide.md, "report").

Usage: /usr/bin/python3 scripts/plot_report.py DIR

Reads the CSV files that `contactrb report` wrote into DIR (study.json lists them) and writes
the PNG figures next to them, the counterparts of the paper's figures:

  pod_singular_values.png   POD singular values against N (Figs. 11 left, 19 left)
  dual_cone_error.png       dual cone error against R: CPG, angle-greedy (true cone error and
                            the linear error that steers it), NMF (Figs. 9, 11 right, 19 right)
  eim_error.png             EIM l-infinity error against M for gamma and kappa (Figs. 12, 20)
  errors_training.png       e_ener, e_displ, e_inter against mu, training set (Figs. 10, 13-16, 21),
                            and e_press (relative L2(Gamma^c) contact-pressure error, ours)
  errors_verification.png   the same on the verification set (Fig. 22), when there is one
  multipliers.png           HF and RB multipliers against the abscissa (Figs. 8, 18)

Exit status: 0 on success, 1 with one line "plot_report: error: ..." on stderr for a missing
or malformed input, 2 when matplotlib or numpy cannot be imported.
"""
import csv
import json
import os
import sys


def fail(message, code=1):
    sys.stderr.write("plot_report: error: %s\n" % message)
    sys.exit(code)


try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as exc:  # pragma: no cover - depends on the installation
    fail("cannot import matplotlib/numpy (%s); install python3-matplotlib and python3-numpy" % exc, 2)

# Models of the study, in the order of the legends.
MODELS = [
    ("cpg", "CPG", "tab:blue", "o", "-"),
    ("nmf", "NMF", "tab:red", "s", "-"),
    ("nmf-truncated", "truncated NMF", "tab:orange", "^", "--"),
    ("angle", "angle-greedy", "tab:green", "d", ":"),
]


def read_csv(directory, name):
    """Rows of DIR/name as dicts; fails clearly when the file is missing or has no header."""
    path = os.path.join(directory, name)
    if not os.path.isfile(path):
        fail("missing input file %s" % path)
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames is None:
            fail("input file %s is empty (no header row)" % path)
        return list(reader)


def column(rows, key, path):
    try:
        return np.array([float(r[key]) for r in rows])
    except (KeyError, ValueError) as exc:
        fail("input file %s: bad or missing column %s (%s)" % (path, key, exc))


def positive(values):
    """Values for a log axis: zeros (exact projections, converged EIM) are not drawn."""
    v = np.array(values, dtype=float)
    v[v <= 0] = np.nan
    return v


def save(fig, directory, name):
    path = os.path.join(directory, name)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print("wrote %s" % path)


def plot_pod(directory, study):
    rows = read_csv(directory, "pod_singular_values.csv")
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.semilogy(column(rows, "index", "pod_singular_values.csv"),
                positive(column(rows, "sigma", "pod_singular_values.csv")), "o-")
    ax.set_xlabel("N")
    ax.set_ylabel("singular value")
    ax.set_title("POD singular values (%s)" % study["case"])
    ax.grid(True, which="both", alpha=0.3)
    save(fig, directory, "pod_singular_values.png")


def by_key(rows, key_column, x_column, y_column, path):
    out = {}
    for r in rows:
        try:
            out.setdefault(r[key_column], ([], []))
            out[r[key_column]][0].append(float(r[x_column]))
            out[r[key_column]][1].append(float(r[y_column]))
        except (KeyError, ValueError) as exc:
            fail("input file %s: bad row %s (%s)" % (path, r, exc))
    return out


def plot_dual(directory, study):
    path = "dual_cone_error.csv"
    series = by_key(read_csv(directory, path), "method", "R", "error", path)
    styles = [
        ("cpg", "CPG", "tab:blue", "o-"),
        ("angle_cone", "angle-greedy (cone projection)", "tab:green", "d-"),
        ("angle_linear", "angle-greedy (linear projection)", "tab:green", "d:"),
        ("nmf", "NMF", "tab:red", "s-"),
    ]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for key, label, color, style in styles:
        if key in series:
            x, y = series[key]
            ax.semilogy(x, positive(y), style, color=color, label=label, markersize=4)
    ax.axhline(study["tolerances"]["eps_du"], color="gray", lw=0.8, ls="--", label="eps_DU")
    ax.set_xlabel("R")
    ax.set_ylabel("max over training set of |lambda - Pi(lambda)|_L2")
    ax.set_title("Dual cone error (%s)" % study["case"])
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, directory, "dual_cone_error.png")


def plot_eim(directory, study):
    path = "eim_error.csv"
    series = by_key(read_csv(directory, path), "function", "M", "error", path)
    fig, axes = plt.subplots(1, 2, figsize=(9, 4))
    for ax, key, name, eps in ((axes[0], "gamma", "gap mapping gamma", "eps_eim_g"),
                               (axes[1], "kappa", "contact mapping kappa", "eps_eim_k")):
        if key in series:
            x, y = series[key]
            ax.semilogy(x, positive(y), "o-", markersize=4)
        ax.axhline(study["tolerances"][eps], color="gray", lw=0.8, ls="--", label=eps)
        ax.set_xlabel("M")
        ax.set_ylabel("EIM l-infinity error")
        ax.set_title("%s (%s)" % (name, study["case"]))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    save(fig, directory, "eim_error.png")


def plot_errors(directory, study, set_name):
    path = "errors_%s.csv" % set_name
    rows = read_csv(directory, path)
    sizes = {m["key"]: m for m in study["models"]}
    fig, axes = plt.subplots(1, 4, figsize=(18, 4))
    for ax, key, name in ((axes[0], "e_ener", "e_ener (64)"), (axes[1], "e_displ", "e_displ (65)"),
                          (axes[2], "e_inter", "e_inter (66)"), (axes[3], "e_press", "e_press (pressure)")):
        for model, label, color, marker, style in MODELS:
            sel = [r for r in rows if r.get("model") == model and r.get("rb_converged") == "1"
                   and r.get("hf_converged") == "1"]
            if not sel:
                continue
            mu = column(sel, "mu", path)
            y = positive(column(sel, key, path))
            size = sizes.get(model)
            if size is not None:
                label = "%s (R = %d)" % (label, size["R"])
            ax.semilogy(mu, y, style, marker=marker, color=color, label=label, markersize=4)
        ax.set_xlabel("mu (%s)" % study["parameter"])
        ax.set_title("%s, %s set" % (name, set_name))
        ax.grid(True, which="both", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    save(fig, directory, "errors_%s.png" % set_name)


def plot_multipliers(directory, study):
    path = "multipliers.csv"
    rows = read_csv(directory, path)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    mus = sorted({float(r["mu"]) for r in rows}) if rows and "mu" in rows[0] else []
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, mu in enumerate(mus):
        sel = sorted((r for r in rows if float(r["mu"]) == mu), key=lambda r: float(r["abscissa"]))
        x = column(sel, "abscissa", path)
        c = colors[i % len(colors)]
        ax.plot(x, column(sel, "lambda_hf", path), "-", color=c, label="HF, mu = %g" % mu)
        ax.plot(x, column(sel, "lambda_rb", path), "o", color=c, markersize=3, mfc="none",
                label="RB (CPG), mu = %g" % mu)
    ax.set_xlabel("abscissa (reference configuration)")
    ax.set_ylabel("contact pressure lambda")
    ax.set_title("Multipliers, %s set (%s)" % (study.get("multiplier_profiles", {}).get("set", "?"),
                                               study["case"]))
    ax.grid(True, alpha=0.3)
    if mus:
        ax.legend(fontsize=7)
    else:
        ax.text(0.5, 0.5, "no profiles requested", ha="center", va="center", transform=ax.transAxes)
    save(fig, directory, "multipliers.png")


def main(argv):
    if len(argv) != 2:
        fail("usage: plot_report.py DIR (a directory written by `contactrb report`)")
    directory = argv[1]
    if not os.path.isdir(directory):
        fail("%s is not a directory" % directory)
    study_path = os.path.join(directory, "study.json")
    if not os.path.isfile(study_path):
        fail("missing input file %s" % study_path)
    try:
        with open(study_path) as f:
            study = json.load(f)
        files = study["files"]
        study["case"], study["tolerances"], study["models"], study["parameter"]
    except (ValueError, KeyError) as exc:
        fail("input file %s is not a contactrb study (%s)" % (study_path, exc))
    for name in files:
        if not os.path.isfile(os.path.join(directory, name)):
            fail("missing input file %s" % os.path.join(directory, name))
    plot_pod(directory, study)
    plot_dual(directory, study)
    plot_eim(directory, study)
    plot_errors(directory, study, "training")
    if "errors_verification.csv" in files:
        plot_errors(directory, study, "verification")
    plot_multipliers(directory, study)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
