#include "contactrb/hf/semismooth_newton.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/hf/newton_steps.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::hf {

const char* to_string(NewtonLinearSolver solver) {
  switch (solver) {
    case NewtonLinearSolver::ActiveSchur: return "schur";
    case NewtonLinearSolver::SaddleLU: return "lu";
    case NewtonLinearSolver::Amg: return "amg";
    case NewtonLinearSolver::Auto: return "auto";
  }
  return "unknown";
}

NewtonLinearSolver newton_linear_solver_from_string(const std::string& name) {
  return enum_from_string(name, "Newton linear solver",
                          std::array{NewtonLinearSolver::ActiveSchur, NewtonLinearSolver::SaddleLU,
                                     NewtonLinearSolver::Amg, NewtonLinearSolver::Auto});
}

NewtonLinearSolver resolved_linear_solver(const NewtonSettings& s, int dimension, int free_dofs) {
  if (s.linear_solver != NewtonLinearSolver::Auto) return s.linear_solver;
  return dimension >= 3 && free_dofs >= s.amg_from_free_dofs && solve::amg_available() ? NewtonLinearSolver::Amg
                                                                                        : NewtonLinearSolver::ActiveSchur;
}

double newton_forcing_term(const NewtonSettings& s, bool newton_phase, double residual, double previous_residual,
                           double previous_eta) {
  const NewtonForcing& f = s.krylov_forcing;
  const double tightest = std::min(s.krylov.tolerance, f.max);
  if (!newton_phase) return f.max;
  double eta = tightest;
  if (previous_residual > 0.0 && residual > 0.0) {
    eta = f.gamma * std::pow(residual / previous_residual, f.exponent);
    const double safeguard = f.gamma * std::pow(previous_eta, f.exponent);
    if (safeguard > 0.1) eta = std::max(eta, safeguard);
  }
  if (residual > 0.0) eta = std::max(eta, 0.5 * s.tolerance / residual);
  return std::clamp(eta, tightest, f.max);
}

const char* to_string(NewtonInnerPasses passes) {
  switch (passes) {
    case NewtonInnerPasses::Frozen: return "frozen";
    case NewtonInnerPasses::Consistent: return "consistent";
  }
  return "unknown";
}

NewtonInnerPasses newton_inner_passes_from_string(const std::string& name) {
  if (name == "frozen") return NewtonInnerPasses::Frozen;
  if (name == "consistent") return NewtonInnerPasses::Consistent;
  throw Error("unknown Newton inner passes '" + name + "' (expected frozen or consistent)");
}

void check_settings(const NewtonSettings& s) {
  const NewtonTuning& t = s.tuning;
  require(t.blas_threads >= 0, "Newton blas_threads must be >= 0 (got " + std::to_string(t.blas_threads) + ")");
  require(std::isfinite(s.tolerance) && s.tolerance > 0.0,
          "Newton tolerance must be > 0 (got " + number_text(s.tolerance) + ")");
  require(s.max_iterations >= 1, "Newton max_iterations must be >= 1 (got " + std::to_string(s.max_iterations) + ")");
  require(std::isfinite(t.armijo) && t.armijo > 0.0 && t.armijo < 0.5,
          "Newton armijo must be in (0, 1/2) (got " + number_text(t.armijo) + ")");
  require(std::isfinite(t.min_step) && t.min_step > 0.0 && t.min_step <= 1.0,
          "Newton min_step must be in (0, 1] (got " + number_text(t.min_step) + ")");
  require(t.max_inner_iterations >= 1,
          "Newton max_inner_iterations must be >= 1 (got " + std::to_string(t.max_inner_iterations) + ")");
  require(std::isfinite(t.min_rcond) && t.min_rcond >= 0.0 && t.min_rcond < 1.0,
          "Newton min_rcond must be in [0, 1) (got " + number_text(t.min_rcond) + ")");
  require(t.krylov_max_iterations >= 0,
          "Newton krylov_max_iterations must be >= 0 (got " + std::to_string(t.krylov_max_iterations) + ")");
  require(std::isfinite(t.krylov_tolerance) && t.krylov_tolerance > 0.0 && t.krylov_tolerance < 1.0,
          "Newton krylov_tolerance must be in (0, 1) (got " + number_text(t.krylov_tolerance) + ")");
  require(s.amg_from_free_dofs >= 0,
          "Newton amg_from_free_dofs must be >= 0 (got " + std::to_string(s.amg_from_free_dofs) + ")");
  require(std::isfinite(s.krylov.tolerance) && s.krylov.tolerance > 0.0 && s.krylov.tolerance < 1.0,
          "Newton AMG Krylov tolerance must be in (0, 1) (got " + number_text(s.krylov.tolerance) + ")");
  require(s.krylov.max_iterations >= 1,
          "Newton AMG Krylov max_iterations must be >= 1 (got " + std::to_string(s.krylov.max_iterations) + ")");
  require(std::isfinite(s.krylov_forcing.max) && s.krylov_forcing.max > 0.0 && s.krylov_forcing.max < 1.0,
          "Newton AMG forcing max must be in (0, 1) (got " + number_text(s.krylov_forcing.max) + ")");
  require(std::isfinite(s.krylov_forcing.gamma) && s.krylov_forcing.gamma > 0.0 && s.krylov_forcing.gamma <= 1.0,
          "Newton AMG forcing gamma must be in (0, 1] (got " + number_text(s.krylov_forcing.gamma) + ")");
  require(std::isfinite(s.krylov_forcing.exponent) && s.krylov_forcing.exponent > 1.0 && s.krylov_forcing.exponent <= 2.0,
          "Newton AMG forcing exponent must be in (1, 2] (got " + number_text(s.krylov_forcing.exponent) + ")");
  require(s.krylov.restart >= 1, "Newton AMG Krylov restart must be >= 1 (got " + std::to_string(s.krylov.restart) + ")");
  require(std::isfinite(s.amg.strong_threshold) && s.amg.strong_threshold > 0.0 && s.amg.strong_threshold < 1.0,
          "Newton AMG strong_threshold must be in (0, 1) (got " + number_text(s.amg.strong_threshold) + ")");
  require(t.max_free_steps >= 0, "Newton max_free_steps must be >= 0 (got " + std::to_string(t.max_free_steps) + ")");
  require(t.max_branch_passes >= 0,
          "Newton max_branch_passes must be >= 0 (got " + std::to_string(t.max_branch_passes) + ")");
  require(std::isfinite(t.kacanov_safeguard) && t.kacanov_safeguard >= 0.0,
          "Newton kacanov_safeguard must be >= 0 (got " + number_text(t.kacanov_safeguard) + ")");
  require(t.switch_passes >= 1, "Newton switch_passes must be >= 1 (got " + std::to_string(t.switch_passes) + ")");
  require(t.chord_steps >= 0, "Newton chord_steps must be >= 0 (got " + std::to_string(t.chord_steps) + ")");
  require(t.max_newton_passes >= 1,
          "Newton max_newton_passes must be >= 1 (got " + std::to_string(t.max_newton_passes) + ")");
  require(t.branch_passes_below >= 0.0, "Newton branch_passes_below must be >= 0 (got " + number_text(t.branch_passes_below) + ")");
}

// The method of docs/theory.md, "Semi-smooth Newton": its steps are NewtonSolve's
// (newton_steps.hpp), numbered as there.
template <int Dim>
NewtonResult semismooth_newton(const BasicNewtonProblem<Dim>& p, const Eigen::VectorXd& u0_start,
                               const Eigen::VectorXd& lambda_start, const NewtonSettings& s) {
  check_settings(s);
  const int n = p.dofs->num_free();
  const int R = static_cast<int>(p.quadrature->weight.size());
  require(u0_start.size() == n, "semismooth_newton: initial u0 has " + std::to_string(u0_start.size()) +
                                    " entries for " + std::to_string(n) + " free DOFs");
  require(lambda_start.size() == R, "semismooth_newton: initial lambda has " + std::to_string(lambda_start.size()) +
                                        " entries for " + std::to_string(R) + " constraint rows");
  NewtonSolve<Dim> solve(p, s);
  if (!solve.start(u0_start, lambda_start)) return solve.result();
  for (int k = 0; solve.keep_iterating(k); ++k) {  // step 6: the convergence test at each iterate
    if (!solve.linearize()) break;                 // step 1: the contact linearized at the iterate
    if (!solve.solve_on_active_set()) break;       // step 2: frozen or consistent passes
    solve.branch_passes();                         // step 3: the step re-solved on its branches
    solve.switch_phase();                          // step 3: Kacanov phase -> Newton phase
    solve.kacanov_safeguard();                     // step 4: the better of the Newton and frozen steps
    solve.chord_corrections();                     // step 4: off by default
    if (!solve.line_search()) break;               // step 5: backtracking on the merit
  }
  return solve.result();
}

template NewtonResult semismooth_newton(const BasicNewtonProblem<2>&, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                        const NewtonSettings&);
template NewtonResult semismooth_newton(const BasicNewtonProblem<3>&, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                        const NewtonSettings&);

}  // namespace contactrb::hf
