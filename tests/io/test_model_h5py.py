"""Model and snapshot files read by an independent reader (h5py + numpy only), against the
C++ code (docs/file-formats.md):

1. Every group has a `description`, every dataset `shape_meaning` and `units`, and every string
   attribute decodes as str (variable-length UTF-8).
2. The reconstruction u = sum_k theta^lift_k(mu) lift_k + P Theta[:, :N] u_hat, computed here from
   the model file's datasets alone (u_hat from `online --json`), equals the displacement the C++
   reconstruction wrote to solution.vtu (raw appended Float64, parsed here) to 1e-12 relative;
   likewise lambda = Xi[:, :R] lambda_hat on the kept rows against multipliers.csv.
3. The mesh is in the files: with the case's .msh file moved away, `online --out` and `evaluate`
   still work, and the VTU holds the same displacement; /mesh/nodes are the VTU's points (the
   case's parameter scales a Dirichlet value: Omega(mu) is the reference mesh).

Usage: /usr/bin/python3 test_model_h5py.py CONTACTRB_CLI SOURCE_DIR WORK_DIR
Exit codes: 0 pass, 1 fail, 77 skipped (h5py or numpy missing).
"""
import json
import os
import re
import shutil
import struct
import subprocess
import sys

try:
    import h5py
    import numpy as np
except ImportError:
    sys.exit(77)

FAILURES = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        FAILURES.append(what)


def run(cli, args, cwd):
    p = subprocess.run([cli] + args, cwd=cwd, capture_output=True, text=True, timeout=600)
    if p.returncode != 0:
        print(p.stdout)
        print(p.stderr, file=sys.stderr)
        raise SystemExit(f"contactrb {' '.join(args)} exited with {p.returncode}")
    return p.stdout


def vtu_arrays(path):
    """The DataArrays of a VTU file written with raw appended data (UInt64 headers)."""
    data = open(path, "rb").read()
    start = data.index(b"<AppendedData")
    xml = data[:start].decode("utf-8")
    base = data.index(b"_", start) + 1
    arrays = {}
    for m in re.finditer(r"<DataArray ([^>]*)/>", xml):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        if attrs.get("type") != "Float64":
            continue
        offset = base + int(attrs["offset"])
        (nbytes,) = struct.unpack_from("<Q", data, offset)
        values = np.frombuffer(data, dtype="<f8", count=nbytes // 8, offset=offset + 8)
        arrays[attrs["Name"]] = values.reshape(-1, int(attrs.get("NumberOfComponents", "1")))
    return arrays


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


def check_descriptions(path):
    bad = []
    with h5py.File(path, "r") as f:
        for key, value in f.attrs.items():
            if isinstance(value, (bytes, np.bytes_)):
                bad.append(f"/ attribute {key} reads as bytes")

        def visit(name, obj):
            for key, value in obj.attrs.items():
                if isinstance(value, (bytes, np.bytes_)):
                    bad.append(f"{name} attribute {key} reads as bytes")
            if isinstance(obj, h5py.Dataset):
                for key in ("shape_meaning", "units"):
                    if not isinstance(obj.attrs.get(key), str):
                        bad.append(f"{name} has no str attribute {key}")
            elif not isinstance(obj.attrs.get("description"), str):
                bad.append(f"group {name} has no str description")

        f.visititems(visit)
        for key in ("format", "contactrb_version", "description"):
            if not isinstance(f.attrs.get(key), str):
                bad.append(f"root attribute {key} is not str")
    for b in bad[:10]:
        print("     " + b)
    return not bad


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

    check(check_descriptions(os.path.join(work, "m.h5")), "model file: descriptions, shape_meaning, units as str")
    check(check_descriptions(os.path.join(work, "s.h5")), "snapshot file: descriptions, shape_meaning, units as str")

    mu = np.array([0.0175])
    answer = json.loads(run(cli, ["online", "--model", "m.h5", "--mu", "0.0175", "--out", "o1"], work))
    u_hat = np.array(answer["u_hat"])
    lambda_hat = np.array(answer["lambda_hat"])
    with h5py.File(os.path.join(work, "m.h5"), "r") as f:
        check(f.attrs["format"] == "contactrb-reduced-model" and int(f.attrs["format_version"]) == 5,
              "model format attributes")
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
