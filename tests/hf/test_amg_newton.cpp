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
