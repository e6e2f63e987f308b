#include "contactrb/rb/error_estimate.hpp"

#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/rb/eim_flatten.hpp"

namespace contactrb::rb {

namespace {
using Index = Eigen::Index;
inline Index ix(std::size_t i) { return static_cast<Index>(i); }
inline std::size_t sz(Index i) { return static_cast<std::size_t>(i); }

// Number of columns of residual_T for the given sizes (layout: error_estimate_data.hpp).
Index residual_columns(int Jf, int Ja, int JD, int N, int Mk, int R) {
  return ix(sz(Jf + Ja * JD + Ja * N)) + static_cast<Index>(Mk) * R;
}
}  // namespace

// The EIM errors on the training snapshots (EstimateData::eim_residual, eim_slack), for every
// leading size: I_M F = Q[:, :M] B[:M, :M]^-1 F(magic[:M]) (B lower triangular).
void calibrate_eim(const EstimateInputs& in, const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>>& llt,
                   const std::vector<Index>& global_to_free, EstimateData& e) {
  const Eigen::MatrixXd& Qk = *in.Q_kappa;
  const Eigen::MatrixXd& Qg = *in.Q_gamma;
  const int Mk = static_cast<int>(Qk.cols()), Mg = static_cast<int>(Qg.cols());
  const Index R_kept = Qg.rows();
  const Index n_c = ix(in.contact_dofs->size());
  const Index n_free = ix(in.free_dofs->size());
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
      const Index fi = global_to_free[sz((*in.contact_dofs)[sz(a)])];
      if (fi >= 0) u0_c(a) = snap.u0(fi);
    }
    const double lambda_norm = std::sqrt((w.array() * lambda.array().square()).sum());
    // Flattened row-major (eim_flatten.hpp): F(r n_c + n) = K(r, n).
    const Eigen::MatrixXd Kt = K.transpose();
    const Eigen::Map<const Eigen::VectorXd> F(Kt.data(), Kt.size());
    std::vector<Eigen::VectorXd> dKu(sz(Mk + 1));
    for (int M = 0; M <= Mk; ++M) {
      Eigen::VectorXd IF = Eigen::VectorXd::Zero(F.size());
      if (M > 0) {
        Eigen::VectorXd values(M);
        for (int i = 0; i < M; ++i) values(i) = F((*in.kappa_magic)[sz(i)]);
        IF = Qk.leftCols(M) * in.B_kappa->topLeftCorner(M, M).triangularView<Eigen::Lower>().solve(values);
      }
      const Eigen::VectorXd dF = F - IF;
      const Eigen::Map<const Eigen::MatrixXd> dKt(dF.data(), n_c, R_kept);  // (K - I_M K)'
      dKu[sz(M)] = dKt.transpose() * u0_c;
      if (lambda_norm > 0.0) {
        const Eigen::VectorXd c = dKt * lambda;  // (K - I_M K)' lambda on the contact DOFs
        Eigen::VectorXd v = Eigen::VectorXd::Zero(n_free);
        for (Index a = 0; a < n_c; ++a) {
          const Index fi = global_to_free[sz((*in.contact_dofs)[sz(a)])];
          if (fi >= 0) v(fi) = c(a);
        }
        Eigen::VectorXd pv = llt.permutationP() * v;
        llt.matrixL().solveInPlace(pv);
        e.eim_residual(M) = std::max(e.eim_residual(M), pv.norm() / lambda_norm);
      }
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

EstimateData build_estimate_data(const EstimateInputs& in) {
  require(in.terms && in.thetas && in.free_dofs && in.contact_dofs && in.Theta && in.Theta_c && in.Xi && in.Q_kappa &&
              in.Q_gamma && in.set && in.kept_rows && in.lift_c && in.weights_kept && in.kappa_magic &&
              in.B_kappa && in.gamma_magic && in.B_gamma,
          "build_estimate_data: a required input is missing");
  const cases::AffineTerms& terms = *in.terms;
  const std::vector<int>& free = *in.free_dofs;
  const Eigen::MatrixXd& Theta = *in.Theta;
  const Eigen::MatrixXd& Xi = *in.Xi;
  const Index n_free = ix(free.size());
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
  const Index num_dofs = terms.A.front().rows();
  std::vector<Index> global_to_free(sz(num_dofs), -1);
  for (std::size_t i = 0; i < free.size(); ++i) global_to_free[sz(free[i])] = ix(i);
  auto restrict_free = [&](const Eigen::VectorXd& g) {
    Eigen::VectorXd out(n_free);
    for (Index i = 0; i < n_free; ++i) out(i) = g(free[sz(i)]);
    return out;
  };

  // The residual terms (layout: error_estimate_data.hpp), on the free DOFs. The Mk R contact
  // columns -E_c' Q_i' Xi_r all lie in the n_c columns of E_c' (the contact DOFs): they are kept
  // as E_c' times the small n_c x (Mk R) matrix C, so the QR below factors n_free x (d0 + n_c),
  // not n_free x d (d0 + Mk R: 5400 columns on hertz-3p, 16 s of unblocked pivoted QR).
  const Index d = residual_columns(Jf, Ja, JD, N, Mk, R);
  const Index d0 = d - static_cast<Index>(Mk) * R;
  Eigen::MatrixXd terms_free(n_free, d0 + n_c);
  Index col = 0;
  for (int j = 0; j < Jf; ++j) terms_free.col(col++) = restrict_free(terms.f[sz(j)]);
  for (int j = 0; j < Ja; ++j) {
    for (int k = 0; k < JD; ++k) terms_free.col(col++) = -restrict_free(terms.A[sz(j)] * terms.lift[sz(k)]);
  }
  // A_j,00 Theta: A_j Theta extended by zero on the constrained DOFs, restricted to the free ones.
  Eigen::MatrixXd Theta_global = Eigen::MatrixXd::Zero(num_dofs, N);
  for (Index i = 0; i < n_free; ++i) Theta_global.row(free[sz(i)]) = Theta.row(i);
  for (int j = 0; j < Ja; ++j) {
    const Eigen::MatrixXd AT = terms.A[sz(j)] * Theta_global;
    for (int n = 0; n < N; ++n) terms_free.col(col++) = -restrict_free(AT.col(n));
  }
  // E_c': contact DOF a -> its free index (a constrained contact DOF has no column entry).
  terms_free.rightCols(n_c).setZero();
  for (Index a = 0; a < n_c; ++a) {
    const Index fi = global_to_free[sz((*in.contact_dofs)[sz(a)])];
    if (fi >= 0) terms_free(fi, d0 + a) = 1.0;
  }
  // The contact term -E_c' K' Xi lambda with K ~ sum_i phi_i Q_i (50): column (i, r) of C is
  // -(Q_i' Xi)_r.
  std::vector<Eigen::MatrixXd> Q(sz(Mk));
  Eigen::MatrixXd C(n_c, static_cast<Index>(Mk) * R);
  for (int i = 0; i < Mk; ++i) {
    Q[sz(i)] = unflatten_column(in.Q_kappa->col(i), R_kept, n_c);
    C.middleCols(static_cast<Index>(i) * R, R) = -(Q[sz(i)].transpose() * Xi);
  }

  // X = A_00(mu_ref) = P L L' P' (Eigen's convention: P X P' = L L'); ||r||_{X'}^2 = |L^-1 P r|^2.
  const fem::SparseMatrix A_ref = cases::combine(terms.A, cases::evaluate(in.thetas->a, in.reference_mu));
  Eigen::SparseMatrix<double> X(n_free, n_free);
  {
    std::vector<Eigen::Triplet<double>> trip;
    for (Index k = 0; k < A_ref.outerSize(); ++k) {
      for (fem::SparseMatrix::InnerIterator it(A_ref, k); it; ++it) {
        const Index r = global_to_free[sz(it.row())], c = global_to_free[sz(it.col())];
        if (r >= 0 && c >= 0) trip.emplace_back(r, c, it.value());
      }
    }
    X.setFromTriplets(trip.begin(), trip.end());
  }
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(X);
  require(llt.info() == Eigen::Success,
          "build_estimate_data: the energy product at the reference value is not positive definite");
  Eigen::MatrixXd W = llt.permutationP() * terms_free;
  llt.matrixL().solveInPlace(W);
  // W = [W0 | G] = Q0 [S0 | SG] (thin, unpivoted, blocked); then every residual column is
  // Q0 times a column of T0 = [S0 | SG C], so |W_full y| = |T0 y| with T0 of d0 + n_c rows at most.
  const Index k0 = std::min<Index>(n_free, d0 + n_c);
  Eigen::HouseholderQR<Eigen::MatrixXd> thin(W);
  const Eigen::MatrixXd S = thin.matrixQR().topRows(k0).triangularView<Eigen::Upper>();
  Eigen::MatrixXd T0(k0, d);
  T0.leftCols(d0) = S.leftCols(d0);
  T0.rightCols(d - d0) = S.rightCols(n_c) * C;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(T0);
  qr.setThreshold(kEstimateRankTolerance);
  const Index rank = std::max<Index>(1, std::min<Index>(qr.rank(), d));

  EstimateData e;
  e.theta_a_reference = cases::evaluate(in.thetas->a, in.reference_mu);
  const Eigen::MatrixXd Rtop = qr.matrixQR().topRows(rank).triangularView<Eigen::Upper>();
  e.residual_T = Rtop * qr.colsPermutation().transpose();  // W = Q R P': |W y| = |R P' y|
  for (int i = 0; i < Mk; ++i) e.QTheta_kappa.push_back(Q[sz(i)] * (*in.Theta_c));
  e.Q_gamma = *in.Q_gamma;
  calibrate_eim(in, llt, global_to_free, e);
  return e;
}

void check_estimate_data(const ReducedModel& m) {
  const EstimateData& e = m.estimate;
  if (e.residual_T.size() == 0 && e.QTheta_kappa.empty() && e.Q_gamma.size() == 0 && e.theta_a_reference.size() == 0) {
    return;  // no estimate
  }
  const Index d = residual_columns(m.J_f(), m.J_a(), m.J_lift(), m.N_max, m.Mk_max, m.R_max);
  auto fail = [](const std::string& what) { throw Error("reduced model: estimate array " + what); };
  if (e.theta_a_reference.size() != m.J_a()) fail("theta_a_reference has the wrong size");
  if (e.residual_T.cols() != d || e.residual_T.rows() < 1 || e.residual_T.rows() > d) {
    fail("residual_T is " + std::to_string(e.residual_T.rows()) + " x " + std::to_string(e.residual_T.cols()) +
         ", expected at most " + std::to_string(d) + " x " + std::to_string(d));
  }
  if (static_cast<int>(e.QTheta_kappa.size()) != m.Mk_max) fail("QTheta_kappa has the wrong count");
  for (const Eigen::MatrixXd& q : e.QTheta_kappa) {
    if (q.rows() != m.R_kept() || q.cols() != m.N_max) fail("QTheta_kappa has the wrong shape");
  }
  if (e.Q_gamma.rows() != m.R_kept() || e.Q_gamma.cols() != m.Mg_max) fail("Q_gamma has the wrong shape");
  if (e.eim_residual.size() != m.Mk_max + 1) fail("eim_residual has the wrong size");
  if (e.eim_slack.rows() != m.Mk_max + 1 || e.eim_slack.cols() != m.Mg_max + 1) fail("eim_slack has the wrong shape");
  if (!e.residual_T.allFinite()) fail("residual_T is not finite");
}

void ErrorEstimator::setup(const ReducedModel& m, int N, int R, int Mk, int Mg) {
  const EstimateData& e = m.estimate;
  available_ = e.residual_T.size() > 0;
  if (!available_) return;
  N_ = N;
  R_ = R;
  Mk_ = Mk;
  Mg_ = Mg;
  thetas_ = m.thetas;
  theta_ref_ = e.theta_a_reference;
  const int Jf = m.J_f(), Ja = m.J_a(), JD = m.J_lift();
  // The columns of the leading sizes, in the order y is filled by evaluate().
  std::vector<Index> sel;
  for (int j = 0; j < Jf + Ja * JD; ++j) sel.push_back(j);
  const Index u0 = Jf + Ja * JD;
  for (int j = 0; j < Ja; ++j) {
    for (int n = 0; n < N; ++n) sel.push_back(u0 + static_cast<Index>(j) * m.N_max + n);
  }
  const Index c0 = u0 + static_cast<Index>(Ja) * m.N_max;
  for (int i = 0; i < Mk; ++i) {
    for (int r = 0; r < R; ++r) sel.push_back(c0 + static_cast<Index>(i) * m.R_max + r);
  }
  const Index d = ix(sel.size());
  Eigen::MatrixXd Tsel(e.residual_T.rows(), d);
  for (Index k = 0; k < d; ++k) Tsel.col(k) = e.residual_T.col(sel[sz(k)]);
  // |Tsel y| = |R P' y| with Tsel P = Q R (column pivoting): only the rows of the numerical rank of
  // the selected terms are kept (the same tolerance as offline), so the online product is rank x d.
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Tsel);
  qr.setThreshold(kEstimateRankTolerance);
  const Index rows = std::max<Index>(1, std::min<Index>(qr.rank(), d));
  T_ = qr.matrixQR().topRows(rows).triangularView<Eigen::Upper>();
  perm_.resize(sz(d));
  for (Index k = 0; k < d; ++k) perm_[sz(k)] = qr.colsPermutation().indices()(k);
  QTheta_.resize(m.R_kept(), static_cast<Index>(Mk) * N);
  for (int i = 0; i < Mk; ++i) QTheta_.middleCols(static_cast<Index>(i) * N, N) = e.QTheta_kappa[sz(i)].leftCols(N);
  Q_gamma_ = e.Q_gamma.leftCols(Mg);
  Xi_ = m.Xi.leftCols(R);
  eim_residual_ = e.eim_residual(Mk);
  eim_slack_ = e.eim_slack(Mk, Mg);
  y_.resize(d);
  v_.resize(rows);
  phi_u_.resize(static_cast<Index>(Mk) * N);
  s_.resize(m.R_kept());
  lam_.resize(m.R_kept());
}

ErrorEstimate ErrorEstimator::evaluate(const Eigen::VectorXd& mu, const Eigen::VectorXd& u_hat, const Eigen::VectorXd& lambda_hat,
                                       const Eigen::VectorXd& phi, const Eigen::VectorXd& phi_gamma,
                                       const Eigen::VectorXd& weight_kept) {
  ErrorEstimate est;
  if (!available_) return est;
  require(u_hat.size() == N_ && lambda_hat.size() == R_ && phi.size() == Mk_ && phi_gamma.size() == Mg_ &&
              weight_kept.size() == s_.size(),
          "ErrorEstimator::evaluate: sizes disagree with the setup");
  const Eigen::VectorXd ta = cases::evaluate(thetas_.a, mu);
  const Eigen::VectorXd tf = cases::evaluate(thetas_.f, mu);
  const Eigen::VectorXd tl = cases::evaluate(thetas_.lift, mu);
  const Index Jf = tf.size(), Ja = ta.size(), JD = tl.size();
  // Coefficients of the residual terms (error_estimate_data.hpp).
  Index k = 0;
  for (Index j = 0; j < Jf; ++j) y_(k++) = tf(j);
  for (Index j = 0; j < Ja; ++j) {
    for (Index l = 0; l < JD; ++l) y_(k++) = ta(j) * tl(l);
  }
  for (Index j = 0; j < Ja; ++j) {
    y_.segment(k, N_) = ta(j) * u_hat;
    k += N_;
  }
  for (Index i = 0; i < Mk_; ++i) {
    y_.segment(k, R_) = phi(i) * lambda_hat;
    k += R_;
  }
  // v = R P' y, column by column over the non-zero coefficients: the contact coefficients
  // phi_i lambda_hat_r vanish for every inactive generator r (lambda_hat >= 0 is usually sparse).
  v_.setZero();
  const Index rows = T_.rows();
  for (Index c = 0; c < y_.size(); ++c) {
    const double yc = y_(perm_[sz(c)]);
    if (yc == 0.0) continue;
    const Index n = std::min(c + 1, rows);  // R is upper trapezoidal
    v_.head(n).noalias() += yc * T_.col(c).head(n);
  }
  est.residual = v_.norm();

  // alpha(mu) = min_j theta^a_j(mu) / theta^a_j(mu_ref): with A_j symmetric positive semi-definite
  // and positive thetas, v'A(mu)v = sum_j theta_j(mu) v'A_j v >= alpha sum_j theta_j(ref) v'A_j v.
  double alpha = std::numeric_limits<double>::infinity();
  for (Index j = 0; j < Ja; ++j) {
    const double ratio = theta_ref_(j) > 0.0 ? ta(j) / theta_ref_(j) : -1.0;
    alpha = std::min(alpha, ratio);
  }
  if (!(alpha > 0.0)) return est;  // the bound does not apply: no estimate (available stays false)
  est.coercivity = alpha;

  // Slack of the EIM constraints on the kept rows: s = gamma - K Theta_c u_hat, K ~ sum_i phi_i Q_i.
  for (Index i = 0; i < Mk_; ++i) phi_u_.segment(i * N_, N_) = phi(i) * u_hat;
  s_.noalias() = Q_gamma_ * phi_gamma;
  s_.noalias() -= QTheta_ * phi_u_;
  lam_.noalias() = Xi_ * lambda_hat;
  double viol2 = 0.0, lam2 = 0.0;
  for (Index r = 0; r < s_.size(); ++r) {
    const double w = weight_kept(r);
    const double neg = std::max(0.0, -s_(r));
    if (w > 0.0) viol2 += neg * neg / w;  // rows weighted by |I_r|: the L2(Gamma^c) dual norm
    lam2 += w * lam_(r) * lam_(r);
  }
  est.violation = std::sqrt(viol2);
  est.multiplier_norm = std::sqrt(lam2);
  est.complementarity = lam_.dot(s_);
  // The EIM's share (calibrated on the training snapshots): the residual with the HF contact map
  // differs by E_c' (K - I K)' lambda, the slack by (gamma - I gamma) - (K - I K) u_0,c.
  est.eim_residual = eim_residual_ * est.multiplier_norm;
  est.eim_slack = eim_slack_;
  // |e|_A^2 <= (|r|_X' / sqrt(alpha)) |e|_A + violation |lambda|_Lambda + complementarity, with
  // |lambda|_Lambda estimated by |lambda_rb|_Lambda: the positive root of the quadratic, as in HSW12.
  const double c1 = 0.5 * (est.residual + est.eim_residual) / std::sqrt(alpha);
  const double c2 = (est.violation + est.eim_slack) * est.multiplier_norm + std::max(0.0, est.complementarity);
  est.energy = c1 + std::sqrt(c1 * c1 + c2);
  est.available = true;
  return est;
}

}  // namespace contactrb::rb
