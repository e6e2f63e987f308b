#pragma once
// The online evaluation of the a posteriori error estimate (docs/offline-online.md, "Error
// estimate"), from the reduced arrays of ReducedModel::estimate (built offline by
// build_estimate_data, offline/error_estimate.hpp): the coefficient vector y of the leading sizes
// (N, R, Mk), |T_sub y| with T_sub the R factor of the selected columns (computed once per size in
// setup), the EIM constraints on the kept rows, and the combination.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "contactrb/cases/theta.hpp"
#include "contactrb/model/error_estimate_data.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/online/complementary_correction.hpp"

namespace contactrb::online {

// One online answer's estimate (OnlineSolution::estimate). The energy norm is |v|_A(mu) =
// sqrt(v' A(mu) v) on the free DOFs. What is bounded and what is estimated: docs/offline-online.md.
struct ErrorEstimate {
  bool available = false;        // false: the model holds no estimate data, or the solve failed
  double residual = 0.0;         // ||r(mu)||_{X'}: dual norm of the primal residual
  double coercivity = 0.0;       // alpha(mu) <= inf_v |v|_A(mu)^2 / |v|_X^2 (min-theta bound)
  double violation = 0.0;        // ||(K u - gamma)^+||_{Lambda'} on the kept rows (EIM K, gamma)
  double complementarity = 0.0;  // (Xi lambda_hat)' (gamma - K u), EIM K, gamma
  double multiplier_norm = 0.0;  // ||Xi lambda_hat||_Lambda, Lambda = L2(Gamma^c)
  double eim_residual = 0.0;     // eim_residual(Mk) ||Xi lambda_hat||_Lambda (estimated EIM part of the residual)
  double eim_slack = 0.0;        // eim_slack(Mk, Mg) (estimated EIM part of the violation, ~ violation)
  bool exact = false;            // from the HF contact rows (ContactRows::Exact): violation and
                                 // complementarity over every row, no EIM part
  double geometric = 0.0;        // eta, the geometric term (exact rows; EstimateData::geometric_ratio)
  double correction = 0.0;       // exact rows: |u~ - u_rb|_A(mu) bound of the complementary correction
                                 // (ComplementaryCorrection), 0 when the complementary bound is not used
  double energy = 0.0;           // Delta_u = (c1 + sqrt(c1^2 + (1 - eta) c2)) / (1 - eta), or the smaller
                                 // complementary bound: estimate of |u_hf - u_rb|_A(mu)
};

// Rows weighted by |I_r| (the L2(Gamma^c) norms, docs/offline-online.md, "Error estimate"):
// violation sqrt(sum_r (s_r^-)^2 / w_r), multiplier_norm sqrt(sum_r w_r lambda_r^2) and the
// complementarity lambda's, over the rows of `slack`, `lambda` and `weight`.
struct ConstraintMeasures {
  double violation = 0.0;
  double multiplier_norm = 0.0;
  double complementarity = 0.0;
};
ConstraintMeasures constraint_measures(const Eigen::VectorXd& slack, const Eigen::VectorXd& lambda,
                                       const Eigen::VectorXd& weight);

// Throws contactrb::Error naming the first array of model.estimate whose shape disagrees with the
// model (an empty estimate is accepted: available() is then false).
void check_estimate_data(const contactrb::model::ReducedModel& model);

// The online evaluation for one set of leading sizes. Not thread-safe (workspaces).
class ErrorEstimator {
 public:
  ErrorEstimator() = default;
  // Copies the leading blocks of model.estimate for (N, R, Mk, Mg) and factors the selected
  // residual columns of the exact-rows estimate; those of the EIM estimate are factored at the
  // first evaluate(). The model must have passed check_model.
  void setup(const contactrb::model::ReducedModel& model, int N, int R, int Mk, int Mg);
  bool available() const { return available_; }

  // u_hat (N), lambda_hat (R), phi = (B^kappa)^-1 kappa_hat (Mk) and phi_gamma = (B^gamma)^-1
  // gamma_hat (Mg) of the linearization that produced (u_hat, lambda_hat), weight_kept = |I_r|(mu)
  // on the kept rows.
  ErrorEstimate evaluate(const Eigen::VectorXd& mu, const Eigen::VectorXd& u_hat, const Eigen::VectorXd& lambda_hat,
                         const Eigen::VectorXd& phi, const Eigen::VectorXd& phi_gamma,
                         const Eigen::VectorXd& weight_kept);

  // The HF contact rows at the returned displacement w = u_D + Theta_c u_hat (ContactRows::Exact):
  // the contact load K(w)' Xi lambda_hat on the n_c contact DOFs and, over every row r with
  // s = g(w) - K(w) w and lambda = Xi lambda_hat (0 on the dropped rows), the violation
  // sqrt(sum (s_r^-)^2 / |I_r|), the complementarity lambda's and |lambda|_Lambda.
  struct ExactContact {
    Eigen::VectorXd load;
    double violation = 0.0;
    double complementarity = 0.0;
    double multiplier_norm = 0.0;
    const Eigen::VectorXd* slack = nullptr;   // s over every row
    const Eigen::VectorXd* lambda = nullptr;  // lambda over every row (0 on the dropped rows)
    // The rows K(w) (rows x n_c), formed on demand (only the complementary bound needs them);
    // callable while the displacement the contact was evaluated at lives.
    std::function<const ComplementaryCorrection::RowSparse&()> rows;
  };
  // The estimate with the exact contact term (EstimateData::residual_exact): no EIM part.
  // Unavailable when the model holds no exact data or the load reaches a DOF outside exact_dofs.
  // Where the violation term dominates, the complementary bound replaces Delta_u when smaller.
  ErrorEstimate evaluate_exact(const Eigen::VectorXd& mu, const Eigen::VectorXd& u_hat, const ExactContact& contact);

 private:
  // y's affine part (theta^f; theta^a theta^lift; theta^a u_hat) and the coercivity bound.
  Eigen::Index fill_affine(const Eigen::VectorXd& mu, const Eigen::VectorXd& u_hat, Eigen::VectorXd& y,
                           double& alpha) const;
  // Delta_u = c1 + sqrt(c1^2 + c2) of the parts of `est` (HSW12).
  static void combine(ErrorEstimate& est);
  // The complementary bound (docs/offline-online.md, "The complementary bound") in place of
  // est.energy when it is smaller.
  void complementary_bound(const Eigen::VectorXd& mu, const ExactContact& contact, ErrorEstimate& est);
  void setup_exact(const contactrb::model::ReducedModel& model, const std::vector<Eigen::Index>& affine);

  bool available_ = false;
  int N_ = 0, R_ = 0, Mk_ = 0, Mg_ = 0;
  cases::AffineThetas thetas_;
  Eigen::VectorXd theta_ref_;
  // rank x d: R factor of the selected columns of residual_T (pivoted); before the first
  // evaluate() (perm_ empty), those columns unfactored.
  Eigen::MatrixXd T_;
  std::vector<Eigen::Index> perm_;  // column pivots: (P' y)(k) = y(perm_[k])
  Eigen::MatrixXd QTheta_;   // R_kept x (Mk N): column i N + n = (Q_i Theta_c)[:, n]
  Eigen::MatrixXd Q_gamma_;  // R_kept x Mg
  Eigen::MatrixXd Xi_;       // R_kept x R
  double eim_residual_ = 0.0, eim_slack_ = 0.0;
  double geometric_ratio_ = 0.0;  // the calibrated EIM terms at (Mk, Mg)
  Eigen::VectorXd y_, v_, phi_u_, s_, lam_;  // workspaces
  bool exact_available_ = false;
  // rank x d_exact: R factor of the selected residual_exact columns; before the first
  // evaluate_exact() (perm_exact_ empty), those columns unfactored.
  Eigen::MatrixXd T_exact_;
  std::vector<Eigen::Index> perm_exact_;
  std::vector<int> exact_dofs_;            // contact DOF of each exact load column
  std::vector<char> is_exact_dof_;         // n_c flags
  Eigen::VectorXd y_exact_, v_exact_;
  Eigen::VectorXd yp_;  // P' y (pivoted_norm)
  ComplementaryCorrection correction_;
};

}  // namespace contactrb::online
