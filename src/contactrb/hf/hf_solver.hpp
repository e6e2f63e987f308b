#pragma once
// High-fidelity contact solver in 2D and 3D (BasicHFSolver<Dim>), two methods (HFMethod):
//  - Newton: semi-smooth Newton / primal-dual active set with the geometry linearized
//    consistently; each Newton system reduced exactly to the contact DOFs of the active rows
//    on one Cholesky of A_00 per solve, or (NewtonLinearSolver::Amg, large 3D meshes) the whole
//    system by AMG-preconditioned GMRES (semismooth_newton.hpp; docs/solvers.md "Semi-smooth Newton");
//  - Kacanov: the paper's iterations (12), (63) around an exact non-negative QP in dual form.
// Kacanov: A(mu) is factorized once per solve; the inner QP matrix
// Q = K A^-1 K' is formed from the block S = (A_00^-1) restricted to the free DOFs of the
// two contact boundaries, computed once, so each iteration costs one back-solve plus
// small dense work.
//
// Lifting (DESIGN.md): u = u_D + u_0; the lift's contact term K u_D is moved into the gap:
// K_0 u_0 <= g - K u_D.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/hf/contact_problem.hpp"
#include "contactrb/hf/semismooth_newton.hpp"
#include "contactrb/solve/kacanov.hpp"
#include "contactrb/solve/nonnegative_qp.hpp"
#include "contactrb/solve/selected_inverse.hpp"

namespace contactrb::hf {

enum class HFMethod { Newton, Kacanov };
const char* to_string(HFMethod method);
HFMethod hf_method_from_string(const std::string& name);  // "newton" | "kacanov"
// The faster method for a mesh when none is asked for (docs/solvers.md, "Which solver for
// snapshots"): Newton, 1.5-7x faster per solve from mesh level 1 in 2D and at every level in 3D;
// Kacanov on the paper's 2D meshes (level 0), where Newton saves 2-3 ms per solve and the paper's
// tables are Kacanov solves.
HFMethod default_method(int dimension, int level);

struct HFSettings {
  solve::KacanovSettings kacanov;  // alpha = 0.3, eps_KA = 1e-3 (paper Section 6.2.2)
  solve::QPSettings qp;
  NewtonSettings newton;           // tolerance 1e-10 on HFKKT::max()
  HFMethod method = HFMethod::Kacanov;
};

// A starting point (warm start, e.g. the solution at a nearby mu): the total displacement
// (num_dofs; its prescribed entries are ignored, the lift of this problem is used) and the
// multipliers (R). Empty vectors: the cold start u = u_D, lambda = 0.
struct HFInitialGuess {
  Eigen::VectorXd u;
  Eigen::VectorXd lambda;
};

// Relative KKT residuals of the returned (u, lambda). Kacanov: for the linearized problem it
// solves exactly (K, g frozen at the previous Kacanov iterate). Newton: for the nonlinear
// problem (K, g at the returned u).
struct HFKKT {
  double stationarity = 0.0;     // |A_00 u_0 + K_0' lambda - b| / max(|b|, |K_0' lambda|)
  double primal = 0.0;           // max(0, max_r (K u - g)_r) / gap scale (max(|g|, max_r sum_j |K_rj u_j|))
  // Multiplier scale: max |lambda|, floored by the rounding of the forces the multipliers balance;
  // multipliers within the floor count as zero (hf/multiplier_scale.hpp).
  double dual = 0.0;             // max(0, -min lambda) / multiplier scale
  double complementarity = 0.0;  // max_r |lambda_r (g - K u)_r| / (multiplier scale * gap scale)
  double max() const;
};

template <int Dim>
struct BasicHFSolution {
  bool converged = false;
  HFMethod method = HFMethod::Kacanov;
  solve::KacanovStatus status = solve::KacanovStatus::StepFailed;  // the status of either method
  std::string message;
  int iterations = 0;
  std::vector<solve::KacanovIteration> history;        // Kacanov
  std::vector<NewtonIteration> newton_history;         // Newton
  NewtonTimings newton_timings;                        // Newton: the once-per-solve work

  Eigen::VectorXd u;       // total displacement u_D + u_0 (num_dofs): last linearized solution
  Eigen::VectorXd u0;      // its free part (num_free)
  Eigen::VectorXd lambda;  // contact pressures, one per constraint row (R)
  contact::PointwiseContactOf<Dim> pointwise;  // geometry the last step used (at the previous iterate)
  contact::ConstraintRows rows;         // K, g of that geometry (R x num_dofs)
  HFKKT kkt;
  double gap_violation = 0.0;  // max(0, k(u; u) - g(u)) pointwise, geometry re-evaluated at u
  double energy = 0.0;         // 1/2 u' A u - f' u (total displacement)
  double contact_force = 0.0;  // sum_r lambda_r |I_r|
  int active_constraints = 0;  // lambda_r > 0
  double time_s = 0.0;         // setup + iterations
};
using HFSolution = BasicHFSolution<2>;
using HFSolution3 = BasicHFSolution<3>;

// What the constructor prepares for the solves to come. newton_analysis: the fill-reducing
// ordering and symbolic analysis of A_00 for the Newton solver (ActiveSchur) run on a second
// thread while the constructor assembles, from the mesh's pattern alone (solve::FactorAnalysis);
// a Newton solve with that ordering then starts at the numeric factorization, with the same
// factor bitwise (tests/hf/test_hf_solver.cpp). Why: docs/performance.md, "Why the defaults are what they are",
// "Analysis beside the assembly".
struct HFSetupOptions {
  bool newton_analysis = false;
  solve::FactorOrdering ordering = solve::FactorOrdering::Auto;  // NewtonSettings::ordering
  // NewtonLinearSolver::Auto: no analysis where the solve will take Amg (resolved_linear_solver
  // with this threshold; -1: analyse).
  int amg_from_free_dofs = -1;
  // A Newton solve (ActiveSchur) leaves its factor of A_00 with the solver, for
  // held_inverse_block (NewtonSettings::keep_factor); off: the factor goes with the solve.
  bool keep_newton_factor = false;
};
// newton_analysis for a Newton ActiveSchur (or Auto) method, with its ordering; off for Kacanov.
HFSetupOptions setup_options_for(const HFSettings& settings);

// Dim = 2 (HFSolver) or 3 (HFSolver3): one code path, the contact geometry of the dimension
// (docs/solvers.md, "Three dimensions").
template <int Dim>
class BasicHFSolver {
 public:
  using Problem = BasicContactProblem<Dim>;
  using Solution = BasicHFSolution<Dim>;
  // Assembles A, f, the lift, the contact pair and quadrature; factorizes A_00.
  // Throws contactrb::Error for an invalid problem or a singular stiffness.
  explicit BasicHFSolver(Problem problem, const HFSetupOptions& options = {});
  ~BasicHFSolver();
  BasicHFSolver(BasicHFSolver&&) noexcept;
  BasicHFSolver& operator=(BasicHFSolver&&) noexcept;

  Solution solve(const HFSettings& settings = {}) const;
  // From an initial guess (warm start). Throws contactrb::Error on sizes that do not match.
  Solution solve(const HFSettings& settings, const HFInitialGuess& guess) const;

  const Problem& problem() const;
  const contact::ContactPairOf<Dim>& pair() const;
  const contact::ContactQuadrature& quadrature() const;
  const fem::DofMap& dofs() const;
  // The bodies the Dirichlet conditions leave free (fem/floating_bodies.hpp); solve() refuses any.
  const std::vector<int>& floating_bodies() const;
  const Eigen::SparseMatrix<double>& stiffness() const;  // global A (num_dofs^2)
  // (A_00^-1)[idx, idx] for free indices idx, from the factorization of A_00 this solver holds:
  // the block S on the contact DOFs that a Kacanov solve builds (ContactCondensation; nullopt
  // when idx leaves the contact DOFs), else the last Newton solve's supernodal factor
  // (HFSetupOptions::keep_newton_factor; any free indices). nullopt when it holds neither. Why: a
  // caller that needs a few entries of A_00(mu)^-1 at the snapshot's mu
  // (offline/geometric_term.hpp) takes them instead of factoring A_00 again.
  std::optional<Eigen::MatrixXd> held_inverse_block(const std::vector<int>& idx) const;
  const Eigen::VectorXd& load() const;                    // global f
  // Assembly, lifting and checks; plus, once a Kacanov solve has needed it, the factorization
  // of A_00 and the condensed block S (built lazily: the Newton method never needs them).
  double setup_time_s() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};
using HFSolver = BasicHFSolver<2>;
using HFSolver3 = BasicHFSolver<3>;
extern template class BasicHFSolver<2>;
extern template class BasicHFSolver<3>;

}  // namespace contactrb::hf
