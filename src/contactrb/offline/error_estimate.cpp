#include "contactrb/offline/error_estimate.hpp"

#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <string>

#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/index_cast.hpp"
#include "contactrb/offline/eim_flatten.hpp"
#include "contactrb/solve/pivoted_qr.hpp"

namespace contactrb::offline {

using model::EstimateData;
using model::kEstimateRankTolerance;
using model::residual_columns;

// |L^-1 P E_c' c| for a load c on the contact DOFs: |R_c c_u| from the base's factor when c
// vanishes off its contact columns (the residual's own columns, to round-off), else a solve.
double contact_load_norm(const Eigen::VectorXd& c, const EstimateInputs& in, const EstimateBase& base) {
  const std::vector<Index>& columns = base.contact_columns;
  Eigen::VectorXd cu(ix(columns.size()));
  double outside = 0.0;
  std::size_t next = 0;
  for (Index a = 0; a < c.size(); ++a) {
    if (next < columns.size() && columns[next] == a) {
      cu(ix(next++)) = c(a);
    } else if (base.global_to_free[sz((*in.contact_dofs)[sz(a)])] >= 0) {
      outside = std::max(outside, std::abs(c(a)));
    }
  }
  if (outside == 0.0 && base.columns_built) return (base.R_fixed.rightCols(cu.size()) * cu).norm();
  Eigen::VectorXd v = Eigen::VectorXd::Zero(ix(in.free_dofs->size()));
  for (Index a = 0; a < c.size(); ++a) {
    const Index fi = base.global_to_free[sz((*in.contact_dofs)[sz(a)])];
    if (fi >= 0) v(fi) = c(a);
  }
  Eigen::VectorXd pv = base.P * v;
  base.llt.matrixL().solveInPlace(pv);
  return pv.norm();
}

// |L^-1 P E_c' c_M| for the loads c_M = KtL - QtL[:, :M] a[:M], M = 0 .. Mk (a the coefficients
// of the largest EIM: those of a leading size are its head, B being lower triangular). When
// K'lambda and every Q_i'lambda vanish off the base's contact columns, so does every c_M, and
// R_c c_M,u = R_c KtL_u - sum_{i<M} a_i R_c QtL_u,i: one triangular product for all M, then an
// axpy per M, instead of a product per M (contact_load_norm).
Eigen::VectorXd eim_load_norms(const Eigen::VectorXd& KtL, const Eigen::MatrixXd& QtL, const Eigen::VectorXd& a,
                               const EstimateInputs& in, const EstimateBase& base) {
  const Index Mk = QtL.cols();
  Eigen::VectorXd norms(Mk + 1);
  const std::vector<Index>& columns = base.contact_columns;
  const Index n_u = ix(columns.size());
  bool inside = base.columns_built;
  std::size_t next = 0;
  for (Index r = 0; inside && r < KtL.size(); ++r) {
    if (next < columns.size() && columns[next] == r) {
      ++next;
    } else if (base.global_to_free[sz((*in.contact_dofs)[sz(r)])] >= 0) {
      inside = KtL(r) == 0.0 && (QtL.row(r).array() == 0.0).all();
    }
  }
  if (!inside) {
    for (Index M = 0; M <= Mk; ++M) {
      norms(M) = contact_load_norm(KtL - QtL.leftCols(M) * a.head(M), in, base);
    }
    return norms;
  }
  Eigen::VectorXd ku(n_u);
  Eigen::MatrixXd qu(n_u, Mk);
  for (Index j = 0; j < n_u; ++j) {
    ku(j) = KtL(columns[sz(j)]);
    qu.row(j) = QtL.row(columns[sz(j)]);
  }
  // R_fixed's contact columns are [R_c; 0], R_c upper triangular (EstimateBase).
  const auto Rc = base.R_fixed.topRightCorner(n_u, n_u).triangularView<Eigen::Upper>();
  // Eigen's triangular product binds a reference to the data of an empty operand (undefined
  // behaviour, UBSan): an empty one (no EIM function, no touched DOF) is skipped.
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n_u);
  Eigen::MatrixXd Y(n_u, Mk);
  if (n_u > 0) y = Rc * ku;
  if (n_u > 0 && Mk > 0) Y = Rc * qu;
  norms(0) = y.norm();
  for (Index M = 1; M <= Mk; ++M) {
    y -= a(M - 1) * Y.col(M - 1);
    norms(M) = y.norm();
  }
  return norms;
}

// The EIM errors on the training snapshots (EstimateData::eim_residual, eim_slack), for every
// leading size: I_M F = Q[:, :M] a_M, a_M = B[:M, :M]^-1 F(magic[:M]) (B lower triangular). The
// two products the bound needs are linear in F, so they are formed from the snapshot's and the
// basis' products once: (K - I_M K)' lambda = K' lambda - [Q_i' lambda]_{i<M} a_M and
// (K - I_M K) u_0 = K u_0 - [Q_i u_0]_{i<M} a_M.
void calibrate_eim(const EstimateInputs& in, const EstimateBase& base, EstimateData& e) {
  const Eigen::MatrixXd& Qk = *in.Q_kappa;
  const Eigen::MatrixXd& Qg = *in.Q_gamma;
  const int Mk = static_cast<int>(Qk.cols()), Mg = static_cast<int>(Qg.cols());
  const Index R_kept = Qg.rows();
  const Index n_c = ix(in.contact_dofs->size());
  const Eigen::VectorXd& w = *in.weights_kept;
  require(ix(in.kappa_magic->size()) == Mk && ix(in.gamma_magic->size()) == Mg && w.size() == R_kept &&
              in.B_kappa->rows() == Mk && in.B_gamma->rows() == Mg,
          "build_estimate_data: the EIM data disagree with the bases");
  e.eim_residual = Eigen::VectorXd::Zero(Mk + 1);
  e.eim_slack = Eigen::MatrixXd::Zero(Mk + 1, Mg + 1);
  for (const io::Snapshot& snap : in.set->snapshots) {
    Eigen::MatrixXd K(R_kept, n_c);
    Eigen::VectorXd lambda(R_kept), G(R_kept);
    const Eigen::VectorXd lift = in.lift_c->cols() > 0
                                     ? Eigen::VectorXd(*in.lift_c * cases::evaluate(in.thetas->lift, snap.mu))
                                     : Eigen::VectorXd::Zero(n_c);
    const Eigen::VectorXd g_lift = snap.g - snap.K * lift;
    for (Index r = 0; r < R_kept; ++r) {
      const int row = (*in.kept_rows)[sz(r)];
      K.row(r) = Eigen::RowVectorXd(snap.K.row(row));
      lambda(r) = std::max(0.0, snap.lambda(row));
      G(r) = g_lift(row);
    }
    Eigen::VectorXd u0_c = Eigen::VectorXd::Zero(n_c);
    for (Index a = 0; a < n_c; ++a) {
      const Index fi = base.global_to_free[sz((*in.contact_dofs)[sz(a)])];
      if (fi >= 0) u0_c(a) = snap.u0(fi);
    }
    const double lambda_norm = std::sqrt((w.array() * lambda.array().square()).sum());
    // Flattened row-major (eim_flatten.hpp): F(r n_c + n) = K(r, n); column i of Q_kappa so
    // flattened is Q_i, and its column-major n_c x R_kept view is Q_i'.
    const Eigen::MatrixXd Kt = K.transpose();
    const Eigen::Map<const Eigen::VectorXd> F(Kt.data(), Kt.size());
    Eigen::MatrixXd QtL(n_c, Mk), QU(R_kept, Mk);
    for (int i = 0; i < Mk; ++i) {
      const Eigen::Map<const Eigen::MatrixXd> Qit(Qk.col(i).data(), n_c, R_kept);
      QtL.col(i) = Qit * lambda;
      QU.col(i) = Qit.transpose() * u0_c;
    }
    const Eigen::VectorXd KtL = Kt * lambda, Ku = K * u0_c;
    Eigen::VectorXd values(Mk);
    for (int i = 0; i < Mk; ++i) values(i) = F((*in.kappa_magic)[sz(i)]);
    // The coefficients of every leading size M are the head of these (forward substitution).
    const Eigen::VectorXd a = in.B_kappa->topLeftCorner(Mk, Mk).triangularView<Eigen::Lower>().solve(values);
    std::vector<Eigen::VectorXd> dKu(sz(Mk + 1));
    for (int M = 0; M <= Mk; ++M) dKu[sz(M)] = Ku - QU.leftCols(M) * a.head(M);
    if (lambda_norm > 0.0) {  // (K - I_M K)' lambda
      const Eigen::VectorXd norms = eim_load_norms(KtL, QtL, a, in, base);
      e.eim_residual = e.eim_residual.cwiseMax(norms / lambda_norm);
    }
    for (int Mp = 0; Mp <= Mg; ++Mp) {
      Eigen::VectorXd dG = G;
      if (Mp > 0) {
        Eigen::VectorXd values(Mp);
        for (int i = 0; i < Mp; ++i) values(i) = G((*in.gamma_magic)[sz(i)]);
        dG -= Qg.leftCols(Mp) * in.B_gamma->topLeftCorner(Mp, Mp).triangularView<Eigen::Lower>().solve(values);
      }
      // The slack error enters the bound as ((delta s)^-)' lambda (the interpenetration the EIM hides,
      // weighted by the pressure that meets it): calibrated as that product per unit |lambda|_Lambda.
      if (lambda_norm <= 0.0) continue;
      for (int M = 0; M <= Mk; ++M) {
        const double hidden = (dKu[sz(M)] - dG).cwiseMax(0.0).dot(lambda) / lambda_norm;  // delta s = dG - dKu
        e.eim_slack(M, Mp) = std::max(e.eim_slack(M, Mp), hidden);
      }
    }
  }
}

// The free contact-surface DOFs the kept rows touch in training, with kExactDofMargin chain
// nodes each side (EstimateData::exact_dofs).
std::vector<int> exact_contact_dofs(const EstimateInputs& in, const std::vector<Index>& global_to_free) {
  const model::ContactSurface& surface = *in.surface;
  const Index n_c = ix(in.contact_dofs->size());
  std::vector<char> node_touched(surface.reference_nodes.size(), 0);
  for (const io::Snapshot& snap : in.set->snapshots) {
    for (int row : *in.kept_rows) {
      for (io::SnapshotRows::InnerIterator it(snap.K, row); it; ++it) {
        if (it.value() != 0.0) node_touched[sz(static_cast<int>(it.col() / 2))] = 1;
      }
    }
  }
  std::vector<char> node_kept = node_touched;
  for (const std::vector<int>* chain : {&surface.slave, &surface.master}) {
    const int n = static_cast<int>(chain->size());
    for (int k = 0; k < n; ++k) {
      if (!node_touched[sz((*chain)[sz(k)])]) continue;
      for (int d = -model::kExactDofMargin; d <= model::kExactDofMargin; ++d) {
        if (k + d >= 0 && k + d < n) node_kept[sz((*chain)[sz(k + d)])] = 1;
      }
    }
  }
  std::vector<int> dofs;
  for (Index a = 0; a < n_c; ++a) {
    if (node_kept[sz(static_cast<int>(a / 2))] && global_to_free[sz((*in.contact_dofs)[sz(a)])] >= 0) {
      dofs.push_back(static_cast<int>(a));
    }
  }
  return dofs;
}

// |S y| = |R P' y| for every y: the rank-truncated R factor of S's column-pivoted QR.
Eigen::MatrixXd residual_factor(const Eigen::MatrixXd& S) {
  const solve::PivotedQR qr = solve::pivoted_qr(S, kEstimateRankTolerance);
  Eigen::MatrixXd RPt(qr.R.rows(), S.cols());
  for (std::size_t k = 0; k < qr.permutation.size(); ++k) RPt.col(qr.permutation[k]) = qr.R.col(ix(k));
  return RPt;
}

namespace {

// X = A_00(reference_mu) on the free DOFs.
Eigen::SparseMatrix<double> energy_product(const EstimateInputs& in, const std::vector<Index>& global_to_free) {
  const fem::SparseMatrix A_ref = cases::combine(in.terms->A, cases::evaluate(in.thetas->a, in.reference_mu));
  const Index n_free = ix(in.free_dofs->size());
  Eigen::SparseMatrix<double> X(n_free, n_free);
  std::vector<Eigen::Triplet<double>> trip;
  for (Index k = 0; k < A_ref.outerSize(); ++k) {
    for (fem::SparseMatrix::InnerIterator it(A_ref, k); it; ++it) {
      const Index r = global_to_free[sz(it.row())], c = global_to_free[sz(it.col())];
      if (r >= 0 && c >= 0) trip.emplace_back(r, c, it.value());
    }
  }
  X.setFromTriplets(trip.begin(), trip.end());
  return X;
}

Eigen::VectorXd restrict_free(const Eigen::VectorXd& g, const std::vector<int>& free) {
  Eigen::VectorXd out(ix(free.size()));
  for (std::size_t i = 0; i < free.size(); ++i) out(ix(i)) = g(free[i]);
  return out;
}

// L^-1 P v column by column (P X P' = L L', EstimateBase).
Eigen::MatrixXd whiten(const EstimateBase& base, const Eigen::MatrixXd& V) {
  Eigen::MatrixXd W = base.P * V;
  base.llt.matrixL().solveInPlace(W);
  return W;
}

// The free index of each DOF (once per problem).
void map_free_dofs(const EstimateInputs& in, EstimateBase& base) {
  const std::vector<int>& free = *in.free_dofs;
  base.global_to_free.assign(sz(in.terms->A.front().rows()), -1);
  for (std::size_t i = 0; i < free.size(); ++i) base.global_to_free[sz(free[i])] = ix(i);
  base.factored = true;
}

// P X P' = L L' with the free DOFs of `contact` eliminated last, in that order, and the others
// in X's AMD order before them.
void factor_contact_last(const EstimateInputs& in, const std::vector<Index>& contact, EstimateBase& base) {
  const Eigen::SparseMatrix<double> X = energy_product(in, base.global_to_free);
  const Index n_free = X.rows();
  std::vector<char> is_contact(sz(n_free), 0);
  Eigen::VectorXi order(n_free);  // elimination position -> free index
  Index next = n_free - ix(contact.size());
  for (const Index a : contact) {
    const Index fi = base.global_to_free[sz((*in.contact_dofs)[sz(a)])];
    require(fi >= 0 && !is_contact[sz(fi)], "internal: an estimate contact column is not a free DOF");
    is_contact[sz(fi)] = 1;
    order(next++) = static_cast<int>(fi);
  }
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
  Eigen::AMDOrdering<int>()(X, amd);
  next = 0;
  for (Index k = 0; k < n_free; ++k) {
    const int fi = amd.indices()(k);
    if (!is_contact[sz(fi)]) order(next++) = fi;
  }
  base.P = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>(order).inverse();
  Eigen::SparseMatrix<double> Xp(n_free, n_free);
  Xp = X.selfadjointView<Eigen::Lower>().twistedBy(base.P);
  base.llt.compute(Xp);
  require(base.llt.info() == Eigen::Success,
          "build_estimate_data: the energy product at the reference value is not positive definite");
}

// L_cc^-1, the whitened unit loads of the contact DOFs eliminated last (their rows; the rows
// before them are zero since L^-1 is lower triangular).
Eigen::MatrixXd whitened_contact_block(const EstimateBase& base, Index n_u) {
  const Eigen::SparseMatrix<double>& L = base.llt.matrixL().nestedExpression();
  const Eigen::MatrixXd Lcc = L.bottomRightCorner(n_u, n_u);
  Eigen::MatrixXd W = Eigen::MatrixXd::Identity(n_u, n_u);
  Lcc.triangularView<Eigen::Lower>().solveInPlace(W);
  return W;
}

// The basis-free columns (layout: model/error_estimate_data.hpp): the loads f_j, the lift terms
// -A_j u_D,k, and the columns of E_c' of the contact DOFs `contact`, whitened and factored in
// the block form of EstimateBase.
void factor_fixed_columns(const EstimateInputs& in, const std::vector<Index>& contact, EstimateBase& base) {
  const cases::AffineTerms& terms = *in.terms;
  const std::vector<int>& free = *in.free_dofs;
  const Index n_free = ix(free.size()), n_u = ix(contact.size()), n_i = n_free - n_u;
  const int Jf = static_cast<int>(terms.f.size()), Ja = static_cast<int>(terms.A.size());
  const int JD = static_cast<int>(terms.lift.size());
  const Index nf = Jf + Ja * JD;
  require(n_i >= nf, "build_estimate_data: fewer free DOFs off the contact surface than load and lift terms");
  factor_contact_last(in, contact, base);
  Eigen::MatrixXd V(n_free, nf);
  Index col = 0;
  for (int j = 0; j < Jf; ++j) V.col(col++) = restrict_free(terms.f[sz(j)], free);
  for (int j = 0; j < Ja; ++j) {
    for (int k = 0; k < JD; ++k) V.col(col++) = -restrict_free(terms.A[sz(j)] * terms.lift[sz(k)], free);
  }
  const Eigen::MatrixXd W = whiten(base, V);
  base.qr_interior.compute(W.topRows(n_i));
  base.R_fixed = Eigen::MatrixXd::Zero(n_u + nf, nf + n_u);
  base.R_fixed.bottomLeftCorner(nf, nf) = base.qr_interior.matrixQR().topRows(nf).triangularView<Eigen::Upper>();
  if (n_u > 0) {
    base.qr_contact.compute(whitened_contact_block(base, n_u));
    base.R_fixed.topLeftCorner(n_u, nf) = base.qr_contact.householderQ().adjoint() * W.bottomRows(n_u);
    base.R_fixed.topRightCorner(n_u, n_u) = base.qr_contact.matrixQR().triangularView<Eigen::Upper>();
  }
  base.n_fixed = static_cast<int>(nf);
  base.contact_columns = contact;
  base.extended = 0;  // the split basis columns were against the former factor
}

// The free contact DOFs (sorted) of the contact nodes within `pad` chain nodes of those of
// `dofs` (2D: contact DOF a is component a % 2 of contact node a / 2).
std::vector<Index> padded_contact_dofs(const EstimateInputs& in, const std::vector<Index>& dofs, int pad,
                                       const std::vector<Index>& global_to_free) {
  const model::ContactSurface& surface = *in.surface;
  const Index n_c = ix(in.contact_dofs->size());
  std::vector<char> node_needed(surface.reference_nodes.size(), 0), node_kept(surface.reference_nodes.size(), 0);
  for (Index a : dofs) node_needed[sz(static_cast<int>(a / 2))] = 1;
  for (const std::vector<int>* chain : {&surface.slave, &surface.master}) {
    const int n = static_cast<int>(chain->size());
    for (int k = 0; k < n; ++k) {
      if (!node_needed[sz((*chain)[sz(k)])]) continue;
      for (int d = std::max(0, k - pad); d <= std::min(n - 1, k + pad); ++d) node_kept[sz((*chain)[sz(d)])] = 1;
    }
  }
  std::vector<Index> out;
  for (Index a = 0; a < n_c; ++a) {
    if ((node_kept[sz(static_cast<int>(a / 2))] || std::binary_search(dofs.begin(), dofs.end(), a)) &&
        global_to_free[sz((*in.contact_dofs)[sz(a)])] >= 0) {
      out.push_back(a);
    }
  }
  return out;
}

// The base holding at least the contact DOFs `needed` (sorted): factored again, with the union,
// when a model needs a contact DOF it misses. A later build that misses some (a greedy's new
// snapshot activating rows next to the contact zone) is likely to miss their neighbours at the
// next steps: such a refactor also takes the contact DOFs within pad_nodes chain nodes of the
// needed ones, the margin doubling at each refactor (from kFirstPadNodes), so that a greedy
// refactors a few times rather than at each widening of the zone (every basis column is whitened
// and split again at a refactor).
constexpr int kFirstPadNodes = 4;
void ensure_estimate_base(const EstimateInputs& in, const std::vector<Index>& needed, EstimateBase& base) {
  if (!base.factored) map_free_dofs(in, base);
  if (base.columns_built && std::includes(base.contact_columns.begin(), base.contact_columns.end(), needed.begin(),
                                          needed.end())) {
    return;
  }
  std::vector<Index> wanted = needed;
  if (base.columns_built) {
    base.pad_nodes = base.pad_nodes == 0 ? kFirstPadNodes : 2 * base.pad_nodes;
    wanted = padded_contact_dofs(in, needed, base.pad_nodes, base.global_to_free);
  }
  std::vector<Index> all;
  std::set_union(base.contact_columns.begin(), base.contact_columns.end(), wanted.begin(), wanted.end(),
                 std::back_inserter(all));
  factor_fixed_columns(in, all, base);
  base.columns_built = true;
}

// The contact DOFs the estimate's contact columns touch: the free exact_dofs and the rows of C
// (the EIM columns -E_c' Q_i' Xi) that are not zero. Only these unit loads enter the residual.
std::vector<Index> used_contact_dofs(const std::vector<int>& exact_dofs, const Eigen::MatrixXd& C,
                                     const EstimateInputs& in, const std::vector<Index>& global_to_free) {
  std::vector<char> used(sz(C.rows()), 0);
  for (int a : exact_dofs) used[sz(a)] = 1;
  for (Index a = 0; a < C.rows(); ++a) {
    if (!used[sz(a)] && (C.row(a).array() != 0.0).any()) used[sz(a)] = 1;
  }
  std::vector<Index> out;
  for (Index a = 0; a < C.rows(); ++a) {
    if (used[sz(a)] && global_to_free[sz((*in.contact_dofs)[sz(a)])] >= 0) out.push_back(a);
  }
  return out;
}

// L^-1 P of the basis columns -A_j,00 Theta (A_j Theta with Theta extended by zero on the
// constrained DOFs, restricted to the free ones).
Eigen::MatrixXd whitened_basis_columns(const EstimateInputs& in, const EstimateBase& base) {
  const cases::AffineTerms& terms = *in.terms;
  const std::vector<int>& free = *in.free_dofs;
  const Eigen::MatrixXd& Theta = *in.Theta;
  const Index n_free = ix(free.size());
  const int Ja = static_cast<int>(terms.A.size()), N = static_cast<int>(Theta.cols());
  Eigen::MatrixXd Theta_global = Eigen::MatrixXd::Zero(terms.A.front().rows(), N);
  for (Index i = 0; i < n_free; ++i) Theta_global.row(free[sz(i)]) = Theta.row(i);
  Eigen::MatrixXd cols(n_free, static_cast<Index>(Ja) * N);
  Index col = 0;
  for (int j = 0; j < Ja; ++j) {
    const Eigen::MatrixXd AT = terms.A[sz(j)] * Theta_global;
    for (int n = 0; n < N; ++n) cols.col(col++) = -restrict_free(AT.col(n), free);
  }
  return whiten(base, cols);
}

// H' Z for whitened columns Z, in the row frame of R_fixed: [Q_c' Z_contact; Q_i' Z_interior]
// (EstimateBase). Its first R_fixed.rows() rows are the coefficients on the fixed columns' frame,
// the rest (Q_i' Z_interior below its first n_fixed rows) is the part orthogonal to them.
Eigen::MatrixXd split_against_fixed(const EstimateBase& base, const Eigen::MatrixXd& Z) {
  const Index nc = ix(base.contact_columns.size()), n_i = Z.rows() - nc;
  Eigen::MatrixXd out(Z.rows(), Z.cols());
  out.bottomRows(n_i) = Z.topRows(n_i);
  out.bottomRows(n_i).applyOnTheLeft(base.qr_interior.householderQ().adjoint());
  if (nc > 0) out.topRows(nc) = base.qr_contact.householderQ().adjoint() * Z.bottomRows(nc);
  return out;
}

// S with |W y| = |S y| for W = L^-1 P [f_j | -A_j u_D,k | -A_j,00 Theta | E_c'] (that column
// order, E_c' on the base's contact columns only): with the base's block factor
// [W_fixed | W_contact] = blockdiag(Q_i, Q_c) R_fixed, the basis columns split as H' W_t = [C; D]
// (split_against_fixed; D = Q_t R_t, thin QR), and S = [[R_f, C, R_c], [0, R_t, 0]]: only the
// n_free x J^a N basis block is factored per model.
Eigen::MatrixXd whitened_residual_factor(const EstimateInputs& in, const EstimateBase& base, Index cols) {
  const Eigen::MatrixXd Z = split_against_fixed(base, whitened_basis_columns(in, base));
  const Index n_free = Z.rows(), nt = Z.cols(), kc = base.R_fixed.rows();
  const Index nf = base.n_fixed, nc = ix(base.contact_columns.size());
  const Index kt = std::min(n_free - kc, nt);
  require(cols == nf + nt + nc, "build_estimate_data: inconsistent residual columns");
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(kc + kt, cols);
  S.topLeftCorner(kc, nf) = base.R_fixed.leftCols(nf);
  S.block(0, nf, kc, nt) = Z.topRows(kc);
  S.topRightCorner(kc, nc) = base.R_fixed.rightCols(nc);
  if (kt > 0) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Z.bottomRows(n_free - kc));
    S.block(kc, nf, kt, nt) = qr.matrixQR().topRows(kt).triangularView<Eigen::Upper>();
  }
  return S;
}

// A column whose part outside Q_t's span is below this fraction of its norm adds no row to R_t.
constexpr double kExtensionRankTolerance = 1e-13;

// Room for at least `cols` columns in Q_t, doubling: the columns in use are not copied at every build.
void reserve_thin_q(EstimateBase& base, Index cols) {
  if (cols <= base.Q_t.cols()) return;
  Eigen::MatrixXd grown(base.Q_t.rows(), std::min(base.Q_t.rows(), std::max(cols, 2 * base.Q_t.cols())));
  grown.leftCols(base.q_t) = base.Q_t.leftCols(base.q_t);
  base.Q_t = std::move(grown);
}

// Each column of Zt against the columns of Q_t from `from` on (classical Gram-Schmidt twice), Q_t
// gaining the column z_perp / rho when rho = |z_perp| leaves the span (kExtensionRankTolerance,
// relative to norm0): Zt's coefficients on those columns, one row per column of Q_t from `from`.
Eigen::MatrixXd append_each(Eigen::MatrixXd& Zt, const Eigen::VectorXd& norm0, EstimateBase& base, Index from) {
  const Index b = Zt.cols();
  Eigen::MatrixXd coef = Eigen::MatrixXd::Zero(b, b);
  for (Index i = 0; i < b; ++i) {
    const Index added = base.q_t - from;
    if (added > 0) {
      const auto Qn = base.Q_t.middleCols(from, added);
      for (int pass = 0; pass < 2; ++pass) {
        const Eigen::VectorXd c = Qn.transpose() * Zt.col(i);
        Zt.col(i).noalias() -= Qn * c;
        coef.col(i).head(added) += c;
      }
    }
    const double rho = Zt.col(i).norm();
    if (rho > kExtensionRankTolerance * norm0(i) && base.q_t < base.Q_t.rows()) {
      base.Q_t.col(base.q_t++) = Zt.col(i) / rho;
      coef(added, i) = rho;
    }
  }
  return coef.topRows(base.q_t - from);
}

// Appends the columns of Zt to the thin QR Q_t R_t by classical Gram-Schmidt twice: the block
// against the columns Q_t had (two matrix products a pass), then each column against the ones the
// block added before it (append_each). R_t gains the columns [Q_t' Zt; R_block].
void append_to_thin_qr(Eigen::MatrixXd Zt, EstimateBase& base) {
  const Index old_q = base.q_t, b = Zt.cols(), n = base.R_t.cols();
  const Eigen::VectorXd norm0 = Zt.colwise().norm().transpose();
  Eigen::MatrixXd coef = Eigen::MatrixXd::Zero(old_q, b);
  if (old_q > 0) {
    const auto Q = base.Q_t.leftCols(old_q);
    for (int pass = 0; pass < 2; ++pass) {
      const Eigen::MatrixXd c = Q.transpose() * Zt;
      Zt.noalias() -= Q * c;
      coef += c;
    }
  }
  reserve_thin_q(base, std::min(Zt.rows(), old_q + b));
  const Eigen::MatrixXd block = append_each(Zt, norm0, base, old_q);
  const Index k = base.q_t;
  base.R_t.conservativeResize(k, n + b);
  base.R_t.bottomLeftCorner(k - old_q, n).setZero();
  base.R_t.block(0, n, old_q, b) = coef;
  base.R_t.block(old_q, n, k - old_q, b) = block;
}

// The split basis columns of an extension build: the base's columns of the reused basis vectors,
// then those of the new ones, computed and appended to the thin QR here.
void extend_split_columns(const EstimateInputs& in, EstimateBase& base) {
  const std::vector<int>& order = *in.extension_order;
  const Index n_free = ix(in.free_dofs->size()), kc = base.R_fixed.rows();
  const int Ja = static_cast<int>(in.terms->A.size()), N = static_cast<int>(order.size());
  if (base.extended > in.extension_reused || base.Q_t.rows() != n_free - kc) base.extended = 0;  // another basis
  if (base.extended == 0) {
    base.Z_fixed.resize(kc, 0);
    base.Q_t.resize(n_free - kc, 0);
    base.q_t = 0;
    base.R_t.resize(0, 0);
  }
  std::vector<int> column_of(sz(N), -1);  // growth index -> column of Theta
  for (int n = 0; n < N; ++n) column_of[sz(order[sz(n)])] = n;
  const int fresh = N - base.extended;
  if (fresh <= 0) return;
  Eigen::MatrixXd theta(n_free, fresh);
  for (int i = 0; i < fresh; ++i) theta.col(i) = in.Theta->col(column_of[sz(base.extended + i)]);
  EstimateInputs part = in;
  part.Theta = &theta;
  const Eigen::MatrixXd Z = split_against_fixed(base, whitened_basis_columns(part, base));  // column j fresh + i
  const Index first = base.Z_fixed.cols(), b = static_cast<Index>(Ja) * fresh;
  base.Z_fixed.conservativeResize(Eigen::NoChange, first + b);
  Eigen::MatrixXd Zt(n_free - kc, b);  // growth order: column J^a i + j
  for (int i = 0; i < fresh; ++i) {
    for (int j = 0; j < Ja; ++j) {
      const Index from = static_cast<Index>(j) * fresh + i, to = static_cast<Index>(Ja) * i + j;
      base.Z_fixed.col(first + to) = Z.col(from).head(kc);
      Zt.col(to) = Z.col(from).tail(n_free - kc);
    }
  }
  append_to_thin_qr(std::move(Zt), base);
  base.extended = N;
}

// whitened_residual_factor of an extension build: the same S up to an orthogonal factor on the
// left, its basis block from the base's split columns (growth order mapped to the layout's) and
// R_t in place of a new QR.
Eigen::MatrixXd extended_residual_factor(const EstimateInputs& in, EstimateBase& base, Index cols) {
  extend_split_columns(in, base);
  const std::vector<int>& order = *in.extension_order;
  const int Ja = static_cast<int>(in.terms->A.size()), N = static_cast<int>(order.size());
  const Index kc = base.R_fixed.rows(), kt = base.R_t.rows();
  const Index nf = base.n_fixed, nt = static_cast<Index>(Ja) * N, nc = base.R_fixed.cols() - nf;
  require(cols == nf + nt + nc, "build_estimate_data: inconsistent residual columns");
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(kc + kt, cols);
  S.topLeftCorner(kc, nf) = base.R_fixed.leftCols(nf);
  for (int j = 0; j < Ja; ++j) {
    for (int n = 0; n < N; ++n) {
      const Index internal = static_cast<Index>(Ja) * order[sz(n)] + j, layout = nf + static_cast<Index>(j) * N + n;
      S.col(layout).head(kc) = base.Z_fixed.col(internal);
      S.col(layout).tail(kt) = base.R_t.col(internal);
    }
  }
  S.topRightCorner(kc, nc) = base.R_fixed.rightCols(nc);
  return S;
}

// The residual factor of an extension build: T itself when it has no more rows than columns
// (|T y| is all the estimate needs; ErrorEstimator factors the columns it uses), else the
// rank-truncated R factor.
Eigen::MatrixXd unpivoted_factor(const Eigen::MatrixXd& T) { return T.rows() <= T.cols() ? T : residual_factor(T); }

}  // namespace

EstimateData build_estimate_data(const EstimateInputs& in) {
  require(in.terms && in.thetas && in.free_dofs && in.contact_dofs && in.Theta && in.Theta_c && in.Xi && in.Q_kappa &&
              in.Q_gamma && in.set && in.kept_rows && in.lift_c && in.weights_kept && in.kappa_magic &&
              in.B_kappa && in.gamma_magic && in.B_gamma && in.surface,
          "build_estimate_data: a required input is missing");
  const cases::AffineTerms& terms = *in.terms;
  const Eigen::MatrixXd& Theta = *in.Theta;
  const Eigen::MatrixXd& Xi = *in.Xi;
  const Index n_free = ix(in.free_dofs->size());
  const Index n_c = ix(in.contact_dofs->size());
  const Index R_kept = Xi.rows();
  const int Jf = static_cast<int>(terms.f.size()), Ja = static_cast<int>(terms.A.size());
  const int JD = static_cast<int>(terms.lift.size());
  const int N = static_cast<int>(Theta.cols()), R = static_cast<int>(Xi.cols());
  const int Mk = static_cast<int>(in.Q_kappa->cols());
  require(Theta.rows() == n_free && in.Theta_c->rows() == n_c && in.Theta_c->cols() == N &&
              in.Q_kappa->rows() == R_kept * n_c && in.Q_gamma->rows() == R_kept && Ja >= 1,
          "build_estimate_data: inconsistent sizes (Theta " + std::to_string(Theta.rows()) + " x " +
              std::to_string(N) + ", n_free " + std::to_string(n_free) + ", Q_kappa " +
              std::to_string(in.Q_kappa->rows()) + " rows for R_kept n_c = " + std::to_string(R_kept * n_c) + ")");
  EstimateBase own;
  EstimateBase& base = in.base ? *in.base : own;
  if (!base.factored) map_free_dofs(in, base);

  // The contact term -E_c' K' Xi lambda with K ~ sum_i phi_i Q_i (50): column (i, r) of C is
  // -(Q_i' Xi)_r.
  std::vector<Eigen::MatrixXd> Q(sz(Mk));
  Eigen::MatrixXd C(n_c, static_cast<Index>(Mk) * R);
  for (int i = 0; i < Mk; ++i) {
    Q[sz(i)] = unflatten_column(in.Q_kappa->col(i), R_kept, n_c);
    C.middleCols(static_cast<Index>(i) * R, R) = -(Q[sz(i)].transpose() * Xi);
  }
  const std::vector<int> exact_dofs = exact_contact_dofs(in, base.global_to_free);
  ensure_estimate_base(in, used_contact_dofs(exact_dofs, C, in, base.global_to_free), base);
  const std::vector<Index>& columns = base.contact_columns;
  const Index n_u = ix(columns.size());

  // The residual terms on the free DOFs, whitened by X's factor: ||r||_{X'}^2 = |L^-1 P r|^2. The
  // Mk R contact columns -E_c' Q_i' Xi_r all lie in the columns of E_c' of the contact DOFs they
  // touch: they are kept as E_c' times the rows of the small n_c x (Mk R) matrix C, so the factor
  // S has d0 + n_u columns, not d (d0 + Mk R: 5400 columns on hertz-3p, 16 s of unblocked pivoted
  // QR), n_u <= n_c the contact DOFs the estimate uses (the others' unit loads never enter).
  const Index d = residual_columns(Jf, Ja, JD, N, Mk, R);
  const Index d0 = d - static_cast<Index>(Mk) * R;
  const bool extension = in.extension_order != nullptr;
  require(!extension || ix(in.extension_order->size()) == N,
          "build_estimate_data: the extension order does not have N = " + std::to_string(N) + " entries");
  const Eigen::MatrixXd S = extension ? extended_residual_factor(in, base, d0 + n_u)
                                      : whitened_residual_factor(in, base, d0 + n_u);
  // W = [W0 | G] = Q0 [S0 | SG]; every residual column is Q0 times a column of T0 = [S0 | SG C],
  // so |W_full y| = |T0 y| with T0 of d0 + n_u rows at most.
  const Index k0 = S.rows();
  Eigen::MatrixXd C_used(n_u, C.cols());
  for (Index u = 0; u < n_u; ++u) C_used.row(u) = C.row(columns[sz(u)]);
  Eigen::MatrixXd T0(k0, d);
  T0.leftCols(d0) = S.leftCols(d0);
  T0.rightCols(d - d0) = S.rightCols(n_u) * C_used;

  EstimateData e;
  e.theta_a_reference = cases::evaluate(in.thetas->a, in.reference_mu);
  e.residual_T = extension ? unpivoted_factor(T0) : residual_factor(T0);  // W = Q R P': |W y| = |R P' y|
  // The exact contact rows' residual: the unit loads on exact_dofs are columns of S itself.
  e.exact_dofs = exact_dofs;
  Eigen::MatrixXd T1(k0, d0 + ix(e.exact_dofs.size()));
  T1.leftCols(d0) = S.leftCols(d0);
  for (std::size_t k = 0; k < e.exact_dofs.size(); ++k) {
    const auto at = std::lower_bound(columns.begin(), columns.end(), static_cast<Index>(e.exact_dofs[k]));
    require(at != columns.end() && *at == e.exact_dofs[k], "internal: an exact contact DOF has no estimate column");
    T1.col(d0 + ix(k)) = S.col(d0 + (at - columns.begin()));
  }
  e.residual_exact = extension ? unpivoted_factor(T1) : residual_factor(T1);
  for (int i = 0; i < Mk; ++i) e.QTheta_kappa.push_back(Q[sz(i)] * (*in.Theta_c));
  e.Q_gamma = *in.Q_gamma;
  calibrate_eim(in, base, e);
  return e;
}

}  // namespace contactrb::offline
