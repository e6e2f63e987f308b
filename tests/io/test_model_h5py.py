"""Model and snapshot files read by an independent reader (h5py + numpy only), against the
C++ code (docs/file-formats.md):

1. Every group has a `description`, every dataset `shape_meaning` and `units`; every string
   attribute is a fixed-length UTF-8 string (h5py: numpy.bytes_, `.decode("utf-8")` is the text)
   and nothing in the files is variable-length; the strings hold what the CLI wrote (the case
   name and kind, the version, a converged status, the model's copy of the snapshot strings).
2. The reconstruction u = sum_k theta^lift_k(mu) lift_k + P Theta[:, :N] u_hat, computed here from
   the model file's datasets alone (u_hat from `online --json`), equals the displacement the C++
   reconstruction wrote to solution.vtu (raw appended Float64, parsed here) to 1e-12 relative;
   likewise lambda = Xi[:, :R] lambda_hat on the kept rows against multipliers.csv.
3. Each snapshot's K (compressed rows: K_indptr, K_indices, K_data) is R x n_c with ascending
   columns in every row, and K maps a rigid translation of the contact nodes to 0 at every row
   (k(w; t)_s = ((1 - xi) t + xi t - t) . n2 = 0, DESIGN's (27)), to round-off.
4. The mesh is in the files: with the case's .msh file moved away, `online --out` and `evaluate`
   still work, and the VTU holds the same displacement; /mesh/nodes are the VTU's points (the
   case's parameter scales a Dirichlet value: Omega(mu) is the reference mesh).

Usage: /usr/bin/python3 test_model_h5py.py CONTACTRB_CLI SOURCE_DIR WORK_DIR
Exit codes: 0 pass, 1 fail, 77 skipped (h5py or numpy missing).
"""
import json
import os
import shutil
import sys

try:
    import h5py
    import numpy as np
except ImportError:
    sys.exit(77)

from h5py_check_support import FAILURES, check, run, vtu_arrays  # noqa: E402 (after the skip)



def theta(group, mu):
    """theta_j(mu) = coefficient_j * prod over its factors (mu_k / s)^p (/theta/*)."""
    monomials = group["monomials"][()]
    factors = group["factors"][()]
    out = np.empty(monomials.shape[0])
    row = 0
    for j, (coefficient, count) in enumerate(monomials):
        value = coefficient
        for _ in range(int(count)):
            k, s, p = factors[row]
            value *= (mu[int(k)] / s) ** int(p)
            row += 1
        out[j] = value
    return out


def string_text(obj, key, bad, where):
    """The text of string attribute `key` of `obj`: fixed-length UTF-8, read as numpy.bytes_."""
    info = h5py.check_string_dtype(obj.attrs.get_id(key).dtype)
    if info is None:
        return None
    if info.length is None:
        bad.append(f"{where} attribute {key} is a variable-length string")
    if info.encoding != "utf-8":
        bad.append(f"{where} attribute {key} is not UTF-8 ({info.encoding})")
    value = obj.attrs[key]
    if not isinstance(value, np.bytes_):
        bad.append(f"{where} attribute {key} reads as {type(value).__name__}, not numpy.bytes_")
        return None
    try:
        return value.decode("utf-8")
    except UnicodeDecodeError:
        bad.append(f"{where} attribute {key} is not valid UTF-8")
        return None


def check_descriptions(path):
    bad = []
    with h5py.File(path, "r") as f:
        for key in f.attrs:
            string_text(f, key, bad, "/")

        def visit(name, obj):
            text = {key: string_text(obj, key, bad, name) for key in obj.attrs}
            if isinstance(obj, h5py.Dataset):
                if h5py.check_vlen_dtype(obj.dtype) is not None or obj.dtype.kind in ("O", "S", "U"):
                    bad.append(f"dataset {name} holds strings or variable-length data ({obj.dtype})")
                for key in ("shape_meaning", "units"):
                    if not text.get(key):
                        bad.append(f"{name} has no {key} text")
            elif not text.get("description"):
                bad.append(f"group {name} has no description text")

        f.visititems(visit)
        for key in ("format", "contactrb_version", "description"):
            if not string_text(f, key, bad, "/"):
                bad.append(f"root attribute {key} has no text")
    for b in bad[:10]:
        print("     " + b)
    return not bad


def text(obj, key):
    return obj.attrs[key].decode("utf-8")


def check_strings(cli, work):
    """The string attributes read by h5py alone hold what the CLI wrote."""
    version = run(cli, ["--version"], work).split()[-1]
    with h5py.File(os.path.join(work, "s.h5"), "r") as s, h5py.File(os.path.join(work, "m.h5"), "r") as m:
        check(text(s, "format") == "contactrb-snapshots" and int(s.attrs["format_version"]) == 8
              and int(s.attrs["dimension"]) == 2, "snapshot format attributes (bytes decoded), dimension 2")
        check(text(s["settings"], "solver") == "kacanov", "snapshot /settings solver (the default on 2D level 0)")
        check(text(m, "format") == "contactrb-reduced-model" and int(m.attrs["format_version"]) == 10,
              "model format attributes (bytes decoded)")
        check(text(s, "contactrb_version") == version and text(m, "contactrb_version") == version,
              f"contactrb_version is `contactrb --version` ({version})")
        check(text(s["case"], "name") == "two-block-patch" and text(s["case"], "kind") == "toml",
              "snapshot /case name and kind")
        spec = text(s["case"], "spec")
        check('name = "two-block-patch"' in spec and "[mesh]" in spec, "snapshot /case spec is the TOML text")
        check(text(m["meta"], "case_name") == "two-block-patch" and text(m["meta"], "case_spec") == spec,
              "model /meta case_name and case_spec are the snapshot file's")
        check(s["snapshots/000000"].attrs["status"] == b"converged", "a converged snapshot's status")
        check(text(s["parameter/000000"], "name") == text(m["parameters/000000"], "name") != "",
              "the parameter's name, in both files")


def check_contact_rows(work):
    """K in compressed rows: its shape, column order and K t = 0 for a rigid translation t."""
    with h5py.File(os.path.join(work, "s.h5"), "r") as f:
        n_c = f["discretization/contact_dofs"].shape[0]
        for key in f["snapshots"]:
            s = f["snapshots"][key]
            if not isinstance(s, h5py.Group) or "K_indptr" not in s:
                continue
            indptr, indices, data = s["K_indptr"][()], s["K_indices"][()], s["K_data"][()]
            R = s["lambda"].shape[0]
            rows = np.repeat(np.arange(R), np.diff(indptr))
            check(indptr.size == R + 1 and indptr[0] == 0 and indptr[-1] == indices.size == data.size
                  and indices.min() >= 0 and indices.max() < n_c
                  and np.all((np.diff(indices) > 0) | (np.diff(rows) > 0)),
                  f"snapshot {key}: K is R x n_c in compressed rows, columns ascending")
            scale = np.abs(data).max()
            for c in range(2):  # a unit translation along x, then along y (contact DOF 2 i + c)
                t = (indices % 2 == c).astype(float)
                Kt = np.zeros(R)
                np.add.at(Kt, rows, data * t)
                check(np.abs(Kt).max() <= 1e-12 * scale,
                      f"snapshot {key}: K maps a translation along axis {c} to 0 ({np.abs(Kt).max():.2e})")


def main():
    cli, source, work = sys.argv[1], sys.argv[2], sys.argv[3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    # A user case with its own .msh file, copied so that the .msh can be moved away.
    case_dir = os.path.join(work, "case")
    os.makedirs(case_dir)
    for name in ("case.toml", "two-block-patch.msh"):
        shutil.copy(os.path.join(source, "examples", "two-block-patch", name), case_dir)
    msh = os.path.join(case_dir, "two-block-patch.msh")
    run(cli, ["snapshots", "--case-file", os.path.join(case_dir, "case.toml"), "--set", "training", "-q",
              "--out", "s.h5"], work)
    run(cli, ["offline", "--snapshots", "s.h5", "--out", "m.h5"], work)

    check(check_descriptions(os.path.join(work, "m.h5")), "model file: fixed-length UTF-8 strings, descriptions, shape_meaning, units")
    check(check_descriptions(os.path.join(work, "s.h5")), "snapshot file: fixed-length UTF-8 strings, descriptions, shape_meaning, units")
    check_strings(cli, work)
    check_contact_rows(work)

    mu = np.array([0.0175])
    answer = json.loads(run(cli, ["online", "--model", "m.h5", "--mu", "0.0175", "--out", "o1"], work))
    u_hat = np.array(answer["u_hat"])
    lambda_hat = np.array(answer["lambda_hat"])
    with h5py.File(os.path.join(work, "m.h5"), "r") as f:
        rec = f["reconstruction"]
        Theta = rec["Theta"][()]
        free = rec["free_dofs"][()]
        lift = rec["lift"][()]
        n_dofs = int(rec.attrs["num_dofs"])
        check(Theta.shape == (free.size, int(f["meta"].attrs["N_max"])), "Theta is n_free x N_max")
        check(lift.shape[1] == n_dofs, "lift is J^D x num_dofs")
        u = theta(f["theta"]["lift"], mu) @ lift
        u[free] += Theta[:, : u_hat.size] @ u_hat
        Xi = rec["Xi"][()]
        lam = np.zeros(int(rec.attrs["num_constraints"]))
        lam[rec["kept_rows"][()]] = Xi[:, : lambda_hat.size] @ lambda_hat
        nodes = f["mesh"]["nodes"][()]
        check(nodes.shape == (n_dofs // 2, 2), "/mesh/nodes is num_nodes x 2")
        check(f["mesh"]["triangles"].shape[1] == 3, "/mesh/triangles is num_triangles x 3")
    vtu = vtu_arrays(os.path.join(work, "o1", "solution.vtu"))
    u_cpp = vtu["displacement"][:, :2].reshape(-1)
    rel = np.linalg.norm(u - u_cpp) / np.linalg.norm(u_cpp)
    check(np.array_equal(vtu["Points"][:, :2], nodes), "/mesh/nodes are the VTU's points")
    check(u_cpp.size == u.size and rel <= 1e-12, f"u from h5py = C++ reconstruction (relative difference {rel:.2e})")
    csv = np.loadtxt(os.path.join(work, "o1", "multipliers.csv"), delimiter=",", skiprows=1)
    lam_cpp = csv[:, 3]
    rel_l = np.linalg.norm(lam - lam_cpp) / max(np.linalg.norm(lam_cpp), 1e-300)
    check(lam_cpp.size == lam.size and rel_l <= 1e-12,
          f"lambda from h5py = C++ reconstruction (relative difference {rel_l:.2e})")
    check(np.linalg.norm(u) > 0 and np.linalg.norm(lam) > 0, "the compared fields are not zero")

    # The .msh file moved away: everything still reads the mesh from the files.
    os.rename(msh, msh + ".moved")
    run(cli, ["online", "--model", "m.h5", "--mu", "0.0175", "--out", "o2"], work)
    u_moved = vtu_arrays(os.path.join(work, "o2", "solution.vtu"))["displacement"]
    check(np.array_equal(u_moved, vtu["displacement"]), "online --out without the .msh file: same displacement")
    run(cli, ["evaluate", "--model", "m.h5", "--set", "verification", "--repeats", "1", "-q", "--out", "e"], work)
    check(os.path.exists(os.path.join(work, "e", "evaluation.csv")), "evaluate without the .msh file")
    run(cli, ["offline", "--snapshots", "s.h5", "--out", "m2.h5"], work)
    with h5py.File(os.path.join(work, "m.h5"), "r") as a, h5py.File(os.path.join(work, "m2.h5"), "r") as b:
        same = all(np.array_equal(a["reconstruction"][k][()], b["reconstruction"][k][()]) for k in ("Theta", "lift"))
    check(same, "offline --snapshots without the .msh file: the same basis")

    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
