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
  if (e.residual_exact.size() == 0 && e.exact_dofs.empty()) return;  // no exact-rows estimate
  int previous = -1;
  for (int a : e.exact_dofs) {
    if (a <= previous || a >= m.surface.num_dofs()) fail("exact_dofs is not increasing within the contact DOFs");
    previous = a;
  }
  const Index d_exact =
      model::exact_residual_columns(m.J_f(), m.J_a(), m.J_lift(), m.N_max, static_cast<int>(e.exact_dofs.size()));
  if (e.residual_exact.cols() != d_exact || e.residual_exact.rows() < 1 || e.residual_exact.rows() > d_exact) {
    fail("residual_exact is " + std::to_string(e.residual_exact.rows()) + " x " +
         std::to_string(e.residual_exact.cols()) + ", expected at most " + std::to_string(d_exact) + " x " +
         std::to_string(d_exact));
  }
  if (!e.residual_exact.allFinite()) fail("residual_exact is not finite");
}

namespace {
// The columns `sel` of T.
Eigen::MatrixXd selected_columns(const Eigen::MatrixXd& T, const std::vector<Index>& sel) {
  Eigen::MatrixXd Tsel(T.rows(), ix(sel.size()));
  for (Index k = 0; k < Tsel.cols(); ++k) Tsel.col(k) = T.col(sel[sz(k)]);
  return Tsel;
}

// |Tsel y| = |R P' y| with Tsel P = Q R (column pivoting): only the rows of the numerical rank of
// the selected terms are kept (the same tolerance as offline), so the online product is rank x d.
void factor_selected(const Eigen::MatrixXd& Tsel, Eigen::MatrixXd& R, std::vector<Index>& perm) {
  const Index d = Tsel.cols();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Tsel);
  qr.setThreshold(kEstimateRankTolerance);
  const Index rows = std::max<Index>(1, std::min<Index>(qr.rank(), d));
  R = qr.matrixQR().topRows(rows).triangularView<Eigen::Upper>();
  perm.resize(sz(d));
  for (Index k = 0; k < d; ++k) perm[sz(k)] = qr.colsPermutation().indices()(k);
}

// |R P' y| for R upper trapezoidal: over the non-zero coefficients of y only when they are few
// (the EIM estimate's contact coefficients phi_i lambda_hat_r vanish for every inactive generator);
// otherwise by a triangular and a dense product (yp: workspace), which run about 1.4 times faster
// than the column updates (measured on the exact-rows estimate, 109 x 180, most of y non-zero).
double pivoted_norm(const Eigen::MatrixXd& R, const std::vector<Index>& perm, const Eigen::VectorXd& y,
                    Eigen::VectorXd& yp, Eigen::VectorXd& v) {
  const Index rows = R.rows(), d = y.size();
  if (2 * (y.array() != 0.0).count() > d) {
    yp.resize(d);
    for (Index c = 0; c < d; ++c) yp(c) = y(perm[sz(c)]);
    const Index square = std::min(rows, d);
    v.noalias() = R.leftCols(square).triangularView<Eigen::Upper>() * yp.head(square);
    if (d > square) v.noalias() += R.rightCols(d - square) * yp.tail(d - square);
    return v.norm();
  }
  v.setZero(rows);
  for (Index c = 0; c < y.size(); ++c) {
    const double yc = y(perm[sz(c)]);
    if (yc == 0.0) continue;
    const Index n = std::min(c + 1, rows);
    v.head(n).noalias() += yc * R.col(c).head(n);
  }
  return v.norm();
}
}  // namespace

ConstraintMeasures constraint_measures(const Eigen::VectorXd& slack, const Eigen::VectorXd& lambda,
                                       const Eigen::VectorXd& weight) {
  double viol2 = 0.0, lam2 = 0.0;
  for (Index r = 0; r < slack.size(); ++r) {
    const double w = weight(r);
    const double neg = std::max(0.0, -slack(r));
    if (w > 0.0) viol2 += neg * neg / w;  // the L2(Gamma^c) dual norm of the violation
    lam2 += w * lambda(r) * lambda(r);
  }
  return {std::sqrt(viol2), std::sqrt(lam2), lambda.dot(slack)};
}

void ErrorEstimator::setup_exact(const ReducedModel& m, const std::vector<Index>& affine) {
  const EstimateData& e = m.estimate;
  exact_dofs_ = e.exact_dofs;
  is_exact_dof_.assign(sz(m.surface.num_dofs()), 0);
  for (int a : exact_dofs_) is_exact_dof_[sz(a)] = 1;
  exact_available_ = e.residual_exact.size() > 0;
  if (!exact_available_) return;
  // Columns: the affine ones of the leading N (their positions in residual_exact are those of
  // residual_T, whose affine block has the same layout), then every exact load column.
  std::vector<Index> sel = affine;
  const Index first_load = ix(m.J_f() + m.J_a() * m.J_lift() + m.J_a() * m.N_max);
  for (std::size_t k = 0; k < exact_dofs_.size(); ++k) sel.push_back(first_load + ix(k));
  // Factored at the first evaluate_exact(), as T_ at the first evaluate(): a solver that gives no
  // estimate (the training-value solves of an offline build) never needs it.
  T_exact_ = selected_columns(e.residual_exact, sel);
  perm_exact_.clear();
  y_exact_.resize(ix(sel.size()));
  correction_.setup(e.residual_exact.middleCols(first_load, ix(exact_dofs_.size())), exact_dofs_,
                    m.surface.num_dofs());
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
  const std::vector<Index> affine(sel.begin(), sel.begin() + (u0 + static_cast<Index>(Ja) * N));
  // Factored at the first evaluate(): a solve on the exact rows (evaluate_exact) never needs it,
  // and the factor costs about as much as ten such solves (N 48, Mk 33, R 15: 595 columns).
  T_ = selected_columns(e.residual_T, sel);
  perm_.clear();
  const Index d = ix(sel.size());
  setup_exact(m, affine);
  QTheta_.resize(m.R_kept(), static_cast<Index>(Mk) * N);
  for (int i = 0; i < Mk; ++i) QTheta_.middleCols(static_cast<Index>(i) * N, N) = e.QTheta_kappa[sz(i)].leftCols(N);
  Q_gamma_ = e.Q_gamma.leftCols(Mg);
  Xi_ = m.Xi.leftCols(R);
  eim_residual_ = e.eim_residual(Mk);
  eim_slack_ = e.eim_slack(Mk, Mg);
  geometric_ratio_ = e.geometric_ratio;
  y_.resize(d);
  phi_u_.resize(static_cast<Index>(Mk) * N);
  s_.resize(m.R_kept());
  lam_.resize(m.R_kept());
}

Index ErrorEstimator::fill_affine(const Eigen::VectorXd& mu, const Eigen::VectorXd& u_hat, Eigen::VectorXd& y,
                                  double& alpha) const {
  const Eigen::VectorXd ta = cases::evaluate(thetas_.a, mu);
  const Eigen::VectorXd tf = cases::evaluate(thetas_.f, mu);
  const Eigen::VectorXd tl = cases::evaluate(thetas_.lift, mu);
  const Index Jf = tf.size(), Ja = ta.size(), JD = tl.size();
  // Coefficients of the residual terms (model/error_estimate_data.hpp).
  Index k = 0;
  for (Index j = 0; j < Jf; ++j) y(k++) = tf(j);
  for (Index j = 0; j < Ja; ++j) {
    for (Index l = 0; l < JD; ++l) y(k++) = ta(j) * tl(l);
  }
  for (Index j = 0; j < Ja; ++j) {
    y.segment(k, N_) = ta(j) * u_hat;
    k += N_;
  }
  // alpha(mu) = min_j theta^a_j(mu) / theta^a_j(mu_ref): with A_j symmetric positive semi-definite
  // and positive thetas, v'A(mu)v = sum_j theta_j(mu) v'A_j v >= alpha sum_j theta_j(ref) v'A_j v.
  alpha = std::numeric_limits<double>::infinity();
  for (Index j = 0; j < Ja; ++j) {
    const double ratio = theta_ref_(j) > 0.0 ? ta(j) / theta_ref_(j) : -1.0;
    alpha = std::min(alpha, ratio);
  }
  return k;
}

void ErrorEstimator::combine(ErrorEstimate& est) {
  // |e|_A^2 <= (|r|_X' / sqrt(alpha)) |e|_A + violation |lambda|_Lambda + complementarity, with
  // |lambda|_Lambda estimated by |lambda_rb|_Lambda: the positive root of the quadratic, as in HSW12.
  // With the geometric term (offline/geometric_term.hpp) the left side is (1 - eta)|e|_A^2.
  const double c1 = 0.5 * (est.residual + est.eim_residual) / std::sqrt(est.coercivity);
  const double c2 = (est.violation + est.eim_slack) * est.multiplier_norm + std::max(0.0, est.complementarity);
  const double keep = 1.0 - est.geometric;
  if (!(keep > 0.0)) return;  // the elastic energy does not bound the contact forces' work: no estimate
  est.energy = (c1 + std::sqrt(c1 * c1 + keep * c2)) / keep;
  est.available = true;
}

ErrorEstimate ErrorEstimator::evaluate(const Eigen::VectorXd& mu, const Eigen::VectorXd& u_hat, const Eigen::VectorXd& lambda_hat,
                                       const Eigen::VectorXd& phi, const Eigen::VectorXd& phi_gamma,
                                       const Eigen::VectorXd& weight_kept) {
  ErrorEstimate est;
  if (!available_) return est;
  require(u_hat.size() == N_ && lambda_hat.size() == R_ && phi.size() == Mk_ && phi_gamma.size() == Mg_ &&
              weight_kept.size() == s_.size(),
          "ErrorEstimator::evaluate: sizes disagree with the setup");
  if (perm_.empty()) {  // T_ holds the selected columns, not yet their factor (setup)
    const Eigen::MatrixXd selected = std::move(T_);
    factor_selected(selected, T_, perm_);
    v_.resize(T_.rows());
  }
  double alpha = 0.0;
  Index k = fill_affine(mu, u_hat, y_, alpha);
  for (Index i = 0; i < Mk_; ++i) {
    y_.segment(k, R_) = phi(i) * lambda_hat;
    k += R_;
  }
  // The contact coefficients phi_i lambda_hat_r vanish for every inactive generator r
  // (lambda_hat >= 0 is usually sparse): pivoted_norm skips them.
  est.residual = pivoted_norm(T_, perm_, y_, yp_, v_);
  if (!(alpha > 0.0)) return est;  // the bound does not apply: no estimate (available stays false)
  est.coercivity = alpha;

  // Slack of the EIM constraints on the kept rows: s = gamma - K Theta_c u_hat, K ~ sum_i phi_i Q_i.
  for (Index i = 0; i < Mk_; ++i) phi_u_.segment(i * N_, N_) = phi(i) * u_hat;
  s_.noalias() = Q_gamma_ * phi_gamma;
  s_.noalias() -= QTheta_ * phi_u_;
  lam_.noalias() = Xi_ * lambda_hat;
  const ConstraintMeasures c = constraint_measures(s_, lam_, weight_kept);
  est.violation = c.violation;
  est.multiplier_norm = c.multiplier_norm;
  est.complementarity = c.complementarity;
  // The EIM's share (calibrated on the training snapshots): the residual with the HF contact map
  // differs by E_c' (K - I K)' lambda, the slack by (gamma - I gamma) - (K - I K) u_0,c.
  est.eim_residual = eim_residual_ * est.multiplier_norm;
  est.eim_slack = eim_slack_;
  combine(est);
  return est;
}

ErrorEstimate ErrorEstimator::evaluate_exact(const Eigen::VectorXd& mu, const Eigen::VectorXd& u_hat,
                                             const ExactContact& contact) {
  ErrorEstimate est;
  est.exact = true;
  if (!available_ || !exact_available_) return est;
  require(u_hat.size() == N_ && contact.load.size() == ix(is_exact_dof_.size()),
          "ErrorEstimator::evaluate_exact: sizes disagree with the setup");
  for (Index a = 0; a < contact.load.size(); ++a) {
    if (contact.load(a) != 0.0 && !is_exact_dof_[sz(a)]) return est;  // a load the model cannot measure
  }
  if (perm_exact_.empty()) {  // T_exact_ holds the selected columns, not yet their factor (setup_exact)
    const Eigen::MatrixXd selected = std::move(T_exact_);
    factor_selected(selected, T_exact_, perm_exact_);
  }
  double alpha = 0.0;
  const Index k = fill_affine(mu, u_hat, y_exact_, alpha);
  // The residual's contact term is -E_c' K' Xi lambda_hat: coefficient -load_a on column e_a.
  for (std::size_t i = 0; i < exact_dofs_.size(); ++i) y_exact_(k + ix(i)) = -contact.load(exact_dofs_[i]);
  est.residual = pivoted_norm(T_exact_, perm_exact_, y_exact_, yp_, v_exact_);
  if (!(alpha > 0.0)) return est;
  est.coercivity = alpha;
  est.violation = contact.violation;
  est.complementarity = contact.complementarity;
  est.multiplier_norm = contact.multiplier_norm;
  est.geometric = geometric_ratio_;
  combine(est);
  if (est.available) complementary_bound(mu, contact, est);
  return est;
}

void ErrorEstimator::complementary_bound(const Eigen::VectorXd& mu, const ExactContact& contact, ErrorEstimate& est) {
  const double keep = 1.0 - est.geometric;
  const double c1 = 0.5 * est.residual / std::sqrt(est.coercivity);
  const double c2 = est.violation * est.multiplier_norm + std::max(0.0, est.complementarity);
  if (!(keep * c2 > c1 * c1) || !contact.rows || !contact.slack || !contact.lambda) return;  // no floor to remove
  // A(mu) = sum_j theta_j A_j against X = sum_j theta_j^ref A_j: alpha X <= A(mu) <= beta X, and the
  // correction is scaled by t = sqrt(alpha beta) (exact when every theta_j / theta_j^ref is t).
  const Eigen::VectorXd ta = cases::evaluate(thetas_.a, mu);
  double alpha = std::numeric_limits<double>::infinity(), beta = 0.0;
  for (Index j = 0; j < ta.size(); ++j) {
    alpha = std::min(alpha, ta(j) / theta_ref_(j));
    beta = std::max(beta, ta(j) / theta_ref_(j));
  }
  const double t = std::sqrt(alpha * beta);
  const ComplementaryCorrection::Result c = correction_.evaluate(contact.rows(), *contact.slack, *contact.lambda, t);
  if (!c.available) return;
  // |(A(mu)/t - X) v|_A(mu)^-1 <= sum_j |theta_j / t - theta_j^ref| |v|_{A_j} / sqrt(theta_j)
  //                            <= mismatch |v|_X.
  double mismatch = 0.0;
  for (Index j = 0; j < ta.size(); ++j) {
    mismatch += std::abs(ta(j) / t - theta_ref_(j)) / std::sqrt(ta(j) * theta_ref_(j));
  }
  // |e| <= |v / t|_A(mu) + |u_hf - u~|_A(mu), and (1 - eta) |u_hf - u~|_A(mu) <= |r~|_A(mu)^-1 for
  // the complementary pair (u~, lambda~).
  const double correction = std::sqrt(beta) / t * c.v_norm;
  const double bound = correction + (est.residual / std::sqrt(est.coercivity) + mismatch * c.v_norm) / keep;
  if (bound < est.energy) {
    est.energy = bound;
    est.correction = correction;
  }
}

}  // namespace contactrb::online
