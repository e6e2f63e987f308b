#pragma once
// High-fidelity contact solver: Kacanov iterations (paper (12), (63)) around an exact
// non-negative QP in dual form. A(mu) is factorized once per solve; the inner QP matrix
// Q = K A^-1 K' is formed from the block S = (A_00^-1) restricted to the free DOFs of the
// two contact boundaries, computed once, so each iteration costs one back-solve plus
// small dense work.
//
// Lifting (DESIGN.md): u = u_D + u_0; the lift's contact term K u_D is moved into the gap:
// K_0 u_0 <= g - K u_D.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/hf/contact_problem.hpp"
#include "contactrb/solve/kacanov.hpp"
#include "contactrb/solve/nonnegative_qp.hpp"

namespace contactrb::hf {

struct HFSettings {
  solve::KacanovSettings kacanov;  // alpha = 0.3, eps_KA = 1e-3 (paper Section 6.2.2)
  solve::QPSettings qp;
};

// Relative KKT residuals of the returned (u, lambda) for the linearized problem it solves
// exactly (K, g frozen at the previous Kacanov iterate).
struct HFKKT {
  double stationarity = 0.0;     // |A_00 u_0 + K_0' lambda - b| / max(|b|, |K_0' lambda|)
  double primal = 0.0;           // max(0, max_r (K u - g)_r) / gap scale (max(|g|, max_r sum_j |K_rj u_j|))
  double dual = 0.0;             // max(0, -min lambda) / max(lambda)
  double complementarity = 0.0;  // max_r |lambda_r (g - K u)_r| / (max lambda * gap scale)
  double max() const;
};

struct HFSolution {
  bool converged = false;
  solve::KacanovStatus status = solve::KacanovStatus::StepFailed;
  std::string message;
  int iterations = 0;
  std::vector<solve::KacanovIteration> history;

  Eigen::VectorXd u;       // total displacement u_D + u_0 (num_dofs): last linearized solution
  Eigen::VectorXd u0;      // its free part (num_free)
  Eigen::VectorXd lambda;  // contact pressures, one per constraint row (R)
  contact::PointwiseContact pointwise;  // geometry the last step used (at the previous iterate)
  contact::ConstraintRows rows;         // K, g of that geometry (R x num_dofs)
  HFKKT kkt;
  double gap_violation = 0.0;  // max(0, k(u; u) - g(u)) pointwise, geometry re-evaluated at u
  double energy = 0.0;         // 1/2 u' A u - f' u (total displacement)
  double contact_force = 0.0;  // sum_r lambda_r |I_r|
  int active_constraints = 0;  // lambda_r > 0
  double time_s = 0.0;         // setup + iterations
};

class HFSolver {
 public:
  // Assembles A, f, the lift, the contact pair and quadrature; factorizes A_00.
  // Throws contactrb::Error for an invalid problem or a singular stiffness.
  explicit HFSolver(ContactProblem problem);
  ~HFSolver();
  HFSolver(HFSolver&&) noexcept;
  HFSolver& operator=(HFSolver&&) noexcept;

  HFSolution solve(const HFSettings& settings = {}) const;

  const ContactProblem& problem() const;
  const contact::ContactPair& pair() const;
  const contact::ContactQuadrature& quadrature() const;
  const fem::DofMap& dofs() const;
  const Eigen::SparseMatrix<double>& stiffness() const;  // global A (num_dofs^2)
  const Eigen::VectorXd& load() const;                    // global f
  double setup_time_s() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace contactrb::hf
