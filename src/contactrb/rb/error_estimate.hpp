#pragma once
// A posteriori error estimate of an online answer, from reduced quantities only, in the spirit
// of Haasdonk, Salomon, Wohlmuth (SINUM 2012) for variational inequalities: the dual norm of
// the primal residual (Riesz representers of the affine terms, offline), the constraint
// violation and the complementarity of the EIM-reconstructed constraints on the kept rows,
// combined into an estimate of the energy-norm error |u_hf - u_rb|_A(mu). Formulas, and which
// parts are bounded and which are estimated: docs/offline-online.md, "Error estimate".
//
// Offline (build_estimate_data): the residual terms on the free DOFs, whitened by the Cholesky
// factor of X = A_00(mu_ref), then one column-pivoted QR: ||r||_{X'} = |T y| with T the R factor
// (Buhr, Engwer, Ohlberger, Rave 2014: no sum of large terms of opposite signs online, so the
// accuracy floor is that of T y, about 1e-15 |T| |y|, not the square root of it).
// Online (ErrorEstimator): the coefficient vector y of the leading sizes (N, R, Mk), |T_sub y|
// with T_sub the R factor of the selected columns (computed once per size in setup), the EIM
// constraints on the kept rows, and the combination.
#include <Eigen/Core>
#include <vector>

#include "contactrb/cases/theta.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/rb/error_estimate_data.hpp"
#include "contactrb/rb/reduced_model.hpp"

namespace contactrb::cases {
struct AffineTerms;
}

namespace contactrb::rb {

// Columns of the column-pivoted QR whose pivot is below this fraction of the largest are dropped
// (their contribution to |T y| is below the rounding of the kept ones).
inline constexpr double kEstimateRankTolerance = 1e-13;

// Inputs of the offline construction (all borrowed).
struct EstimateInputs {
  const cases::AffineTerms* terms = nullptr;  // global A_j, f_j, lift_k of the reference mesh
  const cases::AffineThetas* thetas = nullptr;
  Eigen::VectorXd reference_mu;               // X = A_00(reference_mu)
  const std::vector<int>* free_dofs = nullptr;
  const std::vector<int>* contact_dofs = nullptr;  // global DOF of each contact-surface DOF
  const Eigen::MatrixXd* Theta = nullptr;          // n_free x N_max
  const Eigen::MatrixXd* Theta_c = nullptr;        // n_c x N_max
  const Eigen::MatrixXd* Xi = nullptr;             // R_kept x R_max
  const Eigen::MatrixXd* Q_kappa = nullptr;        // (R_kept n_c) x Mk_max, flattened row-major (eim_flatten.hpp)
  const Eigen::MatrixXd* Q_gamma = nullptr;        // R_kept x Mg_max
  // The EIM calibration on the training snapshots: magic points (flattened rows of the kappa
  // snapshot matrix, rows of gamma's), B matrices, the kept rows, the lift on the contact DOFs,
  // the row weights |I_r| on the kept rows.
  const io::SnapshotSet* set = nullptr;
  const std::vector<int>* kept_rows = nullptr;
  const Eigen::MatrixXd* lift_c = nullptr;         // n_c x J^D
  const Eigen::VectorXd* weights_kept = nullptr;   // R_kept
  const std::vector<int>* kappa_magic = nullptr;   // Mk_max
  const Eigen::MatrixXd* B_kappa = nullptr;
  const std::vector<int>* gamma_magic = nullptr;   // Mg_max
  const Eigen::MatrixXd* B_gamma = nullptr;
};

// Throws contactrb::Error for inconsistent sizes or an X that is not positive definite.
EstimateData build_estimate_data(const EstimateInputs& in);

// Throws contactrb::Error naming the first array of model.estimate whose shape disagrees with the
// model (an empty estimate is accepted: available() is then false).
void check_estimate_data(const ReducedModel& model);

// The online evaluation for one set of leading sizes. Not thread-safe (workspaces).
class ErrorEstimator {
 public:
  ErrorEstimator() = default;
  // Copies the leading blocks of model.estimate for (N, R, Mk, Mg) and factors the selected
  // residual columns. The model must have passed check_model.
  void setup(const ReducedModel& model, int N, int R, int Mk, int Mg);
  bool available() const { return available_; }

  // u_hat (N), lambda_hat (R), phi = (B^kappa)^-1 kappa_hat (Mk) and phi_gamma = (B^gamma)^-1
  // gamma_hat (Mg) of the linearization that produced (u_hat, lambda_hat), weight_kept = |I_r|(mu)
  // on the kept rows.
  ErrorEstimate evaluate(const Eigen::VectorXd& mu, const Eigen::VectorXd& u_hat, const Eigen::VectorXd& lambda_hat,
                         const Eigen::VectorXd& phi, const Eigen::VectorXd& phi_gamma,
                         const Eigen::VectorXd& weight_kept);

 private:
  bool available_ = false;
  int N_ = 0, R_ = 0, Mk_ = 0, Mg_ = 0;
  cases::AffineThetas thetas_;
  Eigen::VectorXd theta_ref_;
  Eigen::MatrixXd T_;        // rank x d: R factor of the selected columns of residual_T (pivoted)
  std::vector<Eigen::Index> perm_;  // column pivots: (P' y)(k) = y(perm_[k])
  Eigen::MatrixXd QTheta_;   // R_kept x (Mk N): column i N + n = (Q_i Theta_c)[:, n]
  Eigen::MatrixXd Q_gamma_;  // R_kept x Mg
  Eigen::MatrixXd Xi_;       // R_kept x R
  double eim_residual_ = 0.0, eim_slack_ = 0.0;  // the calibrated EIM terms at (Mk, Mg)
  Eigen::VectorXd y_, v_, phi_u_, s_, lam_;  // workspaces
};

}  // namespace contactrb::rb
