#!/usr/bin/python3
"""Best approximation of HF contact pressures (and displacements) by reduced spaces that follow a
moving contact zone, on snapshot files of `contactrb snapshots` (2D, format 5 or 6, docs/file-formats.md).

For every verification point mu and every candidate space, the relative error of the best
approximation of the HF pressure lambda(mu) in the weighted L2(Gamma_c) norm
||v||^2 = sum_r |I_r| v_r^2 (|I_r|: the rows' `weight` at mu):

  C0  global cone: non-negative combinations of all training pressures (NNLS);
  C1  local cones: the k training pressures nearest to mu (parameters scaled to [0, 1]^p), and the
      cones of k-means clusters (of the scaled parameters, or of the active sets), with and without
      overlap (a training point also joins the cluster of its second-nearest centroid);
  C2  registered cones: each snapshot's pressure profile along the slave boundary (arc-length
      coordinate s of the reference slave chain) is mapped affinely so that its support
      [a_j, b_j] becomes [0, 1]; the query's support is predicted from the training supports
      (p = 1: linear interpolation; p > 1: thin-plate RBF with a linear term, or linear
      regression on the 8 nearest) or taken from the query itself (oracle, the floor of any
      predictor); support ends estimated discretely (midpoint to the first inactive row) or by a
      square-root fit p^2 ~ c (a - s) through the last two active rows, or from the deformed gap
      g - K u at the first two inactive rows (g ~ c (s - a)^(3/2)); with the gap rule the
      "oracle" support is what a reduced model can compute online from its own displacement;
      registered POD modes (R = 1..6, least squares) and greedy registered cones of R generators;
  C3  local + registered: the k nearest training pressures, registered (alone, and together with
      the same k unregistered);
  C4  HF rows: every constraint row of a support is a generator (the union of the training
      supports, or of the k nearest supports widened by one row), the limit of a registration
      that respects the nodes;
  C5  the k nearest registered pressures plus the HF rows around the predicted support ends;
  and for the displacement the relative Euclidean error over the free DOFs of the projection of
  u_0(mu) onto global POD modes and onto local POD modes (the 2N nearest training points).

Usage: best_approximation.py --pair NAME TRAIN.h5 VERIF.h5 [--pair ...] [--csv OUT.csv]
The files of one pair are the same case at the same level, e.g.
  contactrb snapshots --case hertz-a --set training --tol 1e-8 --max-iterations 5000 --out train.h5
  contactrb snapshots --case hertz-a --set verification --tol 1e-8 --max-iterations 5000 --out verif.h5
(a Kacanov tolerance of 1e-8 keeps the snapshots' own solver error, about 5e-4 in the pressure at
the default 1e-3, below the errors measured). Prints a markdown table per candidate and a summary
(best per family, with the predicted and with the oracle support).
(Debian python3-h5py, python3-numpy, python3-scipy.)
"""
import argparse
import csv
import sys
import warnings

import h5py
import numpy as np
from scipy.cluster.vq import kmeans2
from scipy.interpolate import RBFInterpolator
from scipy.optimize import nnls

ACTIVE = 1e-8          # a row is active when lambda_r > ACTIVE * max lambda (solver round-off)
GRID = np.linspace(0.0, 1.0, 1001)   # reference coordinate of the registered profiles
R_MODES = range(1, 7)


# ---------------------------------------------------------------------------------------------
# Reading a snapshot file
# ---------------------------------------------------------------------------------------------
class Snapshots:
    """The converged snapshots of one file, rows sorted along the slave boundary."""


def slave_arc_length(nodes, slave):
    """Arc length of each slave node along the reference slave chain."""
    steps = np.linalg.norm(np.diff(nodes[slave], axis=0), axis=1)
    return dict(zip(slave.tolist(), np.concatenate([[0.0], np.cumsum(steps)])))


def row_positions(K, contact_dofs, arc):
    """Position of each constraint row on the slave boundary: the mean arc length of the slave
    nodes the row touches, weighted by the size of the row's entries on them (collocation: the
    row's node; LAC: the centre of its macro-segment)."""
    node_of_col = contact_dofs // 2
    pos = np.empty(K.shape[0])
    for r in range(K.shape[0]):
        num = den = 0.0
        for n in set(node_of_col[np.flatnonzero(K[r])].tolist()):
            if n in arc:
                wt = np.linalg.norm(K[r, node_of_col == n])
                num, den = num + wt * arc[n], den + wt
        pos[r] = num / den
    return pos


def check_format(path):
    """Stops with one message unless `path` is a complete 2D snapshot file of format 5 or 6."""
    try:
        with h5py.File(path, 'r') as f:
            fmt, version = f.attrs.get('format'), f.attrs.get('format_version')
            complete = f.attrs.get('complete')
            dimension = f.attrs.get('dimension', 2)  # format 5 files are 2D
    except OSError as e:
        sys.exit(f'best_approximation.py: {path}: cannot be read as HDF5 ({e})')
    fmt = fmt.decode() if isinstance(fmt, bytes) else fmt
    if fmt != 'contactrb-snapshots' or version not in (5, 6) or complete != 1 or dimension != 2:
        sys.exit(f'best_approximation.py: {path}: not a complete 2D contactrb snapshot file of format 5 or 6 '
                 f'(format {fmt!r}, version {version}, complete {complete}, dimension {dimension})')


def read(path):
    check_format(path)
    d = Snapshots()
    with h5py.File(path, 'r') as f:
        count, p = int(f['snapshots'].attrs['count']), int(f['parameter'].attrs['count'])
        ok = np.flatnonzero(f['snapshots/converged'][:] == 1)
        if len(ok) < count:
            print(f"{path}: {count - len(ok)} failed snapshots left out", file=sys.stderr)
        d.lo = np.array([f[f'parameter/{k:06d}'].attrs['min'] for k in range(p)])
        d.hi = np.array([f[f'parameter/{k:06d}'].attrs['max'] for k in range(p)])
        d.mu = f['parameter/values'][:].reshape(count, p)[ok]
        arc = slave_arc_length(f['mesh/nodes'][:], f['discretization/slave'][:])
        s = row_positions(f[f'snapshots/{ok[0]:06d}/K'][:], f['discretization/contact_dofs'][:], arc)
        order = np.argsort(s)
        d.s = s[order]
        g = [f[f'snapshots/{k:06d}'] for k in ok]
        d.lam = np.array([x['lambda'][:][order] for x in g])
        d.w = np.array([x['weight'][:][order] for x in g])
        dofs = f['discretization/contact_dofs'][:]
        d.gap = np.array([((x['g'][:] - x['K'][:] @ x['u'][:][dofs]) / x['weight'][:])[order] for x in g])
        d.u = np.array([x['u0'][:] for x in g])
    d.x = (d.mu - d.lo) / (d.hi - d.lo)
    return d


# ---------------------------------------------------------------------------------------------
# Norms and best approximations
# ---------------------------------------------------------------------------------------------
def rel_err(w, exact, approx):
    return np.sqrt(np.sum(w * (exact - approx) ** 2) / np.sum(w * exact ** 2))


def cone_error(w, lam, G):
    """Best non-negative combination of the columns of G, weighted L2."""
    sw = np.sqrt(w)
    c, _ = nnls(sw[:, None] * G, sw * lam, maxiter=50 * G.shape[1] + 100)
    return rel_err(w, lam, G @ c)


def span_error(w, lam, G):
    """Best (unsigned) combination of the columns of G, weighted L2."""
    sw = np.sqrt(w)
    c, *_ = np.linalg.lstsq(sw[:, None] * G, sw * lam, rcond=None)
    return rel_err(w, lam, G @ c)


# ---------------------------------------------------------------------------------------------
# Support ends and registered profiles
# ---------------------------------------------------------------------------------------------
def active_hull(lam):
    act = np.flatnonzero(lam > ACTIVE * lam.max())
    return act.min(), act.max()


def discrete_ends(s, lam, gap=None):
    """Midpoints to the first inactive rows (the last active row at the end of the chain)."""
    i, j = active_hull(lam)
    a = 0.5 * (s[i - 1] + s[i]) if i > 0 else s[i]
    b = 0.5 * (s[j] + s[j + 1]) if j + 1 < len(s) else s[j]
    return a, b


def sqrt_end(s_out, s_in, p_out, p_in, s_next):
    """Edge of p ~ c sqrt(|a - s|) through the outermost active row (s_out, p_out) and its inner
    neighbour (s_in, p_in), kept between the outermost active row and the first inactive row."""
    if p_in ** 2 <= p_out ** 2:
        return 0.5 * (s_out + s_next)
    a = s_out + (s_out - s_in) * p_out ** 2 / (p_in ** 2 - p_out ** 2)
    lo, hi = sorted((s_out, s_next))
    return min(max(a, lo), hi)


def sqrt_ends(s, lam, gap=None):
    i, j = active_hull(lam)
    if j - i < 1 or i == 0 or j + 1 == len(s):
        return discrete_ends(s, lam)
    a = sqrt_end(s[i], s[i + 1], lam[i], lam[i + 1], s[i - 1])
    b = sqrt_end(s[j], s[j - 1], lam[j], lam[j - 1], s[j + 1])
    return a, b


def gap_end(s_in, s1, s2, g1, g2):
    """Edge of a gap g ~ c |s - a|^(3/2) (Hertz) through the first two inactive rows (s1, g1),
    (s2, g2), kept between the outermost active row s_in and s1."""
    if not (0.0 < g1 < g2):
        return 0.5 * (s_in + s1)
    r = (g1 / g2) ** (2.0 / 3.0)
    a = (s1 - r * s2) / (1.0 - r)
    lo, hi = sorted((s_in, s1))
    return min(max(a, lo), hi)


def gap_ends(s, lam, gap):
    """Support ends from the deformed gap g - K u at the inactive rows next to the support: a
    smooth function of the displacement, which a reduced model knows online."""
    i, j = active_hull(lam)
    if i < 2 or j + 2 >= len(s):
        return sqrt_ends(s, lam)
    return (gap_end(s[i], s[i - 1], s[i - 2], gap[i - 1], gap[i - 2]),
            gap_end(s[j], s[j + 1], s[j + 2], gap[j + 1], gap[j + 2]))


ENDS = {'discrete': discrete_ends, 'sqrt': sqrt_ends, 'gap': gap_ends}


class Profile:
    """The pressure of one snapshot as a function of the arc length: linear between the rows of
    its active hull, and from the outermost active rows to zero at the support ends (linearly
    for discrete ends, as sqrt(distance to the end) for square-root ends); zero outside."""

    def __init__(self, s, lam, ends, rule):
        self.i, self.j = active_hull(lam)
        self.s, self.lam, self.a, self.b, self.rule = s, lam, ends[0], ends[1], rule

    def edge(self, t, end, row):
        dist, span = np.abs(t - end), max(abs(self.s[row] - end), 1e-300)
        shape = dist / span if self.rule == 'discrete' else np.sqrt(dist / span)
        return self.lam[row] * np.minimum(shape, 1.0)

    def __call__(self, t):
        i, j, s = self.i, self.j, self.s
        out = np.interp(t, s[i:j + 1], self.lam[i:j + 1])
        left, right = (t >= self.a) & (t < s[i]), (t > s[j]) & (t <= self.b)
        out[left], out[right] = self.edge(t[left], self.a, i), self.edge(t[right], self.b, j)
        out[(t < self.a) | (t > self.b)] = 0.0
        return out

    def registered(self, xi):
        """The profile at reference coordinates xi (0: support start, 1: support end)."""
        return self(self.a + xi * (self.b - self.a))


def registered_generators(profiles, s, ends):
    """Columns: the training profiles registered onto the support `ends`, at the rows s."""
    xi = (s - ends[0]) / (ends[1] - ends[0])
    return np.array([pr.registered(xi) for pr in profiles]).T


# ---------------------------------------------------------------------------------------------
# Predictors of the query's support ends
# ---------------------------------------------------------------------------------------------
def quadratic_features(x):
    """1, x_k, x_k x_l (k <= l) of scaled parameter points (rows)."""
    x = np.atleast_2d(x)
    cols = [np.ones(len(x))] + [x[:, k] for k in range(x.shape[1])]
    cols += [x[:, k] * x[:, l] for k in range(x.shape[1]) for l in range(k, x.shape[1])]
    return np.array(cols).T


def end_predictors(train_x, train_ends):
    """name -> function(x_query) -> (a, b), from the training supports: an interpolant
    (p = 1 linear; p > 1 thin-plate RBF with a linear term, or linear regression on the 8 nearest)
    and a quadratic least-squares fit over all training points (smooths the ends' jitter)."""
    coef, *_ = np.linalg.lstsq(quadratic_features(train_x), train_ends, rcond=None)
    quadratic = lambda x: tuple((quadratic_features(x) @ coef)[0])
    if train_x.shape[1] == 1:
        t = train_x[:, 0]
        order = np.argsort(t)
        return {'interp': lambda x: tuple(np.interp(x[0], t[order], train_ends[order, c]) for c in (0, 1)),
                'quadratic fit': quadratic}
    rbf = RBFInterpolator(train_x, train_ends, kernel='thin_plate_spline', degree=1)

    def knn_linear(x, k=8):
        near = np.argsort(np.linalg.norm(train_x - x, axis=1))[:k]
        A = np.hstack([np.ones((k, 1)), train_x[near]])
        coef, *_ = np.linalg.lstsq(A, train_ends[near], rcond=None)
        return tuple(np.concatenate([[1.0], x]) @ coef)
    return {'rbf': lambda x: tuple(rbf(x[None, :])[0]), 'knn8-linear': knn_linear, 'quadratic fit': quadratic}


# ---------------------------------------------------------------------------------------------
# Clusters
# ---------------------------------------------------------------------------------------------
def kmeans(features, K, seeds=10):
    """k-means with several seeded starts, the lowest inertia kept (deterministic); None when
    the features have fewer than K distinct values or no start gives K clusters."""
    best = None
    if len(np.unique(features, axis=0)) < K:
        return None
    for seed in range(seeds):
        with warnings.catch_warnings():
            warnings.simplefilter('ignore')
            cent, lab = kmeans2(features, K, minit='++', seed=seed)
        if len(set(lab.tolist())) < K:
            continue
        inertia = np.sum((features - cent[lab]) ** 2)
        if best is None or inertia < best[0]:
            best = (inertia, cent, lab)
    return None if best is None else best[1:]


def cluster_members(features, cent, overlap):
    """Members of each cluster: the points nearest to its centroid, and with overlap also the
    points whose second-nearest centroid it is."""
    dist = np.linalg.norm(features[:, None, :] - cent[None, :, :], axis=2)
    rank = np.argsort(dist, axis=1)
    depth = 2 if overlap else 1
    return [np.flatnonzero((rank[:, :depth] == k).any(axis=1)) for k in range(len(cent))]


# ---------------------------------------------------------------------------------------------
# The study of one case
# ---------------------------------------------------------------------------------------------
def summary(errors):
    e = np.asarray(errors)
    return float(e.max()), float(np.median(e))


class Study:
    def __init__(self, name, tr, ve):
        self.name, self.tr, self.ve, self.rows = name, tr, ve, []
        self.p = tr.mu.shape[1]
        self.P, self.R_hf = tr.lam.shape
        self.support_rows = int(np.sum(tr.lam.max(axis=0) > 0))

    def add(self, family, candidate, sizes, errors, touches):
        mx, med = summary(errors)
        self.rows.append(dict(case=self.name, family=family, candidate=candidate, sizes=sizes,
                              max=mx, median=med, touches=touches))

    def nearest(self, x, k):
        return np.argsort(np.linalg.norm(self.tr.x - x, axis=1), kind='stable')[:k]

    def k_values(self):
        return [k for k in ((2, 4, 8, 12) if self.p > 1 else (2, 4, 8)) if k <= self.P]

    # C0 ---------------------------------------------------------------------------------------
    def global_cone(self):
        tr, ve = self.tr, self.ve
        errs = [cone_error(ve.w[q], ve.lam[q], tr.lam.T) for q in range(len(ve.mu))]
        self.add('C0', 'global cone (NNLS)', f'R {self.P}', errs, f'{self.support_rows} rows x {self.P}')

    # C1 ---------------------------------------------------------------------------------------
    def local_cones(self):
        tr, ve = self.tr, self.ve
        for k in self.k_values():
            errs = [cone_error(ve.w[q], ve.lam[q], tr.lam[self.nearest(ve.x[q], k)].T) for q in range(len(ve.mu))]
            self.add('C1', f'{k} nearest', f'R {k}', errs, f'search {self.P} x p; rows x {k}')

    def cluster_cones(self):
        tr, ve = self.tr, self.ve
        active = (tr.lam > ACTIVE * tr.lam.max(axis=1, keepdims=True)).astype(float)
        for K in range(2, 9):
            if K >= self.P:
                break
            for feat_name, feats in (('parameters', tr.x), ('active sets', active)):
                found = kmeans(feats, K)
                if found is None:
                    continue
                cent, lab = found
                for overlap in (False, True):
                    members = cluster_members(feats, cent, overlap)
                    assign = self.assigners(feat_name, feats, cent, lab)
                    for how, pick in assign.items():
                        errs = [cone_error(ve.w[q], ve.lam[q], tr.lam[members[pick(q)]].T) for q in range(len(ve.mu))]
                        size = max(len(m) for m in members)
                        tag = f'K {K} k-means on {feat_name}{", overlap" if overlap else ""}{how}'
                        self.add('C1', tag, f'R <= {size}', errs, f'search {K} centroids; rows x {size}')

    def assigners(self, feat_name, feats, cent, lab):
        """How a query picks its cluster: the nearest centroid in parameter space; for active-set
        clusters, the cluster of the nearest training point, or (oracle) the centroid nearest to
        the query's own active set."""
        ve = self.ve
        if feat_name == 'parameters':
            return {'': lambda q: int(np.argmin(np.linalg.norm(cent - ve.x[q], axis=1)))}
        own = (ve.lam > ACTIVE * ve.lam.max(axis=1, keepdims=True)).astype(float)
        return {' (by nearest point)': lambda q: int(lab[self.nearest(ve.x[q], 1)[0]]),
                ' (oracle active set)': lambda q: int(np.argmin(np.linalg.norm(cent - own[q], axis=1)))}

    def row_spaces(self):
        """Every HF row of a support as its own generator (no snapshot compression): the rows of
        the union of all training supports, or of the k nearest points' supports widened by one
        row on each side. Exact whenever the query's support lies inside."""
        tr, ve = self.tr, self.ve
        union = np.flatnonzero(tr.lam.max(axis=0) > 0)
        errs = [cone_error(ve.w[q], ve.lam[q], np.eye(self.R_hf)[:, union]) for q in range(len(ve.mu))]
        self.add('C4', 'HF rows of the training supports', f'R {len(union)}', errs, f'{len(union)} rows x {len(union)}')
        for k in self.k_values():
            errs, sizes = [], []
            for q in range(len(ve.mu)):
                near = tr.lam[self.nearest(ve.x[q], k)].max(axis=0) > 0
                rows = np.flatnonzero(near | np.roll(near, 1) | np.roll(near, -1))
                sizes.append(len(rows))
                errs.append(cone_error(ve.w[q], ve.lam[q], np.eye(self.R_hf)[:, rows]))
            self.add('C4', f'HF rows of the {k} nearest supports, +1 row each side',
                     f'R median {int(np.median(sizes))}, max {max(sizes)}', errs,
                     f'search {self.P} x p; rows x rows')

    # C2 / C3 ----------------------------------------------------------------------------------
    def registration(self):
        tr, ve = self.tr, self.ve
        Q = len(ve.mu)
        for rule, ends_of in ENDS.items():
            t_ends = np.array([ends_of(tr.s, l, g) for l, g in zip(tr.lam, tr.gap)])
            profiles = [Profile(tr.s, l, e, rule) for l, e in zip(tr.lam, t_ends)]
            reg = np.array([pr.registered(GRID) for pr in profiles])        # P x grid
            sig = np.linalg.svd(reg, compute_uv=False)
            n_modes = int(np.sum(sig / sig[0] > 1e-3))
            modes = np.linalg.svd(reg.T, full_matrices=False)[0]            # grid x P
            greedy = self.greedy_generators(reg, max(R_MODES))
            predictors = dict(end_predictors(tr.x, t_ends))
            predictors['oracle'] = lambda x, q=None: None
            for pname, predict in predictors.items():
                q_ends = [ends_of(ve.s, ve.lam[q], ve.gap[q]) if pname == 'oracle' else predict(ve.x[q]) for q in range(Q)]
                tag = f'ends {rule}, support {pname}'
                gens = [registered_generators(profiles, ve.s, q_ends[q]) for q in range(Q)]
                errs = [cone_error(ve.w[q], ve.lam[q], gens[q]) for q in range(Q)]
                self.add('C2', f'registered cone, {tag}', f'R {self.P}; modes>1e-3: {n_modes}', errs,
                         f'rows in support x {self.P} profile evaluations')
                for R in R_MODES:
                    xi = [(ve.s - e[0]) / (e[1] - e[0]) for e in q_ends]
                    pod = [np.array([np.interp(xi[q], GRID, modes[:, i], left=0, right=0) for i in range(R)]).T
                           for q in range(Q)]
                    e_pod = [span_error(ve.w[q], ve.lam[q], pod[q]) for q in range(Q)]
                    self.add('C2', f'registered POD (least squares), {tag}', f'R {R}', e_pod,
                             f'rows in support x {R} mode evaluations')
                    e_gr = [cone_error(ve.w[q], ve.lam[q], gens[q][:, greedy[:R]]) for q in range(Q)]
                    self.add('C2', f'registered greedy cone, {tag}', f'R {R}', e_gr,
                             f'rows in support x {R} profile evaluations')
                self.registered_with_edges(tag, gens, q_ends)
                for k in self.k_values():
                    e_loc = [cone_error(ve.w[q], ve.lam[q], gens[q][:, self.nearest(ve.x[q], k)]) for q in range(Q)]
                    self.add('C3', f'{k} nearest, registered, {tag}', f'R {k}', e_loc,
                             f'search {self.P} x p; rows in support x {k}')
                    e_uni = [cone_error(ve.w[q], ve.lam[q], np.hstack([gens[q][:, near], tr.lam[near].T]))
                             for q in range(Q) for near in [self.nearest(ve.x[q], k)]]
                    self.add('C3', f'{k} nearest, as is + registered, {tag}', f'R {2 * k}', e_uni,
                             f'search {self.P} x p; rows x {2 * k}')

    def edge_rows(self, ends, width):
        """Identity generators of the `width` rows on each side of each predicted support end."""
        s = self.ve.s
        rows = set()
        for e in ends:
            c = int(np.searchsorted(s, e))
            rows.update(range(max(c - width, 0), min(c + width, len(s))))
        return np.eye(len(s))[:, sorted(rows)]

    def registered_with_edges(self, tag, gens, q_ends):
        """C5: the k nearest registered pressures plus the HF rows around the predicted ends: the
        rows absorb the support ends' error and the discrete edge, the registered pressures carry
        the interior."""
        tr, ve = self.tr, self.ve
        for k in (2, 4, 8):
            for width in (1, 2, 3):
                errs = [cone_error(ve.w[q], ve.lam[q],
                                   np.hstack([gens[q][:, self.nearest(ve.x[q], k)], self.edge_rows(q_ends[q], width)]))
                        for q in range(len(ve.mu))]
                self.add('C5', f'{k} nearest registered + {2 * width} rows at each end, {tag}',
                         f'R {k + 4 * width}', errs, f'search {self.P} x p; rows in support x {k + 4 * width}')

    @staticmethod
    def greedy_generators(reg, R):
        """Registered generators picked one at a time: the training profile worst approximated by
        the cone of those picked so far (first: the largest)."""
        picked = [int(np.argmax(np.linalg.norm(reg, axis=1)))]
        ones = np.ones(reg.shape[1])
        while len(picked) < min(R, len(reg)):
            errs = [cone_error(ones, r, reg[picked].T) if np.any(r) else 0.0 for r in reg]
            picked.append(int(np.argmax(errs)))
        return picked

    # Primal -----------------------------------------------------------------------------------
    def primal(self):
        tr, ve = self.tr, self.ve
        basis = np.linalg.svd(tr.u.T, full_matrices=False)[0]
        proj_err = lambda V, u: np.linalg.norm(u - V @ (V.T @ u)) / np.linalg.norm(u)
        for N in (5, 10, 20, 40):
            if N > self.P:
                continue
            errs = [proj_err(basis[:, :N], u) for u in ve.u]
            self.add('primal', 'global POD', f'N {N}', errs, f'n_free x {N}')
            k = min(2 * N, self.P)
            errs = []
            for q in range(len(ve.mu)):
                V = np.linalg.svd(tr.u[self.nearest(ve.x[q], k)].T, full_matrices=False)[0][:, :N]
                errs.append(proj_err(V, ve.u[q]))
            self.add('primal', f'local POD of the {k} nearest', f'N {N}', errs, f'n_free x {N}')

    def run(self):
        self.global_cone()
        self.local_cones()
        self.cluster_cones()
        self.row_spaces()
        self.registration()
        self.primal()
        return self.rows


def print_summary(rows):
    """Per case and family: the candidate of smallest max error with a predicted support (or no
    support), and the one with the query's own support (oracle)."""
    print('\n| case | family | best candidate | sizes | max | median | best with the oracle support | sizes | max |')
    print('| --- | --- | --- | --- | ---: | ---: | --- | --- | ---: |')
    for case in dict.fromkeys(r['case'] for r in rows):
        for fam in dict.fromkeys(r['family'] for r in rows if r['case'] == case):
            mine = [r for r in rows if r['case'] == case and r['family'] == fam]
            real = min((r for r in mine if 'oracle' not in r['candidate']), key=lambda r: r['max'], default=None)
            orac = min((r for r in mine if 'oracle' in r['candidate']), key=lambda r: r['max'], default=None)
            left = f"{real['candidate']} | {real['sizes']} | {real['max']:.2e} | {real['median']:.2e}" if real else '| | |'
            right = f"{orac['candidate']} | {orac['sizes']} | {orac['max']:.2e}" if orac else '| |'
            print(f'| {case} | {fam} | {left} | {right} |')


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--pair', nargs=3, action='append', required=True, metavar=('NAME', 'TRAIN', 'VERIF'))
    ap.add_argument('--csv', help='write every row to this CSV file')
    args = ap.parse_args()
    rows = []
    for name, train, verif in args.pair:
        tr, ve = read(train), read(verif)
        if tr.lam.shape[1] != ve.lam.shape[1] or not np.allclose(tr.s, ve.s):
            sys.exit(f'{name}: training and verification files have different contact rows')
        print(f'{name}: {len(tr.mu)} training, {len(ve.mu)} verification points, {tr.lam.shape[1]} rows',
              file=sys.stderr)
        rows += Study(name, tr, ve).run()
    print('| case | family | candidate | sizes | max error | median | online: touches |')
    print('| --- | --- | --- | --- | ---: | ---: | --- |')
    for r in rows:
        print(f"| {r['case']} | {r['family']} | {r['candidate']} | {r['sizes']} | {r['max']:.2e} | "
              f"{r['median']:.2e} | {r['touches']} |")
    print_summary(rows)
    if args.csv:
        with open(args.csv, 'w', newline='') as f:
            wr = csv.DictWriter(f, fieldnames=list(rows[0]))
            wr.writeheader()
            wr.writerows(rows)


if __name__ == '__main__':
    main()
