// Semi-smooth Newton HF solver (hf/semismooth_newton.hpp): the same solution as
// Kacanov (its fixed point solves the same equations) to 1e-10 on the patch test and the
// paper's three cases with both constraint discretizations, KKT residuals, local
// superlinear convergence, warm starts, and non-convergence as a status with the residuals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/solve/blas_threads.hpp"
#include "hf_test_meshes.hpp"

using namespace contactrb;

namespace {

hf::HFSettings kacanov_to_roundoff() {
  hf::HFSettings s;
  s.method = hf::HFMethod::Kacanov;
  // alpha = 1 limit-cycles on LAC (docs/solvers.md), alpha = 0.5 contracts on every case here.
  s.kacanov.alpha = 0.5;
  s.kacanov.tolerance = 1e-12;
  s.kacanov.max_iterations = 2000;
  return s;
}

hf::HFSettings newton(double tolerance = 1e-10) {
  hf::HFSettings s;
  s.method = hf::HFMethod::Newton;
  s.newton.tolerance = tolerance;
  if (const char* lu = std::getenv("CONTACTRB_TEST_LU")) s.newton.lu = solve::sparse_lu_backend_from_string(lu);
  if (const char* lin = std::getenv("CONTACTRB_TEST_LINEAR")) s.newton.linear_solver = hf::newton_linear_solver_from_string(lin);
  return s;
}

double relative(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm() / std::max(b.norm(), 1e-300);
}

// Both methods on one problem: same u, lambda, force and energy to 1e-10.
void expect_same_solution(const hf::ContactProblem& problem, const std::string& label, int max_newton_iterations = 8,
                          int free_steps = 0) {
  const hf::HFSolver solver(problem);
  const hf::HFSolution k = solver.solve(kacanov_to_roundoff());
  hf::HFSettings ns = newton(1e-13);
  ns.newton.tuning.max_free_steps = free_steps;
  const hf::HFSolution n = solver.solve(ns);  // lambda = u-error x stiffness: solve tight
  ASSERT_TRUE(k.converged) << label << ": " << k.message;
  ASSERT_TRUE(n.converged) << label << ": " << n.message;
  EXPECT_EQ(n.method, hf::HFMethod::Newton);
  EXPECT_LT(relative(n.u, k.u), 1e-10) << label;
  EXPECT_LT(relative(n.lambda, k.lambda), 1e-10) << label;
  EXPECT_NEAR(n.contact_force, k.contact_force, 1e-10 * std::abs(k.contact_force)) << label;
  EXPECT_NEAR(n.energy, k.energy, 1e-10 * std::abs(k.energy)) << label;
  EXPECT_EQ(n.active_constraints, k.active_constraints) << label;
  EXPECT_LT(n.kkt.max(), 1e-13) << label;
  // Pointwise penetration: zero for collocation; LAC enforces the integral only, so compare.
  if (problem.discretization == contact::Discretization::Collocation) {
    EXPECT_LT(n.gap_violation, 1e-10) << label;
  } else {
    EXPECT_NEAR(n.gap_violation, k.gap_violation, 1e-9) << label;
  }
  EXPECT_LE(n.iterations, max_newton_iterations) << label;
  std::cout << "[ info     ] " << label << ": Newton " << n.iterations << " iterations, Kacanov (alpha 0.5) "
            << k.iterations << ", force " << n.contact_force << ", KKT " << n.kkt.max() << "\n";
}

hf::ContactProblem patch_problem(contact::Discretization d, int master_cells = 11) {
  hf::ContactProblem p;
  p.mesh = test_meshes::two_blocks(1.0, 1.0, 1.0, 8, 4, master_cells, 5);
  p.materials = {{10.0, 0.3}, {10.0, 0.3}};
  p.dirichlet = {{"top", std::nullopt, -0.02}, {"bottom", std::nullopt, 0.0},
                 {"left1", 0.0, std::nullopt}, {"left2", 0.0, std::nullopt}};
  p.discretization = d;
  return p;
}

}  // namespace

TEST(SemismoothNewton, PatchTestMatchesKacanovAndTheExactPressure) {
  const double exact = 10.0 / (1.0 - 0.09) * 0.02 / 2.0;  // E / (1 - nu^2) d / (h1 + h2)
  // Collocation on matching meshes, exact LAC on non-matching ones (8 / 11 cells). Known limit
  // (docs/solvers.md): collocation with non-matching meshes stalls at stationarity 2e-2, the
  // end slave node, aligned with the master's end, leaves the candidates at an iterate.
  // Matching collocation converges, in 7 iterations, only with free steps (5 here; the
  // default 0 stalls at stationarity 2e-9): the same end node drops out of the candidates at
  // some iterates and the merit cannot decrease across that switch (docs/performance.md, "Why the
  // defaults are what they are", "Newton: no free steps").
  expect_same_solution(patch_problem(contact::Discretization::Collocation, 8), "patch collocation (matching)", 25, 5);
  // The Kacanov phase (exact frozen-geometry steps; the geometry is linear here) converges
  // without free steps, in one iteration (consistent passes alone stall at 2e-9).
  expect_same_solution(patch_problem(contact::Discretization::Collocation, 8), "patch collocation (matching, no free steps)", 1, 0);
  expect_same_solution(patch_problem(contact::Discretization::LAC), "patch lac (non-matching)");
  // Exact LAC passes the patch test with non-matching meshes (docs/contact.md).
  const hf::HFSolution n = hf::HFSolver(patch_problem(contact::Discretization::LAC)).solve(newton());
  for (int r = 0; r < n.lambda.size(); ++r) EXPECT_NEAR(n.lambda(r), exact, 1e-9 * exact) << r;
}

TEST(SemismoothNewton, PaperCasesMatchKacanovBothDiscretizations) {
  struct Case {
    const char* name;
    double mu;
  };
  for (const Case c : {Case{"hertz-a", 0.15}, Case{"hertz-a", 0.45}, Case{"hertz-b", 0.9}, Case{"hertz-b", 1.12},
                       Case{"ring-block", 0.95}, Case{"ring-block", 1.15}}) {
    for (auto d : {contact::Discretization::Collocation, contact::Discretization::LAC}) {
      expect_same_solution(cases::make_problem(c.name, c.mu, 0, d),
                           std::string(c.name) + " mu " + std::to_string(c.mu) + " " + contact::to_string(d));
    }
  }
}

// Fine levels: from u = u_D the Kacanov phase (exact frozen-geometry steps until the active set
// settles) then Newton converge in <= 8 iterations, to Kacanov's answer (docs/performance.md,
// "Why the defaults are what they are", "Newton: Kacanov phase first").
TEST(SemismoothNewton, FineLevelsConvergeInAtMostEightIterations) {
  expect_same_solution(cases::make_problem("hertz-a", 0.3, 3, contact::Discretization::Collocation),
                       "hertz-a level 3 (8 964 DOFs) collocation", 8);
  expect_same_solution(cases::make_problem("ring-block", 1.05, 2, contact::Discretization::LAC),
                       "ring-block level 2 lac", 8);
}

// The Kacanov safeguard (docs/theory.md, "Semi-smooth Newton", step 4; on by default): on
// hertz-b level 2 at mu 0.9 (3 304 DOFs) one full Newton step leaves the merit above half the
// iterate's and the exact frozen-geometry step is the better one. The default takes it, every
// step a full one, to the answer of the solve without the safeguard. (Where the safeguard ends
// a crawl of damped steps, hertz-a level 5 at mu 0.45, and the chord corrections, off by
// default: bench/bench_newton_globalization.cpp.)
TEST(SemismoothNewton, KacanovSafeguardTakesTheFrozenStepWhereTheNewtonStepStalls) {
  const hf::HFSolver solver(cases::make_problem("hertz-b", 0.9, 2, contact::Discretization::Collocation));
  hf::HFSettings s = newton(1e-12);
  const hf::HFSolution n = solver.solve(s);
  ASSERT_TRUE(n.converged) << n.message;
  EXPECT_LE(n.iterations, 8);
  int kacanov_steps = 0;
  for (const auto& it : n.newton_history) {
    EXPECT_EQ(it.step, 1.0) << "a damped step at KKT " << it.residual;
    kacanov_steps += it.kacanov_step ? 1 : 0;
  }
  EXPECT_GE(kacanov_steps, 1);
  s.newton.tuning.kacanov_safeguard = 0.0;
  const hf::HFSolution off = solver.solve(s);
  ASSERT_TRUE(off.converged) << off.message;
  for (const auto& it : off.newton_history) EXPECT_FALSE(it.kacanov_step);
  EXPECT_LT(relative(n.u, off.u), 1e-9);
  EXPECT_LT(relative(n.lambda, off.lambda), 1e-8);
  EXPECT_EQ(n.active_constraints, off.active_constraints);
}

// The active-rows reduction on a once-factorized A_00 (default) is exact algebra: it takes the
// same steps as the sparse LU of the whole saddle point (same iterations, same active sets),
// whether its Newton-phase systems go through GMRES (default) or the dense LU.
TEST(SemismoothNewton, ActiveSchurTakesTheStepsOfTheSaddlePointLU) {
  for (const char* name : {"hertz-a", "ring-block"}) {
    const hf::HFSolver solver(cases::make_problem(name, std::string(name) == "hertz-a" ? 0.3 : 1.05));
    hf::HFSettings s = newton(1e-12);
    s.newton.linear_solver = hf::NewtonLinearSolver::ActiveSchur;
    const hf::HFSolution a = solver.solve(s);
    s.newton.linear_solver = hf::NewtonLinearSolver::SaddleLU;
    const hf::HFSolution b = solver.solve(s);
    ASSERT_TRUE(a.converged) << name << ": " << a.message;
    ASSERT_TRUE(b.converged) << name << ": " << b.message;
    ASSERT_EQ(a.iterations, b.iterations) << name;
    for (std::size_t k = 0; k < a.newton_history.size(); ++k) {
      EXPECT_EQ(a.newton_history[k].active, b.newton_history[k].active) << name << " iteration " << k;
      // Absolute floor 1e-12: round-off. Summing G = X'X in another order (dsyrk or
      // dgemm) moves ring-block's residual after 4 steps (1.66e-8) by 1.6e-13.
      EXPECT_NEAR(a.newton_history[k].residual, b.newton_history[k].residual, 1e-6 * b.newton_history[k].residual + 1e-12)
          << name << " iteration " << k;
    }
    EXPECT_LT((a.u - b.u).lpNorm<Eigen::Infinity>(), 1e-10 * b.u.lpNorm<Eigen::Infinity>()) << name;
    EXPECT_LT((a.lambda - b.lambda).lpNorm<Eigen::Infinity>(), 1e-8 * b.lambda.lpNorm<Eigen::Infinity>()) << name;
    EXPECT_GT(a.newton_history.back().reduced_size, 0) << name;
    // The Newton phase's systems by GMRES (default, preconditioned by the frozen-geometry
    // system) and by the dense LU of size |E| + |A| (krylov_max_iterations 0): the same steps.
    s.newton.linear_solver = hf::NewtonLinearSolver::ActiveSchur;
    s.newton.tuning.krylov_max_iterations = 0;
    const hf::HFSolution d = solver.solve(s);
    ASSERT_TRUE(d.converged) << name << ": " << d.message;
    ASSERT_EQ(a.iterations, d.iterations) << name;
    int krylov_default = 0, krylov_dense = 0;
    for (std::size_t k = 0; k < a.newton_history.size(); ++k) {
      EXPECT_EQ(a.newton_history[k].active, d.newton_history[k].active) << name << " iteration " << k;
      krylov_default += a.newton_history[k].krylov;
      krylov_dense += d.newton_history[k].krylov;
    }
    EXPECT_GT(krylov_default, 0) << name;  // the default took the GMRES path
    EXPECT_EQ(krylov_dense, 0) << name;
    EXPECT_LT((a.u - d.u).lpNorm<Eigen::Infinity>(), 1e-10 * d.u.lpNorm<Eigen::Infinity>()) << name;
    EXPECT_LT((a.lambda - d.lambda).lpNorm<Eigen::Infinity>(), 1e-8 * d.lambda.lpNorm<Eigen::Infinity>()) << name;
  }
}

// The factorization's ordering (METIS on the node graph, CHOLMOD's default) and its BLAS threads
// (2 from 0 rows on against the BLAS's own count) change round-off only: the same iterations,
// active sets, and the solution to 1e-12.
TEST(SemismoothNewton, OrderingAndBlasThreadsGiveTheSameSolution) {
  const hf::HFSolver solver(cases::make_problem("hertz-a", 0.3, 1));
  hf::HFSettings s = newton(1e-12);
  s.newton.ordering = solve::FactorOrdering::Cholmod;
  const hf::HFSolution a = solver.solve(s);
  s.newton.ordering = solve::FactorOrdering::NodeMetis;
  s.newton.tuning.blas_threads = 2;
  s.newton.tuning.blas_threads_from = 0;
  const hf::HFSolution b = solver.solve(s);
  ASSERT_TRUE(a.converged) << a.message;
  ASSERT_TRUE(b.converged) << b.message;
  ASSERT_EQ(a.iterations, b.iterations);
  for (std::size_t k = 0; k < a.newton_history.size(); ++k) {
    EXPECT_EQ(a.newton_history[k].active, b.newton_history[k].active) << "iteration " << k;
  }
  EXPECT_LT(relative(b.u, a.u), 1e-12);
  EXPECT_LT(relative(b.lambda, a.lambda), 1e-12);
  EXPECT_NEAR(b.contact_force, a.contact_force, 1e-12 * std::abs(a.contact_force));
  EXPECT_GT(a.newton_timings.factor_nonzeros, 0);
  EXPECT_EQ(a.newton_timings.blas_threads, solve::blas_threads());
  if (solve::blas_threads_settable()) {
    EXPECT_EQ(b.newton_timings.blas_threads, 2);
  }
}

// The ordering and symbolic analysis of A_00 made on a second thread during the constructor's
// assembly (HFSetupOptions::newton_analysis) give the same factor, hence bitwise the same
// iterates, as the analysis in the solve, for both orderings; a solve asking for another
// ordering than the prepared one analyses A_00 itself; the prepared analysis serves every solve.
TEST(SemismoothNewton, AnalysisBesideTheAssemblyGivesBitwiseTheSameSolution) {
  for (const solve::FactorOrdering ordering : {solve::FactorOrdering::Cholmod, solve::FactorOrdering::NodeMetis}) {
    hf::HFSettings s = newton(1e-12);
    s.newton.ordering = ordering;
    const hf::HFSetupOptions options = hf::setup_options_for(s);
    ASSERT_TRUE(options.newton_analysis);
    // `serial` analyses A_00 in its solve while `ahead`'s analysis runs on its thread: the two
    // orderings at once (METIS's shared state: solve/selected_inverse.cpp).
    const hf::HFSolver serial(cases::make_problem("hertz-a", 0.3, 2));
    const hf::HFSolver ahead(cases::make_problem("hertz-a", 0.3, 2), options);
    const hf::HFSolution a = serial.solve(s), b = ahead.solve(s);
    ASSERT_TRUE(a.converged) << a.message;
    ASSERT_TRUE(b.converged) << b.message;
    EXPECT_FALSE(a.newton_timings.analysis_ahead);
    EXPECT_TRUE(b.newton_timings.analysis_ahead) << solve::to_string(ordering);
    EXPECT_GT(b.newton_timings.analyze_s, 0.0);
    EXPECT_EQ(a.newton_timings.factor_nonzeros, b.newton_timings.factor_nonzeros);
    ASSERT_EQ(a.iterations, b.iterations);
    EXPECT_TRUE((a.u.array() == b.u.array()).all()) << solve::to_string(ordering);
    EXPECT_TRUE((a.lambda.array() == b.lambda.array()).all()) << solve::to_string(ordering);
    EXPECT_EQ(a.energy, b.energy);
    // Again (the analysis is kept), and with the other ordering (not the prepared one).
    const hf::HFSolution again = ahead.solve(s);
    EXPECT_TRUE(again.newton_timings.analysis_ahead);
    EXPECT_TRUE((again.u.array() == a.u.array()).all());
    hf::HFSettings other = s;
    other.newton.ordering = ordering == solve::FactorOrdering::Cholmod ? solve::FactorOrdering::NodeMetis
                                                                      : solve::FactorOrdering::Cholmod;
    const hf::HFSolution c = ahead.solve(other), d = serial.solve(other);
    EXPECT_FALSE(c.newton_timings.analysis_ahead);
    EXPECT_TRUE((c.u.array() == d.u.array()).all());
  }
  // Kacanov prepares nothing.
  EXPECT_FALSE(hf::setup_options_for(hf::HFSettings{}).newton_analysis);
}

// Newton's local rate: the last steps shrink the KKT residual superlinearly
// (r_{k+1} / r_k -> 0); a linear method at Kacanov's rate would keep the ratio near its
// contraction factor (0.1-0.7 here).
TEST(SemismoothNewton, LocalConvergenceIsSuperlinear) {
  for (const char* name : {"hertz-a", "ring-block"}) {
    const double mu = std::string(name) == "hertz-a" ? 0.45 : 1.05;
    hf::HFSettings s = newton();
    s.newton.tolerance = 1e-13;
    const hf::HFSolution n = hf::HFSolver(cases::make_problem(name, mu)).solve(s);
    ASSERT_TRUE(n.converged) << name << ": " << n.message;
    const auto& h = n.newton_history;
    ASSERT_GE(h.size(), 3u) << name;
    // History entries are the residuals before each step; the last pair below 1e-3.
    std::vector<double> r;
    for (const auto& it : h) r.push_back(it.residual);
    r.push_back(n.kkt.max());
    // The first residual below 1e-11 (before round-off takes over) and the two before it.
    std::size_t last = 2;
    while (last + 1 < r.size() && r[last] >= 1e-11) ++last;
    const double ratio_last = r[last] / r[last - 1];
    const double ratio_prev = r[last - 1] / r[last - 2];
    std::cout << "[ info     ] " << name << ": residuals";
    for (double x : r) std::cout << " " << x;
    std::cout << "\n";
    EXPECT_LT(ratio_last, 1e-2) << name;
    EXPECT_LT(ratio_last, ratio_prev) << name;  // the rate improves: superlinear
  }
}

TEST(SemismoothNewton, WarmStartFromANearbyParameterGivesTheSameAnswerInFewerIterations) {
  const hf::HFSolver near(cases::make_problem("hertz-a", 0.29));
  const hf::HFSolution seed = near.solve(newton());
  ASSERT_TRUE(seed.converged) << seed.message;
  const hf::HFSolver solver(cases::make_problem("hertz-a", 0.3));
  // Both solved to 1e-12: lambda is compared to 1e-10 (it carries the residual times the
  // stiffness; at the default 1e-10 the two differ by 1.09e-10).
  const hf::HFSolution cold = solver.solve(newton(1e-12));
  const hf::HFSolution warm = solver.solve(newton(1e-12), hf::HFInitialGuess{seed.u, seed.lambda});
  ASSERT_TRUE(cold.converged && warm.converged) << cold.message << warm.message;
  EXPECT_LT(warm.iterations, cold.iterations);
  EXPECT_LT(relative(warm.u, cold.u), 1e-10);
  EXPECT_LT(relative(warm.lambda, cold.lambda), 1e-10);
  // Kacanov warm-starts too (same fixed point; both iterates start at the seed).
  hf::HFSettings k = kacanov_to_roundoff();
  const hf::HFSolution kcold = solver.solve(k);
  const hf::HFSolution kwarm = solver.solve(k, hf::HFInitialGuess{seed.u, seed.lambda});
  ASSERT_TRUE(kcold.converged && kwarm.converged);
  EXPECT_LT(kwarm.iterations, kcold.iterations);
  EXPECT_LT(relative(kwarm.u, cold.u), 1e-10);
  // Wrong sizes are refused, naming the vector.
  EXPECT_THROW(solver.solve(newton(), hf::HFInitialGuess{Eigen::VectorXd::Zero(3), {}}), contactrb::Error);
  EXPECT_THROW(solver.solve(newton(), hf::HFInitialGuess{{}, Eigen::VectorXd::Zero(2)}), contactrb::Error);
}

TEST(SemismoothNewton, NonConvergenceIsAStatusWithIterationsAndResiduals) {
  hf::HFSettings s = newton();
  s.newton.max_iterations = 2;
  const hf::HFSolution n = hf::HFSolver(cases::make_problem("hertz-a", 0.45)).solve(s);
  EXPECT_FALSE(n.converged);
  EXPECT_EQ(n.status, solve::KacanovStatus::MaxIterations);
  EXPECT_EQ(n.iterations, 2);
  EXPECT_NE(n.message.find("did not converge in 2 iterations"), std::string::npos) << n.message;
  EXPECT_NE(n.message.find("stationarity"), std::string::npos) << n.message;
  EXPECT_NE(n.message.find("complementarity"), std::string::npos) << n.message;
  EXPECT_GT(n.kkt.max(), s.newton.tolerance);
}

TEST(SemismoothNewton, InvalidSettingsThrowNamingTheSetting) {
  const hf::HFSolver solver(cases::make_problem("hertz-a", 0.3));
  hf::HFSettings s = newton();
  s.newton.tolerance = 0.0;
  EXPECT_THROW(solver.solve(s), contactrb::Error);
  s = newton();
  s.newton.max_iterations = 0;
  EXPECT_THROW(solver.solve(s), contactrb::Error);
  s = newton();
  s.newton.tuning.min_step = 2.0;
  EXPECT_THROW(solver.solve(s), contactrb::Error);
  // Each bad value is refused with an error that names its setting.
  const std::vector<std::pair<std::string, std::function<void(hf::NewtonSettings&)>>> named{
      {"max_branch_passes", [](hf::NewtonSettings& n) { n.tuning.max_branch_passes = -1; }},
      {"branch_passes_below", [](hf::NewtonSettings& n) { n.tuning.branch_passes_below = -1.0; }},
      {"kacanov_safeguard", [](hf::NewtonSettings& n) { n.tuning.kacanov_safeguard = -0.5; }},
      {"max_newton_passes", [](hf::NewtonSettings& n) { n.tuning.max_newton_passes = 0; }},
      {"switch_passes", [](hf::NewtonSettings& n) { n.tuning.switch_passes = 0; }},
      {"chord_steps", [](hf::NewtonSettings& n) { n.tuning.chord_steps = -1; }},
      {"blas_threads", [](hf::NewtonSettings& n) { n.tuning.blas_threads = -1; }},
  };
  for (const auto& [name, spoil] : named) {
    s = newton();
    spoil(s.newton);
    try {
      (void)solver.solve(s);
      ADD_FAILURE() << name << ": no error";
    } catch (const contactrb::Error& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  s = newton();
  s.newton.tuning.krylov_max_iterations = -1;
  EXPECT_THROW(solver.solve(s), contactrb::Error);
  s = newton();
  s.newton.tuning.krylov_tolerance = 1.0;
  EXPECT_THROW(solver.solve(s), contactrb::Error);
  EXPECT_THROW(hf::hf_method_from_string("gauss"), contactrb::Error);
}
