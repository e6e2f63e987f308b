"""3D snapshot files read by an independent reader (h5py + numpy only), against the analytic
patch answer and the direct solves of `contactrb solve` (docs/file-formats.md, "Snapshot file"):

1. The file says its dimension (root attribute `dimension` = 3, format 8) and its HF method
   (/settings `solver` = newton, the 3D default); /mesh holds the
   tetrahedra (num_nodes x 3 nodes, num_tetrahedra x 4 cells, boundary triangles x 3);
   num_dofs = 3 x nodes, contact_dofs the three components of every contact node, ascending,
   u has 3 components per node; each K is R x n_c in compressed rows (K_indptr R + 1 entries from
   0 to nnz, every column in [0, n_c) and ascending within its row).
2. patch-3d (LAC, non-matching meshes): at every mu the stored pressure is the analytic patch
   answer p = E mu (E = 10) at every row to round-off, and the rows' weights add up to the unit
   interface.
3. patch-3d and hertz-3d (level 0, collocation): the stored displacement equals the one a
   direct `contactrb solve --solver newton` at the same mu writes to solution.vtu (same solver,
   same settings, both from a cold start: to round-off), the stored pressures equal its multipliers.csv, /mesh/nodes its VTU points.

Usage: /usr/bin/python3 test_snapshots_3d_h5py.py CONTACTRB_CLI WORK_DIR
Exit codes: 0 pass, 1 fail, 77 skipped (h5py or numpy missing).
"""
import csv
import os
import shutil
import sys

try:
    import h5py
    import numpy as np
except ImportError:
    sys.exit(77)

from h5py_check_support import FAILURES, check, run, vtu_arrays  # noqa: E402 (after the skip)

# patch-3d's Young's modulus (docs/cases.md, "patch-3d": p = E mu).
PATCH_E = 10.0
ROUND_OFF = 1e-12


def relative(a, b):
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def check_contact_rows(s, contact_dofs, name, key):
    """K in compressed rows (scipy's csr layout), R x n_c."""
    indptr, indices, data = s["K_indptr"][()], s["K_indices"][()], s["K_data"][()]
    R, n_c = s["lambda"].shape[0], contact_dofs.size
    check(indptr.size == R + 1 and indptr[0] == 0 and np.all(np.diff(indptr) >= 0)
          and indptr[-1] == indices.size == data.size, f"{name}: snapshot {key} K_indptr has R + 1 row pointers")
    rows = np.repeat(np.arange(R), np.diff(indptr))
    ascending = np.all((np.diff(indices) > 0) | (np.diff(rows) > 0))
    check(indices.size == 0 or (indices.min() >= 0 and indices.max() < n_c and ascending),
          f"{name}: snapshot {key} K_indices are contact columns, ascending within a row")
    check(np.all(np.isfinite(data)), f"{name}: snapshot {key} K_data is finite")


def check_layout(f, name):
    check(int(f.attrs["dimension"]) == 3, f"{name}: root attribute dimension is 3")
    check(int(f.attrs["format_version"]) == 8, f"{name}: format_version is 8")
    check(f["settings"].attrs["solver"] == b"newton", f"{name}: /settings solver is newton (the 3D default)")
    nodes = f["mesh/nodes"][()]
    tets = f["mesh/tetrahedra"][()]
    n = nodes.shape[0]
    check(nodes.shape[1] == 3 and tets.shape[1] == 4, f"{name}: /mesh nodes x 3, tetrahedra x 4")
    check(tets.min() >= 0 and tets.max() < n, f"{name}: tetrahedra index the nodes")
    groups = f["mesh/boundaries"]
    names = {groups[k].attrs["name"].decode("utf-8") for k in groups if isinstance(groups[k], h5py.Group)}
    check({"slave", "master"} <= names, f"{name}: /mesh/boundaries holds slave and master ({sorted(names)})")
    check(all(groups[k]["faces"].shape[1] == 3 for k in groups if isinstance(groups[k], h5py.Group)),
          f"{name}: boundary groups are triangles (faces x 3)")
    d = f["discretization"]
    check(int(d.attrs["num_dofs"]) == 3 * n, f"{name}: num_dofs = 3 x nodes")
    contact = np.unique(np.concatenate([d["slave"][()], d["master"][()]]))
    expected = (3 * contact[:, None] + np.arange(3)[None, :]).ravel()
    check(np.array_equal(d["contact_dofs"][()], expected), f"{name}: contact_dofs are 3 components per contact node")
    for key in f["snapshots"]:
        s = f["snapshots"][key]
        if not isinstance(s, h5py.Group):
            continue
        check(s["u"].shape == (3 * n,), f"{name}: snapshot {key} u has 3 components per node")
        check_contact_rows(s, expected, name, key)
        check(s["gap_pointwise"].shape == (d["slave"].shape[0],), f"{name}: snapshot {key} one gap per slave node")
    return nodes


def compare_with_solve(cli, work, f, index, case, mu, extra, nodes):
    """Snapshot `index` against `contactrb solve` at the same mu."""
    out = os.path.join(work, f"solve-{case}-{mu}")
    run(cli, ["solve", "--case", case, "--mu", mu, "--solver", "newton", "--out", out] + extra, work)
    arrays = vtu_arrays(os.path.join(out, "solution.vtu"))
    s = f["snapshots"][f"{index:06d}"]
    u = s["u"][()].reshape(-1, 3)
    check(relative(u, arrays["displacement"]) < ROUND_OFF,
          f"{case} mu {mu}: stored u equals the direct solve's ({relative(u, arrays['displacement']):.2e})")
    check(np.array_equal(nodes, arrays["Points"]), f"{case}: /mesh/nodes are the solve's VTU points")
    with open(os.path.join(out, "multipliers.csv"), newline="") as fh:
        rows = list(csv.DictReader(fh))
    pressure = np.array([float(r["pressure"]) for r in rows])
    weight = np.array([float(r["weight"]) for r in rows])
    check(relative(s["lambda"][()], pressure) < ROUND_OFF, f"{case} mu {mu}: stored lambda equals multipliers.csv")
    check(relative(s["weight"][()], weight) < ROUND_OFF, f"{case} mu {mu}: stored weights equal multipliers.csv")


def main():
    cli, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)

    patch = os.path.join(work, "patch-3d.h5")
    run(cli, ["snapshots", "--case", "patch-3d", "--values", "0.01,0.02", "--jobs", "2",
              "--warm-start", "off", "-q", "--out", patch], work)
    with h5py.File(patch, "r") as f:
        nodes = check_layout(f, "patch-3d")
        mus = f["parameter/values"][()][:, 0]
        for i, mu in enumerate(mus):
            s = f["snapshots"][f"{i:06d}"]
            lam = s["lambda"][()]
            exact = PATCH_E * mu
            err = float(np.max(np.abs(lam - exact)) / exact)
            check(err < 1e-10, f"patch-3d mu {mu}: pressure = E mu = {exact} at all {lam.size} rows ({err:.2e})")
            check(abs(s["weight"][()].sum() - 1.0) < ROUND_OFF, f"patch-3d mu {mu}: weights add up to the unit square")
        compare_with_solve(cli, work, f, 1, "patch-3d", "0.02", [], nodes)

    hertz = os.path.join(work, "hertz-3d.h5")
    run(cli, ["snapshots", "--case", "hertz-3d", "--level", "0", "--values", "0.02", "-q", "--out", hertz], work)
    with h5py.File(hertz, "r") as f:
        nodes = check_layout(f, "hertz-3d")
        check(f["case"].attrs["constraint"].decode("utf-8") == "collocation", "hertz-3d: collocation")
        compare_with_solve(cli, work, f, 0, "hertz-3d", "0.02", ["--level", "0"], nodes)

    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
