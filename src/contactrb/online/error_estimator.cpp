#include "contactrb/online/error_estimator.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/common/index_cast.hpp"

namespace contactrb::online {

using model::EstimateData;
using model::ReducedModel;
using model::kEstimateRankTolerance;
using model::residual_columns;

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
  // Coefficients of the residual terms (model/error_estimate_data.hpp).
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

}  // namespace contactrb::online
