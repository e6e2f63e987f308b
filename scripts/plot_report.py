#!/usr/bin/python3
"""Figures of a `contactrb report` directory (docs/cli.md, "`contactrb report`").

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
  multipliers.png           HF and RB multipliers against the abscissa (Figs. 4, 6, 18)
  deformed_configuration.png  the HF deformed configurations Omega(mu) + u(mu) (Figs. 3, 5, 17),
                            when the report computed them
  constraint_comparison.png HF pressure of the LAC and collocation discretizations (Figs. 7, 8),
                            when the report computed them

Every figure is written twice: NAME.png at 300 dpi and NAME.pdf (vector). Sizes (N, R, M) get
integer ticks; log axes get decade ticks in mathtext; a value that a log axis cannot show (zero:
an exact projection, a converged EIM) is counted in the panel ("k zeros not drawn") instead of
vanishing silently, and a panel without data says so.

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
    import matplotlib.tri as mtri
    import numpy as np
    from matplotlib.ticker import LogFormatterMathtext, LogLocator, MaxNLocator
except ImportError as exc:  # pragma: no cover - depends on the installation
    fail("cannot import matplotlib/numpy (%s); install python3-matplotlib and python3-numpy" % exc, 2)

# Models of the study, in the order of the legends.
MODELS = [
    ("cpg", "CPG", "tab:blue", "o", "-"),
    ("nmf", "NMF", "tab:red", "s", "-"),
    ("nmf-truncated", "truncated NMF", "tab:orange", "^", "--"),
    ("angle", "angle-greedy", "tab:green", "d", ":"),
    ("rows", "row cone", "tab:purple", "v", "-."),
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
    """Values for a log axis: zeros (exact projections, converged EIM) are not drawn (NaN);
    note_zeros() says so in the panel."""
    v = np.array(values, dtype=float)
    v[v <= 0] = np.nan
    return v


def count_zeros(values):
    v = np.asarray(values, dtype=float)
    return int(np.sum(v <= 0))


def note_zeros(ax, zeros):
    """A log panel states how many values it could not draw (never a silent gap)."""
    if zeros > 0:
        ax.text(0.98, 0.02, "%d zero value%s not drawn (log axis)" % (zeros, "" if zeros == 1 else "s"),
                ha="right", va="bottom", fontsize=7, color="0.3", transform=ax.transAxes)


def note_empty(ax, what):
    ax.text(0.5, 0.5, "no data: %s" % what, ha="center", va="center", transform=ax.transAxes)


def log_axis(ax):
    """Decade ticks labelled 10^k in mathtext, minor ticks unlabelled."""
    ax.yaxis.set_major_locator(LogLocator(base=10.0, numticks=12))
    ax.yaxis.set_major_formatter(LogFormatterMathtext(base=10.0))
    ax.yaxis.set_minor_locator(LogLocator(base=10.0, subs=np.arange(2, 10) * 0.1, numticks=12))


def integer_axis(axis):
    axis.set_major_locator(MaxNLocator(integer=True))


def save(fig, directory, name):
    """NAME.png at 300 dpi and NAME.pdf."""
    fig.tight_layout()
    for ext, dpi in (("png", 300), ("pdf", None)):
        path = os.path.join(directory, "%s.%s" % (name, ext))
        fig.savefig(path, dpi=dpi)
        print("wrote %s" % path)
    plt.close(fig)


def plot_pod(directory, study):
    rows = read_csv(directory, "pod_singular_values.csv")
    fig, ax = plt.subplots(figsize=(5, 4))
    sigma = column(rows, "sigma", "pod_singular_values.csv")
    if len(rows):
        ax.semilogy(column(rows, "index", "pod_singular_values.csv"), positive(sigma), "o-", markersize=4)
        log_axis(ax)
    else:
        note_empty(ax, "no singular values")
    note_zeros(ax, count_zeros(sigma))
    integer_axis(ax.xaxis)
    ax.set_xlabel(r"$N$")
    ax.set_ylabel(r"singular value $\sigma_N$")
    ax.set_title("POD singular values (%s)" % study["case"])
    ax.grid(True, which="both", alpha=0.3)
    save(fig, directory, "pod_singular_values")


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
    zeros = 0
    for key, label, color, style in styles:
        if key in series:
            x, y = series[key]
            ax.semilogy(x, positive(y), style, color=color, label=label, markersize=4)
            zeros += count_zeros(y)
    if not series:
        note_empty(ax, "no dual cone history")
    ax.axhline(study["tolerances"]["eps_du"], color="gray", lw=0.8, ls="--", label=r"$\epsilon_{\mathrm{DU}}$")
    log_axis(ax)
    note_zeros(ax, zeros)
    integer_axis(ax.xaxis)
    ax.set_xlabel(r"$R$")
    ax.set_ylabel(r"$\max_{\mu \in \mathcal{P}^{\mathrm{tr}}} \|\lambda(\mu) - \Pi_{\widehat{W}_R^+}\lambda(\mu)\|_{L^2(\Gamma^c)}$")
    ax.set_title("Dual cone error (%s)" % study["case"])
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, directory, "dual_cone_error")


def plot_eim(directory, study):
    path = "eim_error.csv"
    series = by_key(read_csv(directory, path), "function", "M", "error", path)
    fig, axes = plt.subplots(1, 2, figsize=(9, 4))
    for ax, key, name, eps, eps_label in (
            (axes[0], "gamma", r"gap mapping $\gamma$", "eps_eim_g", r"$\epsilon_{\mathrm{EIM}}^{g}$"),
            (axes[1], "kappa", r"contact mapping $\kappa$", "eps_eim_k", r"$\epsilon_{\mathrm{EIM}}^{k}$")):
        if key in series:
            x, y = series[key]
            ax.semilogy(x, positive(y), "o-", markersize=4)
            note_zeros(ax, count_zeros(y))
        else:
            ax.set_yscale("log")
            note_empty(ax, "no EIM history for %s" % key)
        ax.axhline(study["tolerances"][eps], color="gray", lw=0.8, ls="--", label=eps_label)
        log_axis(ax)
        integer_axis(ax.xaxis)
        ax.set_xlabel(r"$M$")
        ax.set_ylabel(r"EIM $\ell^\infty$ error on the training set")
        ax.set_title("%s (%s)" % (name, study["case"]))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    save(fig, directory, "eim_error")


def plot_errors(directory, study, set_name):
    path = "errors_%s.csv" % set_name
    rows = read_csv(directory, path)
    sizes = {m["key"]: m for m in study["models"]}
    fig, axes = plt.subplots(1, 4, figsize=(18, 4))
    for ax, key, name in ((axes[0], "e_ener", r"$e_{\mathrm{ener}}(\mu)$, Eq. (64)"),
                          (axes[1], "e_displ", r"$e_{\mathrm{displ}}(\mu)$, Eq. (65)"),
                          (axes[2], "e_inter", r"$e_{\mathrm{inter}}(\mu)$, Eq. (66)"),
                          (axes[3], "e_press", r"$e_{\mathrm{press}}(\mu)$ (relative $L^2(\Gamma^c)$)")):
        zeros = 0
        for model, label, color, marker, style in MODELS:
            sel = [r for r in rows if r.get("model") == model and r.get("rb_converged") == "1"
                   and r.get("hf_converged") == "1"]
            if not sel:
                continue
            mu = column(sel, "mu", path)
            raw = column(sel, key, path)
            zeros += count_zeros(raw)
            size = sizes.get(model)
            if size is not None:
                label = r"%s ($R = %d$)" % (label, size["R"])
            ax.semilogy(mu, positive(raw), style, marker=marker, color=color, label=label, markersize=4)
        ax.set_yscale("log")
        log_axis(ax)
        note_zeros(ax, zeros)
        ax.set_xlabel(r"$\mu$ (%s)" % study["parameter"])
        ax.set_ylabel(name)
        ax.set_title("%s set" % set_name)
        ax.grid(True, which="both", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
        else:
            note_empty(ax, "no pair of converged HF and RB solves")
    save(fig, directory, "errors_%s" % set_name)


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
        ax.plot(x, column(sel, "lambda_hf", path), "-", color=c, label=r"HF, $\mu = %g$" % mu)
        ax.plot(x, column(sel, "lambda_rb", path), "o", color=c, markersize=3, mfc="none",
                label=r"RB (CPG), $\mu = %g$" % mu)
    ax.set_xlabel(r"abscissa $x$ (reference configuration)")
    ax.set_ylabel(r"contact pressure $\lambda$")
    ax.set_title("Multipliers, %s set (%s)" % (study.get("multiplier_profiles", {}).get("set", "?"),
                                               study["case"]))
    ax.grid(True, alpha=0.3)
    if mus:
        ax.legend(fontsize=7)
    else:
        note_empty(ax, "no profiles requested")
    save(fig, directory, "multipliers")


def plot_deformed(directory, study):
    """Figs. 3, 5, 17: the reference mesh and Omega(mu) + u(mu) for each computed mu."""
    npath, tpath = "deformed_nodes.csv", "deformed_triangles.csv"
    nodes = read_csv(directory, npath)
    tris = read_csv(directory, tpath)
    triangles = np.array([[int(r["n0"]), int(r["n1"]), int(r["n2"])] for r in tris], dtype=int)
    mus = sorted({float(r["mu"]) for r in nodes})
    fig, axes = plt.subplots(1, len(mus) + 1, figsize=(4.2 * (len(mus) + 1), 4.2), squeeze=False)
    axes = axes[0]
    colors = ["tab:blue", "tab:orange", "tab:green", "tab:red"]

    def draw(ax, x, y, title):
        body = np.array([int(r["body"]) for r in tris])
        for b in sorted(set(body.tolist())):
            sel = triangles[body == b]
            ax.triplot(mtri.Triangulation(x, y, sel), lw=0.3, color=colors[b % len(colors)])
        ax.set_aspect("equal")
        ax.set_xlabel(r"$x$")
        ax.set_ylabel(r"$y$")
        ax.set_title(title)

    for k, mu in enumerate(mus):
        sel = sorted((r for r in nodes if float(r["mu"]) == mu), key=lambda r: int(r["node"]))
        x = column(sel, "x", npath)
        y = column(sel, "y", npath)
        if k == 0:
            draw(axes[0], x, y, r"$\Omega(\mu)$, $\mu = %g$ (undeformed)" % mu)
        draw(axes[k + 1], x + column(sel, "ux", npath), y + column(sel, "uy", npath),
             r"$\Omega(\mu) + u_{\mathcal{N}}(\mu)$, $\mu = %g$" % mu)
    fig.suptitle("Deformed configurations, HF (%s)" % study["case"])
    save(fig, directory, "deformed_configuration")


def plot_constraint_comparison(directory, study):
    """Figs. 7, 8: HF pressure of the LAC and the collocation discretizations, one panel per mu."""
    path = "constraint_comparison.csv"
    rows = read_csv(directory, path)
    mus = sorted({float(r["mu"]) for r in rows})
    cols = 2 if len(mus) > 1 else 1
    nrows = (len(mus) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(5.5 * cols, 4 * nrows), squeeze=False)
    for k, mu in enumerate(mus):
        ax = axes[k // cols][k % cols]
        for name, label, color, style in (("lac", "LAC", "tab:blue", "o-"),
                                          ("collocation", "collocation (Col)", "tab:green", "s-")):
            sel = sorted((r for r in rows if float(r["mu"]) == mu and r["constraint"] == name),
                         key=lambda r: float(r["abscissa"]))
            if sel:
                ax.plot(column(sel, "abscissa", path), column(sel, "pressure", path), style, color=color,
                        markersize=3, lw=1, label=label)
        ax.set_xlabel(r"abscissa $x$ (reference configuration)")
        ax.set_ylabel(r"normal contact stress $\lambda$")
        ax.set_title(r"$\mu = %g$" % mu)
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
        else:
            note_empty(ax, "no profile")
    for k in range(len(mus), nrows * cols):
        axes[k // cols][k % cols].axis("off")
    fig.suptitle("HF contact pressure: LAC against collocation (%s)" % study["case"])
    save(fig, directory, "constraint_comparison")


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
    if "deformed_nodes.csv" in files:
        plot_deformed(directory, study)
    if "constraint_comparison.csv" in files:
        plot_constraint_comparison(directory, study)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
