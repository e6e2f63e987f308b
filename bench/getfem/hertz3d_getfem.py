#!/usr/bin/python3
"""hertz-3d on one mesh with GetFEM and with contactrb, side by side (docs/performance.md,
"HF scaling in 3D"). Not part of CI; needs Debian's python3-getfem (apt-get install
python3-getfem) and python3-meshio, run with /usr/bin/python3.

    /usr/bin/python3 bench/getfem/hertz3d_getfem.py --contactrb build/apps/contactrb/contactrb \
        --level 2 [--mu 0.02] [--work DIR]

The mesh is the one `contactrb mesh --case hertz-3d --level L` writes (mesh.msh, Gmsh 4.1), read
with meshio and split into the two bodies (two GetFEM meshes: the bodies touch at the origin, and
a single GetFEM mesh would merge the two coincident nodes there). Same problem as the case
(docs/cases.md, "Three-dimensional cases"): P1 tetrahedra, E = 15, nu = 0.3 in both bodies, `top`
u = (0, 0, -mu), `bottom` u = 0 (both eliminated), rollers u.n = 0 on `symmetry_x` and
`symmetry_y` (a penalty 1e9 on the face integral of (u.n)(v.n); 1e11 moves the force by 2e-8 on
level 1), frictionless contact of the slave nodes against the master faces: GetFEM's nodal
contact between non-matching meshes (small sliding, Alart-Curnier augmented Lagrangian, r = E)
solved by GetFEM's Newton with MUMPS.

GetFEM's multipliers are nodal forces; the pressure of a slave node is its force over its nodal
area (a third of the area of each slave triangle at the node), as contactrb's collocation
weights. OPENBLAS_NUM_THREADS is 1 on both sides unless set. The time of each side is the wall
time of the solve from the mesh in memory: GetFEM's model assembly and Newton; contactrb's setup
and solve (solution.json "time_s").
"""
import argparse
import json
import os
import subprocess
import sys
import time

# One BLAS thread on both sides unless the caller says otherwise (as bench/hf_scaling.sh): the
# comparison is per core, and it is set before NumPy and GetFEM load OpenBLAS.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

E = 15.0
NU = 0.3
PENALTY = 1e9
SLAVE, MASTER, TOP, BOTTOM, SYM_X, SYM_Y = 1, 2, 3, 4, 5, 6


def run(cmd):
    try:
        done = subprocess.run(cmd, capture_output=True, text=True)
    except OSError as e:
        sys.exit("hertz3d_getfem: cannot run %s: %s (--contactrb)" % (cmd[0], e))
    if done.returncode != 0:
        sys.exit("hertz3d_getfem: '%s' failed (%d):\n%s%s" % (" ".join(cmd), done.returncode, done.stdout, done.stderr))
    return done.stdout


def read_mesh(path):
    """Nodes, the tetrahedra of each body, the boundary triangles of each named group."""
    import meshio
    m = meshio.read(path)
    groups = {}
    for name, data in m.field_data.items():
        groups[(int(data[1]), int(data[0]))] = name
    tets = {}
    faces = {}
    for block, phys in zip(m.cells, m.cell_data["gmsh:physical"]):
        dim = 3 if block.type == "tetra" else 2 if block.type == "triangle" else None
        if dim is None:
            continue
        for tag in np.unique(phys):
            name = groups[(dim, int(tag))]
            cells = block.data[phys == tag]
            target = tets if dim == 3 else faces
            target[name] = np.vstack([target[name], cells]) if name in target else cells
    return m.points, tets, faces


class Body:
    """One body as its own GetFEM mesh: the nodes of its tetrahedra, renumbered, convex k being
    tetrahedron k with its vertices in order (checked)."""

    def __init__(self, gf, points, tets):
        self.nodes = np.unique(tets)
        self.local = -np.ones(len(points), dtype=int)
        self.local[self.nodes] = np.arange(len(self.nodes))
        cells = self.local[tets]
        self.mesh = gf.Mesh("ptND", points[self.nodes].T.copy(), cells.T.copy())
        pid, _ = self.mesh.pid_from_cvid(np.arange(len(cells)))
        if not np.allclose(self.mesh.pts().T, points[self.nodes]) or not np.array_equal(pid.reshape(-1, 4), cells):
            sys.exit("hertz3d_getfem: GetFEM renumbered the nodes or the tetrahedra of a body")
        self.outer = self.mesh.outer_faces()
        # Face f of a GetFEM simplex is the one opposite its vertex f.
        vertices = cells[self.outer[0]]
        keep = np.arange(4)[None, :] != self.outer[1][:, None]
        keys = np.sort(vertices[keep].reshape(-1, 3), axis=1)
        self.outer_keys = {tuple(k): j for j, k in enumerate(keys.tolist())}

    def set_region(self, number, triangles):
        """The group's triangles on this body as GetFEM region `number`; returns their count."""
        local = np.sort(self.local[triangles], axis=1)
        mine = local[(local >= 0).all(axis=1)]  # the others are on the other body
        cols = [self.outer_keys.get(tuple(k), -1) for k in mine.tolist()]
        if -1 in cols:
            sys.exit("hertz3d_getfem: a boundary triangle is not on the boundary of its body")
        if cols:
            self.mesh.set_region(number, self.outer[:, cols])
        return len(cols)


def nodal_areas(points, triangles):
    area = {}
    for a, b, c in triangles:
        s = 0.5 * np.linalg.norm(np.cross(points[b] - points[a], points[c] - points[a])) / 3.0
        for v in (a, b, c):
            area[int(v)] = area.get(int(v), 0.0) + s
    return area


def solve_getfem(gf, points, tets, faces, mu):
    """GetFEM's solve of hertz-3d on the mesh; returns time, iterations, force, max pressure."""
    t0 = time.perf_counter()
    slave, master = Body(gf, points, tets["body1"]), Body(gf, points, tets["body2"])
    groups = {"slave": SLAVE, "master": MASTER, "top": TOP, "bottom": BOTTOM, "symmetry_x": SYM_X, "symmetry_y": SYM_Y}
    for name, number in groups.items():
        if sum(body.set_region(number, faces[name]) for body in (slave, master)) != len(faces[name]):
            sys.exit("hertz3d_getfem: group '%s' is not on the bodies' boundaries" % name)
    t_mesh = time.perf_counter() - t0
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    shear = E / (2 * (1 + NU))
    t0 = time.perf_counter()
    md = gf.Model("real")
    md.add_initialized_data("lambda", [lam])
    md.add_initialized_data("mu", [shear])
    md.add_initialized_data("top_u", [0.0, 0.0, -mu])
    md.add_initialized_data("zero_u", [0.0, 0.0, 0.0])
    md.add_initialized_data("r", [E])
    bodies = {}
    for name, body in (("u1", slave), ("u2", master)):
        mf = gf.MeshFem(body.mesh, 3)
        mf.set_classical_fem(1)
        mim = gf.MeshIm(body.mesh, 2)
        md.add_fem_variable(name, mf)
        md.add_isotropic_linearized_elasticity_brick(mim, name, "lambda", "mu")
        for region in (SYM_X, SYM_Y):
            if region in body.mesh.regions():
                md.add_linear_term(mim, "%g*(%s.Normal)*(Test_%s.Normal)" % (PENALTY, name, name), region)
        bodies[name] = (mf, mim)
    md.add_Dirichlet_condition_with_simplification("u1", TOP, "top_u")
    md.add_Dirichlet_condition_with_simplification("u2", BOTTOM, "zero_u")
    mf1 = bodies["u1"][0]
    slave_dofs = mf1.basic_dof_on_region(SLAVE)
    md.add_nodal_contact_between_nonmatching_meshes_brick(bodies["u1"][1], bodies["u2"][1], "u1", "u2", "lambda_n",
                                                          "r", SLAVE, MASTER)
    out = md.solve("max_res", 1e-9, "max_iter", 50, "lsolver", "mumps")
    seconds = time.perf_counter() - t0
    iterations, converged = int(out[0]), bool(out[1])  # (nbit, converged)
    forces = np.abs(np.asarray(md.variable("lambda_n")))
    # The slave nodes in the multipliers' order: the x-component dofs on the region, in order.
    basic = mf1.basic_dof_nodes(slave_dofs[::3])
    area = nodal_areas(points, faces["slave"])
    coords = {tuple(np.round(points[v], 12)): a for v, a in area.items()}
    areas = np.array([coords[tuple(np.round(basic[:, k], 12))] for k in range(basic.shape[1])])
    pressure = forces / areas
    return {"time": seconds, "mesh_time": t_mesh, "iterations": iterations, "force": forces.sum(),
            "max_pressure": pressure.max(), "active": int((forces > 1e-10 * forces.max()).sum()), "converged": converged, "dofs": mf1.nbdof() + bodies["u2"][0].nbdof()}


def solve_contactrb(binary, level, mu, work):
    out = os.path.join(work, "contactrb")
    t0 = time.perf_counter()
    run([binary, "solve", "--case", "hertz-3d", "--level", str(level), "--mu", repr(mu), "--solver", "newton",
         "--out", out])
    wall = time.perf_counter() - t0
    with open(os.path.join(out, "solution.json")) as f:
        sol = json.load(f)
    pressure = np.genfromtxt(os.path.join(out, "multipliers.csv"), delimiter=",", names=True)["pressure"]
    return {"time": sol["time_s"], "process": wall, "iterations": sol["iterations"], "force": sol["contact_force"],
            "max_pressure": pressure.max(), "active": sol["active_constraints"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--contactrb", default="build/apps/contactrb/contactrb")
    ap.add_argument("--level", type=int, default=1)
    ap.add_argument("--mu", type=float, default=0.02)
    ap.add_argument("--work", default="out/hertz3d_getfem")
    args = ap.parse_args()
    try:
        import getfem as gf
    except ImportError:
        sys.exit("hertz3d_getfem: GetFEM is missing (apt-get install python3-getfem; run with /usr/bin/python3)")
    gf.util_trace_level(0)
    mesh_dir = os.path.join(args.work, "mesh")
    run([args.contactrb, "mesh", "--case", "hertz-3d", "--level", str(args.level), "--out", mesh_dir])
    points, tets, faces = read_mesh(os.path.join(mesh_dir, "mesh.msh"))
    c = solve_contactrb(args.contactrb, args.level, args.mu, args.work)
    g = solve_getfem(gf, points, tets, faces, args.mu)
    print("hertz-3d level %d, mu = %g: %d DOFs, %d slave nodes" % (args.level, args.mu, g["dofs"], len(nodal_areas(points, faces["slave"]))))
    print("%-22s %14s %14s %10s" % ("", "contactrb", "GetFEM", "ratio"))
    rows = [("solve time (s)", "time", "%14.3f"), ("Newton iterations", "iterations", "%14d"),
            ("contact force", "force", "%14.6g"), ("max pressure", "max_pressure", "%14.6g"), ("active nodes", "active", "%14d")]
    for label, key, fmt in rows:
        ratio = g[key] / c[key] if c[key] else float("nan")
        print(("%-22s " + fmt + " " + fmt + " %10.3f") % (label, c[key], g[key], ratio))
    if not g["converged"]:
        print("GetFEM's Newton did not converge in 50 iterations (max_res 1e-9)")
    print("contactrb process wall (mesh + setup + solve + files): %.3f s; GetFEM mesh split: %.3f s" % (c["process"], g["mesh_time"]))


if __name__ == "__main__":
    main()
