// The semi-smooth Newton with the AMG-preconditioned Krylov solve of its systems
// (NewtonLinearSolver::Amg; docs/solvers.md, "AMG-preconditioned Krylov solve") against the direct
// one (ActiveSchur, CHOLMOD) on the same problems: the patch test's uniform pressure E mu
// (patch-3d), the Hertz force and the KKT conditions (hertz-3d level 0); a GMRES that cannot
// reach its tolerance is a failed solve with its message, never an answer; Auto's choice.
#include <gtest/gtest.h>

#include <string>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/solve/amg_preconditioner.hpp"

using namespace contactrb;

namespace {

hf::HFSettings newton(hf::NewtonLinearSolver linear) {
  hf::HFSettings s;
  s.method = hf::HFMethod::Newton;
  s.newton.linear_solver = linear;
  return s;
}

hf::HFSolver3 case_solver(const std::string& name, int level, double mu) {
  const cases::CaseSpec spec = cases::builtin_case_spec(name);
  return hf::HFSolver3(cases::make_problem(spec, cases::reference_mesh3(spec, level), cases::Mu::Constant(1, mu)));
}

}  // namespace

// patch-3d (LAC): uniaxial stress, the exact pressure E mu = 10 x 0.02 on every active row, with
// both linear solvers, and the same multipliers.
TEST(AmgNewton, PatchTestUniformPressureAsDirect) {
  if (!solve::amg_available()) GTEST_SKIP() << "this build has no hypre";
  const hf::HFSolver3 solver = case_solver("patch-3d", 0, 0.02);
  const hf::HFSolution3 direct = solver.solve(newton(hf::NewtonLinearSolver::ActiveSchur));
  const hf::HFSolution3 amg = solver.solve(newton(hf::NewtonLinearSolver::Amg));
  ASSERT_TRUE(direct.converged) << direct.message;
  ASSERT_TRUE(amg.converged) << amg.message;
  EXPECT_EQ(amg.newton_timings.linear_solver, hf::NewtonLinearSolver::Amg);
  EXPECT_GT(amg.newton_history.front().krylov, 0);
  const double p = 10.0 * 0.02;
  ASSERT_GT(amg.active_constraints, 0);
  EXPECT_EQ(amg.active_constraints, direct.active_constraints);
  for (Eigen::Index r = 0; r < amg.lambda.size(); ++r) {
    if (direct.lambda(r) > 0.0) {
      EXPECT_NEAR(amg.lambda(r), p, 1e-8 * p) << "row " << r;
    }
    EXPECT_NEAR(amg.lambda(r), direct.lambda(r), 1e-8 * p) << "row " << r;
  }
  EXPECT_LE(amg.kkt.max(), hf::NewtonSettings{}.tolerance);
}

// hertz-3d level 0 (collocation): the same active set, force, displacement and KKT residual to
// the Newton tolerance (1e-10 relative).
TEST(AmgNewton, HertzLevel0ForceAndKktAsDirect) {
  if (!solve::amg_available()) GTEST_SKIP() << "this build has no hypre";
  const hf::HFSolver3 solver = case_solver("hertz-3d", 0, 0.02);
  const hf::HFSolution3 direct = solver.solve(newton(hf::NewtonLinearSolver::ActiveSchur));
  const hf::HFSolution3 amg = solver.solve(newton(hf::NewtonLinearSolver::Amg));
  ASSERT_TRUE(direct.converged) << direct.message;
  ASSERT_TRUE(amg.converged) << amg.message;
  EXPECT_EQ(amg.active_constraints, direct.active_constraints);
  EXPECT_NEAR(amg.contact_force, direct.contact_force, 1e-8 * direct.contact_force);
  EXPECT_LE((amg.u - direct.u).lpNorm<Eigen::Infinity>(), 1e-8 * direct.u.lpNorm<Eigen::Infinity>());
  EXPECT_LE((amg.lambda - direct.lambda).lpNorm<Eigen::Infinity>(), 1e-7 * direct.lambda.lpNorm<Eigen::Infinity>());
  // KKT of the AMG answer on its own: stationarity, feasibility, sign, complementarity.
  EXPECT_LE(amg.kkt.max(), hf::NewtonSettings{}.tolerance);
  EXPECT_LE(amg.gap_violation, 1e-9);
  EXPECT_GE(amg.lambda.minCoeff(), 0.0);
  EXPECT_LE(amg.iterations, direct.iterations + 1);
}

// The forcing terms (hf::newton_forcing_term) against their formulas: the loosest in the Kacanov
// phase; in the Newton phase Eisenstat and Walker's gamma (r_k / r_k-1)^2, raised by the
// safeguard gamma eta_k-1^2 when that exceeds 0.1 and by Kelley's 0.5 tol / r_k, within
// [krylov.tolerance, max]; max equal to the tolerance gives the constant forcing term.
TEST(AmgNewton, ForcingTermsFollowTheirFormulasWithinTheBounds) {
  hf::NewtonSettings s;  // tolerance 1e-10, krylov.tolerance 1e-4, max 3e-2, gamma 0.9, exponent 2
  ASSERT_EQ(s.krylov_forcing.max, 3e-2);
  EXPECT_EQ(hf::newton_forcing_term(s, false, 1e-3, 1e-2, 1e-4), 3e-2);
  EXPECT_EQ(hf::newton_forcing_term(s, false, 1e-3, 0.0, 0.0), 3e-2);
  // First Newton-phase iteration (no previous ratio): the tightest, or 0.5 tol / r above it.
  EXPECT_EQ(hf::newton_forcing_term(s, true, 1e-6, 0.0, 3e-2), 1e-4);
  EXPECT_DOUBLE_EQ(hf::newton_forcing_term(s, true, 2e-9, 0.0, 3e-2), 0.025);
  EXPECT_EQ(hf::newton_forcing_term(s, true, 1e-9, 0.0, 3e-2), 3e-2);
  // Eisenstat-Walker choice 2: 0.9 (1e-5 / 1e-4)^2 = 9e-3 (Kelley's bound 5e-6 below it).
  EXPECT_DOUBLE_EQ(hf::newton_forcing_term(s, true, 1e-5, 1e-4, 1e-4), 9e-3);
  EXPECT_EQ(hf::newton_forcing_term(s, true, 1e-6, 1e-3, 1e-4), 1e-4);  // 9e-7 and 5e-5: the tightest
  EXPECT_DOUBLE_EQ(hf::newton_forcing_term(s, true, 1e-7, 1e-3, 1e-4), 5e-4);  // Kelley's 0.5 tol / r
  s.krylov_forcing.max = 0.9;
  EXPECT_DOUBLE_EQ(hf::newton_forcing_term(s, true, 1e-6, 1e-4, 0.5), 0.9 * 0.25);  // the safeguard
  EXPECT_EQ(hf::newton_forcing_term(s, true, 1e-6, 1e-4, 0.3), 1e-4);  // 0.081 <= 0.1: no safeguard
  s.krylov_forcing.max = s.krylov.tolerance;
  for (bool newton_phase : {false, true}) {
    for (double r : {1.0, 1e-5, 2e-10}) EXPECT_EQ(hf::newton_forcing_term(s, newton_phase, r, 1e-2, 0.5), 1e-4);
  }
  hf::NewtonSettings bad;
  bad.krylov_forcing.max = 1.0;
  try {
    hf::check_settings(bad);
    ADD_FAILURE() << "forcing max 1 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("forcing max must be in (0, 1)"), std::string::npos) << e.what();
  }
}

// The iterations record their forcing terms: the loosest in the Kacanov phase, every one within
// the bounds; with a constant forcing term (max = tolerance) and with the symmetric smoother the
// answer is the same as with the defaults, to the Newton tolerance.
TEST(AmgNewton, ForcingTermsAndSmoothersKeepTheAnswer) {
  if (!solve::amg_available()) GTEST_SKIP() << "this build has no hypre";
  const hf::HFSolver3 solver = case_solver("hertz-3d", 0, 0.02);
  const hf::HFSettings defaults = newton(hf::NewtonLinearSolver::Amg);
  const hf::HFSolution3 adaptive = solver.solve(defaults);
  ASSERT_TRUE(adaptive.converged) << adaptive.message;
  EXPECT_EQ(adaptive.newton_history.front().forcing, defaults.newton.krylov_forcing.max);
  for (const hf::NewtonIteration& it : adaptive.newton_history) {
    EXPECT_GE(it.forcing, defaults.newton.krylov.tolerance);
    EXPECT_LE(it.forcing, defaults.newton.krylov_forcing.max);
  }
  hf::HFSettings constant = defaults;
  constant.newton.krylov_forcing.max = constant.newton.krylov.tolerance;
  constant.newton.amg.smoother = solve::AmgSmoother::Symmetric;
  const hf::HFSolution3 fixed = solver.solve(constant);
  ASSERT_TRUE(fixed.converged) << fixed.message;
  for (const hf::NewtonIteration& it : fixed.newton_history) EXPECT_EQ(it.forcing, constant.newton.krylov.tolerance);
  EXPECT_EQ(adaptive.active_constraints, fixed.active_constraints);
  EXPECT_NEAR(adaptive.contact_force, fixed.contact_force, 1e-8 * fixed.contact_force);
  EXPECT_LE((adaptive.u - fixed.u).lpNorm<Eigen::Infinity>(), 1e-8 * fixed.u.lpNorm<Eigen::Infinity>());
  EXPECT_LE(adaptive.kkt.max(), defaults.newton.tolerance);
}

// One GMRES product per system cannot reach the tolerance: the solve fails with StepFailed and a
// message naming the Krylov solve, and says it has not converged.
TEST(AmgNewton, KrylovFailureIsAFailedSolve) {
  if (!solve::amg_available()) GTEST_SKIP() << "this build has no hypre";
  const hf::HFSolver3 solver = case_solver("hertz-3d", 0, 0.02);
  hf::HFSettings s = newton(hf::NewtonLinearSolver::Amg);
  s.newton.krylov.max_iterations = 1;
  const hf::HFSolution3 sol = solver.solve(s);
  EXPECT_FALSE(sol.converged);
  EXPECT_EQ(sol.status, solve::KacanovStatus::StepFailed);
  EXPECT_NE(sol.message.find("AMG-preconditioned GMRES"), std::string::npos) << sol.message;
  EXPECT_NE(sol.message.find("max-iterations after 1 products"), std::string::npos) << sol.message;
}

// Auto: the direct solve in 2D and below the threshold in 3D, AMG from it on.
TEST(AmgNewton, AutoPicksAmgIn3dFromTheThreshold) {
  hf::NewtonSettings s;
  s.linear_solver = hf::NewtonLinearSolver::Auto;
  s.amg_from_free_dofs = 1000;
  EXPECT_EQ(hf::resolved_linear_solver(s, 2, 10'000'000), hf::NewtonLinearSolver::ActiveSchur);
  EXPECT_EQ(hf::resolved_linear_solver(s, 3, 999), hf::NewtonLinearSolver::ActiveSchur);
  EXPECT_EQ(hf::resolved_linear_solver(s, 3, 1000), solve::amg_available() ? hf::NewtonLinearSolver::Amg
                                                                           : hf::NewtonLinearSolver::ActiveSchur);
  s.linear_solver = hf::NewtonLinearSolver::SaddleLU;
  EXPECT_EQ(hf::resolved_linear_solver(s, 3, 1000), hf::NewtonLinearSolver::SaddleLU);
  EXPECT_EQ(hf::newton_linear_solver_from_string("amg"), hf::NewtonLinearSolver::Amg);
  EXPECT_EQ(hf::newton_linear_solver_from_string("auto"), hf::NewtonLinearSolver::Auto);
  EXPECT_THROW(hf::newton_linear_solver_from_string("direct"), Error);
}
