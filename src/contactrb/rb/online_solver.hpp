#pragma once
// The online stage (Evaluation, in rbOOmit's terms): paper Algorithm 1, the reduced Kacanov
// iteration on (53). Per mu: A_hat(mu), f_hat(mu) from (49); per iteration: kappa_hat and
// gamma_hat at the EIM magic points from the contact-surface data only (the chain nodes mapped
// to Omega(mu), the displacement u_D,c(mu) + Theta_c u_hat on the contact DOFs), D^kappa (54),
// the reduced non-negative QP in dual form, u_hat = A_hat^-1 (f_hat - D' lambda_hat).
// Nothing of HF size is touched. Sizes N <= N_max, R <= R_max, Mk <= Mk_max, Mg <= Mg_max use
// the leading sub-blocks of the model's arrays.
//
// Magic-point evaluation: collocation and LAC-Simpson rows are weighted sums of pointwise rows
// of a few slave nodes, so only the slave nodes under the magic rows are projected (the
// "restricted operator"; the deformed master polyline is still built whole, O(master nodes)).
// Exactly integrated LAC rows need the whole slave chain: every row of the contact-surface
// mesh is recomputed and the magic entries are picked (docs/offline-online.md).
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/mesh/mesh.hpp"
#include "contactrb/rb/reduced_model.hpp"
#include "contactrb/solve/kacanov.hpp"
#include "contactrb/solve/nonnegative_qp.hpp"

namespace contactrb::rb {

// -1: the model's maximum.
struct OnlineSizes {
  int N = -1;
  int R = -1;
  int Mk = -1;
  int Mg = -1;
};

struct OnlineSettings {
  // Empty: the Kacanov settings of the HF snapshots the model was built from.
  std::optional<solve::KacanovSettings> kacanov;
  solve::QPSettings qp;
  // false: recompute every row of the contact-surface mesh (the reference path of the tests).
  bool restricted_rows = true;
};

struct OnlineSolution {
  solve::KacanovStatus status = solve::KacanovStatus::StepFailed;
  std::string message;  // why it stopped, when not converged
  int iterations = 0;
  Eigen::VectorXd u_hat;       // last linearized solution (as the HF solver returns)
  Eigen::VectorXd lambda_hat;  // >= 0
  double energy = 0.0;         // 1/2 u'A(mu)u - f(mu)'u of u = u_D(mu) + Theta u_hat (exact: (49) + lift terms)
  double contact_force = 0.0;  // sum_r |I_r|(mu) (Xi lambda_hat)_r
  double time_s = 0.0;
  bool converged() const { return status == solve::KacanovStatus::Converged; }
};

class OnlineSolver {
 public:
  // Borrows nothing: copies the leading blocks. Throws contactrb::Error for an inconsistent
  // model or sizes outside [1, max] (R, Mk, Mg may be 0 only when their maximum is 0).
  explicit OnlineSolver(const ReducedModel& model, const OnlineSizes& sizes = {});

  // Throws contactrb::Error for mu outside the parameter domain or invalid settings;
  // non-convergence is a status.
  OnlineSolution solve(double mu, const OnlineSettings& settings = {});

  int N() const { return N_; }
  int R() const { return R_; }
  int Mk() const { return Mk_; }
  int Mg() const { return Mg_; }

 private:
  // Contact-surface mesh at mu (chain nodes only, no triangles) and the EIM values at the
  // magic points for the contact-DOF displacement w.
  void evaluate_magic(const Eigen::VectorXd& w, const Eigen::VectorXd& lift_c, Eigen::VectorXd& kappa_hat,
                      Eigen::VectorXd& gamma_hat) const;
  void evaluate_magic_restricted(const Eigen::VectorXd& w, const Eigen::VectorXd& lift_c, Eigen::VectorXd& kappa_hat,
                                 Eigen::VectorXd& gamma_hat) const;
  // For the restricted evaluation at the current mu: the slave nodes under the magic rows.
  void prepare_restriction();

  int N_ = 0, R_ = 0, Mk_ = 0, Mg_ = 0;
  cases::ParameterSpec parameter_;
  cases::AffineThetas thetas_;
  double kacanov_alpha_ = 0.3, kacanov_tolerance_ = 1e-3;
  int kacanov_max_iterations_ = 500;
  std::vector<Eigen::MatrixXd> A_hat_;
  std::vector<Eigen::VectorXd> f_hat_, A_lift_hat_;
  std::vector<double> lift_AA_, lift_f_;
  std::vector<Eigen::MatrixXd> C_;       // Mk of R x N
  Eigen::PartialPivLU<Eigen::MatrixXd> B_kappa_lu_, B_gamma_lu_;  // leading blocks (Remark 4)
  Eigen::MatrixXd XiQ_gamma_;            // R x Mg
  Eigen::MatrixXd Xi_;                   // R_kept x R
  std::vector<int> kept_rows_;
  std::vector<int> kappa_row_, kappa_dof_, gamma_row_;  // constraint rows (R_hf numbering), DOFs
  ContactSurface surface_;
  Eigen::MatrixXd Theta_c_;              // n_c x N
  Eigen::MatrixXd lift_c_;               // n_c x J^D
  mesh::Mesh mesh_;                      // contact nodes in Omega(mu) (positions set per solve)
  contact::ContactPair pair_;
  contact::ContactQuadrature quadrature_;
  std::vector<int> needed_rows_;          // union of the magic rows (R_hf numbering), increasing
  contact::ContactPair restricted_pair_;  // slave = the slave nodes those rows weigh, master = all
  std::vector<int> restricted_slave_position_;  // positions in the slave chain, increasing
  solve::NonnegativeQPSolver qp_;
};

}  // namespace contactrb::rb
