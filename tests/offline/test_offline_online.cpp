// Offline builder and online solver (paper Algorithm 1): with nothing truncated the online
// solution at a training mu reproduces the HF snapshot; leading sub-blocks equal a model built
// at those sizes; truncation errors fall as the sizes grow; the model holds no HF-size array.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/theta.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/dual_cone.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "support/cpg_settings.hpp"

namespace {

using contactrb::io::SnapshotSet;
using contactrb::offline::OfflineResult;
using contactrb::offline::OfflineSettings;
using contactrb::online::OnlineSettings;
using contactrb::online::OnlineSizes;
using contactrb::online::OnlineSolver;

constexpr double kTightTolerance = 1e-10;  // Kacanov eps on both sides (alpha = 1)

const std::map<std::string, std::vector<double>>& verification_values() {
  static const std::map<std::string, std::vector<double>> values{{"hertz-a", {0.18, 0.30, 0.42}},
                                                                  {"hertz-b", {0.925, 1.005, 1.085}}};
  return values;
}

const std::map<std::string, std::vector<double>>& training_values() {
  static const std::map<std::string, std::vector<double>> values{
      {"hertz-a", {0.15, 0.21, 0.27, 0.33, 0.39, 0.45}},
      {"hertz-b", {0.905, 0.945, 0.985, 1.025, 1.065, 1.105}}};
  return values;
}

// Snapshots of a case, generated once per test binary run.
const SnapshotSet& snapshots(const std::string& name, bool verification = false) {
  static std::map<std::string, std::unique_ptr<SnapshotSet>> cache;
  auto& slot = cache[name + (verification ? "/verification" : "/training")];
  if (!slot) {
    contactrb::offline::SnapshotRequest r = contactrb::offline::make_snapshot_request(
        contactrb::cases::builtin_case_spec(name), "training", 0, std::nullopt,
        contactrb::cases::points_1d(verification ? verification_values().at(name) : training_values().at(name)));
    r.settings.kacanov.alpha = 1.0;
    r.settings.kacanov.tolerance = kTightTolerance;
    r.settings.kacanov.max_iterations = 500;
    contactrb::offline::SnapshotRunOptions options;
    options.jobs = 2;
    slot = std::make_unique<SnapshotSet>(contactrb::offline::generate_snapshots(r, options));
  }
  return *slot;
}

OfflineSettings untruncated(bool compression) {
  OfflineSettings s = test_support::cpg_settings();
  s.pod_modes = 1000;  // capped at the numerical rank: N = P
  s.eps_du = 0.0;      // CPG until every snapshot lies in the cone
  s.eps_eim_k = 0.0;   // EIM until exhausted
  s.eps_eim_g = 0.0;
  s.compression = compression;
  return s;
}

OnlineSettings tight_online() {
  OnlineSettings s;
  s.kacanov = contactrb::solve::KacanovSettings{1.0, kTightTolerance, 500};
  return s;
}

struct Errors {
  double u = 0.0;
  double lambda = 0.0;
};

// Relative errors of the online solution against the HF snapshot p.
Errors compare(const OfflineResult& off, OnlineSolver& solver, const SnapshotSet& set, std::size_t p,
               const OnlineSettings& settings) {
  const contactrb::io::Snapshot& snap = set.snapshots[p];
  const contactrb::online::OnlineSolution sol = solver.solve(snap.mu, settings);
  EXPECT_TRUE(sol.converged()) << "mu = " << snap.mu << ": " << sol.message;
  const Eigen::VectorXd u = contactrb::online::reconstruct_displacement(off.reconstruction, snap.mu, sol.u_hat);
  const Eigen::VectorXd lambda = contactrb::online::reconstruct_multipliers(off.reconstruction, snap.mu, sol.lambda_hat);
  EXPECT_GE(sol.lambda_hat.minCoeff(), 0.0);
  return {(u - snap.u).norm() / snap.u.norm(), (lambda - snap.lambda).norm() / snap.lambda.norm()};
}

// A truncated model (N 4, R 4, Mk 4, Mg 3) of a case's test snapshots.
OfflineResult truncated_model(const SnapshotSet& set, const std::string& name) {
  OfflineSettings s = test_support::cpg_settings();
  s.eps_pod = 0.0;
  s.pod_modes = 4;
  s.dual_size = 4;
  s.eim_k_size = 4;
  s.eim_g_size = 3;
  return contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec(name), s);
}

// The reduced fixed point to 1e-11: the paper's relaxed iteration (alpha 0.3) from u_hat = 0
// (at 1e-12 its relative increments stall on round-off at some values in an AVX2/FMA build).
OnlineSettings reduced_fixed_point() {
  OnlineSettings s;
  s.kacanov = contactrb::solve::KacanovSettings{0.3, 1e-11, 5000};
  s.iteration = contactrb::online::OnlineIteration::Relaxed;
  s.initial_guess = contactrb::online::InitialGuess::Zero;
  return s;
}

class OfflineOnline : public ::testing::TestWithParam<std::string> {};

TEST_P(OfflineOnline, UntruncatedModelReproducesTrainingSnapshots) {
  const SnapshotSet& set = snapshots(GetParam());
  ASSERT_EQ(set.num_failed(), 0);
  const auto spec = contactrb::cases::builtin_case_spec(GetParam());
  for (bool compression : {true, false}) {
    SCOPED_TRACE(compression ? "compression on" : "compression off");
    const OfflineResult off = contactrb::offline::build_reduced_model(set, spec, untruncated(compression));
    const auto& m = off.model;
    // Every POD mode, then the supremizers outside the snapshots' span.
    EXPECT_EQ(m.N_max - m.N_supremizers, static_cast<int>(set.snapshots.size()));
    if (compression) {
      EXPECT_LT(m.R_kept(), m.surface.num_constraints);
    } else {
      EXPECT_EQ(m.R_kept(), m.surface.num_constraints);
    }
    OnlineSolver solver(m);
    double worst_u = 0.0, worst_l = 0.0;
    for (std::size_t p = 0; p < set.snapshots.size(); ++p) {
      const Errors e = compare(off, solver, set, p, tight_online());
      worst_u = std::max(worst_u, e.u);
      worst_l = std::max(worst_l, e.lambda);
    }
    // The online energy (49) + lift terms against 1/2 u'A u - f'u of the HF snapshot.
    {
      const auto reference = contactrb::cases::reference_mesh(spec, set.level);
      const auto terms = contactrb::cases::assemble_affine_terms(spec, reference);
      const auto th = contactrb::cases::theta_functions(spec);
      const auto& snap = set.snapshots[3];
      const auto A = contactrb::cases::combine(terms.A, contactrb::cases::evaluate(th.a, snap.mu));
      const Eigen::VectorXd f =
          contactrb::cases::combine(terms.f, contactrb::cases::evaluate(th.f, snap.mu), set.num_dofs);
      const double hf_energy = 0.5 * snap.u.dot(A * snap.u) - f.dot(snap.u);
      const auto sol = solver.solve(snap.mu, tight_online());
      EXPECT_NEAR(sol.energy, hf_energy, 1e-8 * std::abs(hf_energy));
      EXPECT_NEAR(sol.contact_force, snap.lambda.dot(snap.weight), 1e-6 * snap.lambda.dot(snap.weight));
    }
    std::printf("[ %s ] %s N=%d R=%d Mk=%d Mg=%d R_kept=%d/%d: max rel err u %.3e, lambda %.3e\n",
                GetParam().c_str(), compression ? "compressed" : "uncompressed", m.N_max, m.R_max, m.Mk_max,
                m.Mg_max, m.R_kept(), m.surface.num_constraints, worst_u, worst_l);
    EXPECT_LT(worst_u, 1e-6);
    EXPECT_LT(worst_l, 1e-6);
  }
}

TEST_P(OfflineOnline, UntruncatedAngleGreedyModelReproducesTrainingSnapshots) {
  const SnapshotSet& set = snapshots(GetParam());
  OfflineSettings s = untruncated(true);
  s.dual_method = contactrb::offline::DualConeMethod::AngleGreedy;
  s.inner_product = contactrb::offline::InnerProduct::H1;
  const OfflineResult off =
      contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec(GetParam()), s);
  OnlineSolver solver(off.model);
  for (std::size_t p = 0; p < set.snapshots.size(); p += 2) {
    const Errors e = compare(off, solver, set, p, tight_online());
    EXPECT_LT(e.u, 1e-6);
    EXPECT_LT(e.lambda, 1e-6);
  }
}

// Two offline settings, tolerances relative to the data's own scales (the default mode);
// errors at parameter values outside the training set (HF solves at the verification values).
TEST_P(OfflineOnline, ErrorsFallAsOfflineTolerancesTighten) {
  const SnapshotSet& set = snapshots(GetParam());
  const SnapshotSet& check = snapshots(GetParam(), true);
  const auto spec = contactrb::cases::builtin_case_spec(GetParam());
  std::vector<double> worst;
  for (double rel : {1e-1, 1e-4}) {
    OfflineSettings s = test_support::cpg_settings();
    ASSERT_TRUE(s.eps_pod_relative && s.eps_du_relative && s.eps_eim_k_relative && s.eps_eim_g_relative);
    s.eps_pod = rel;
    s.eps_du = rel;
    s.eps_eim_k = rel;
    s.eps_eim_g = rel;
    const OfflineResult off = contactrb::offline::build_reduced_model(set, spec, s);
    OnlineSolver solver(off.model);
    OnlineSettings settings;
    settings.kacanov = contactrb::solve::KacanovSettings{0.5, 1e-9, 1000};
    double w = 0.0;
    for (std::size_t p = 0; p < check.snapshots.size(); ++p) w = std::max(w, compare(off, solver, check, p, settings).u);
    std::printf("[ %s ] tolerances %.0e x scale: N=%d R=%d Mk=%d Mg=%d, max rel err u (verification) %.3e\n",
                GetParam().c_str(), rel, off.model.N_max, off.model.R_max, off.model.Mk_max, off.model.Mg_max, w);
    worst.push_back(w);
  }
  EXPECT_LT(worst[1], worst[0]);
}

// The restricted magic-point evaluation (only the slave nodes under the magic rows) against
// the full contact-surface rows.
TEST_P(OfflineOnline, RestrictedMagicRowsEqualFullRows) {
  const SnapshotSet& set = snapshots(GetParam());
  OfflineSettings s = test_support::cpg_settings();
  s.eps_pod = 0.0;
  s.dual_size = 3;
  s.eim_k_size = 4;
  s.eim_g_size = 4;
  const OfflineResult off =
      contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec(GetParam()), s);
  OnlineSolver solver(off.model);
  OnlineSettings full;
  full.kacanov = contactrb::solve::KacanovSettings{0.3, 1e-6, 500};
  full.restricted_rows = false;
  OnlineSettings restricted = full;
  restricted.restricted_rows = true;
  for (const auto iteration :
       {contactrb::online::OnlineIteration::Relaxed, contactrb::online::OnlineIteration::Accelerated}) {
    full.iteration = restricted.iteration = iteration;
    for (const double mu : verification_values().at(GetParam())) {
      const auto a = solver.solve(mu, full);
      const auto b = solver.solve(mu, restricted);
      ASSERT_EQ(a.status, b.status);
      EXPECT_EQ(a.iterations, b.iterations);
      EXPECT_LT((a.u_hat - b.u_hat).norm(), 1e-10 * a.u_hat.norm());
      EXPECT_LT((a.lambda_hat - b.lambda_hat).norm(), 1e-10 * std::max(1.0, a.lambda_hat.norm()));
    }
  }
}

// The row cone solved with the exact contact rows: the restricted evaluation (the slaves under
// the kept rows, MagicPointEvaluator::evaluate_rows) gives the answer of the full contact-surface
// rows; and with every POD mode the reduced problem holds each training snapshot, so at a
// training value the reduced pressure is the HF pressure on the kept rows (0 elsewhere) and the
// displacement the HF one, to the solvers' tolerance.
TEST_P(OfflineOnline, RowConeWithExactRowsReproducesTheTrainingSnapshots) {
  const SnapshotSet& set = snapshots(GetParam());
  OfflineSettings s = untruncated(true);
  s.dual_method = contactrb::offline::DualConeMethod::Rows;
  const OfflineResult off =
      contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec(GetParam()), s);
  ASSERT_EQ(off.model.dual_method, "rows");
  ASSERT_EQ(off.model.R_max, off.model.R_kept());
  // Solved on the exact rows only: no EIM of kappa, and the EIM rows are refused.
  EXPECT_EQ(off.model.Mk_max, 0);
  EXPECT_TRUE(off.model.C_kappa.empty());
  EXPECT_EQ(off.report.eim_kappa_status, "not built: the cone is solved on the exact contact rows");
  OnlineSolver solver(off.model);
  {
    OnlineSettings eim = tight_online();
    eim.contact_rows = contactrb::online::ContactRows::Eim;
    EXPECT_THROW((void)solver.solve(set.snapshots.front().mu, eim), contactrb::Error);
  }
  OnlineSettings exact = tight_online();
  OnlineSettings full = exact;
  full.restricted_rows = false;
  for (const auto& snap : set.snapshots) {
    const auto a = solver.solve(snap.mu, exact);
    ASSERT_TRUE(a.converged()) << a.message;
    const auto b = solver.solve(snap.mu, full);
    ASSERT_EQ(a.status, b.status);
    EXPECT_LT((a.u_hat - b.u_hat).norm(), 1e-10 * a.u_hat.norm());
    EXPECT_LT((a.lambda_hat - b.lambda_hat).norm(), 1e-10 * std::max(1.0, a.lambda_hat.norm()));
    const Eigen::VectorXd lambda = contactrb::online::reconstruct_multipliers(off.reconstruction, snap.mu, a.lambda_hat);
    EXPECT_LT((lambda - snap.lambda).norm(), 1e-6 * snap.lambda.norm()) << "mu = " << snap.mu(0);
    const Eigen::VectorXd u =
        contactrb::online::reconstruct_displacement(off.reconstruction, snap.mu, a.u_hat);
    EXPECT_LT((u - snap.u).norm(), 1e-6 * snap.u.norm()) << "mu = " << snap.mu(0);
    // The estimate from the exact rows is available and small there.
    ASSERT_TRUE(a.estimate.available);
    EXPECT_TRUE(a.estimate.exact);
  }
}

// The reduced semi-smooth Newton (OnlineIteration::Newton) on a row-cone model reaches the fixed
// point of the accelerated iteration at a tight tolerance, in a few steps where the fixed point
// needs tens, and its answer carries a smaller estimate (no complementarity lag of the last step).
TEST_P(OfflineOnline, ReducedNewtonReachesTheFixedPointInFewSteps) {
  const SnapshotSet& set = snapshots(GetParam());
  OfflineSettings s = test_support::cpg_settings();
  s.dual_method = contactrb::offline::DualConeMethod::Rows;
  const OfflineResult off =
      contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec(GetParam()), s);
  OnlineSolver solver(off.model);
  OnlineSettings fixed_point;
  fixed_point.kacanov = contactrb::solve::KacanovSettings{1.0, 1e-10, 2000};
  fixed_point.iteration = contactrb::online::OnlineIteration::Accelerated;
  OnlineSettings newton = fixed_point;
  newton.iteration = contactrb::online::OnlineIteration::Newton;
  newton.kacanov->max_iterations = 30;
  for (const double mu : verification_values().at(GetParam())) {
    const auto a = solver.solve(mu, fixed_point);
    const auto b = solver.solve(mu, newton);
    ASSERT_TRUE(a.converged()) << a.message;
    ASSERT_TRUE(b.converged()) << b.message;
    std::printf("[ %s mu %.4g ] accelerated %d steps, Newton %d steps, estimate %.3e / %.3e\n", GetParam().c_str(), mu,
                a.iterations, b.iterations, a.estimate.energy, b.estimate.energy);
    EXPECT_LE(b.iterations, 10) << "mu = " << mu;
    EXPECT_LT((a.u_hat - b.u_hat).norm(), 1e-7 * a.u_hat.norm()) << "mu = " << mu;
    EXPECT_LT((a.lambda_hat - b.lambda_hat).norm(), 1e-6 * a.lambda_hat.norm()) << "mu = " << mu;
    EXPECT_GE(b.lambda_hat.minCoeff(), 0.0);
  }
}

// An explicit start (OnlineSettings::start) at the converged answer: the accelerated iteration
// (on the truncated CPG model) stops after one step, the reduced Newton (on the row-cone model,
// the greedy's sweep) after two (its test needs the same active set twice), at the same answer.
// A start of another size is refused with the sizes in the message.
TEST_P(OfflineOnline, ExplicitStartAtTheAnswerConvergesAtOnce) {
  const SnapshotSet& set = snapshots(GetParam());
  const double mu = verification_values().at(GetParam()).front();
  OnlineSettings accelerated;
  accelerated.kacanov = contactrb::solve::KacanovSettings{1.0, 1e-10, 500};
  accelerated.iteration = contactrb::online::OnlineIteration::Accelerated;
  OnlineSettings newton = accelerated;
  newton.iteration = contactrb::online::OnlineIteration::Newton;
  const OfflineResult cpg = truncated_model(set, GetParam());
  const OfflineResult rows =
      contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec(GetParam()), OfflineSettings{});
  for (const bool is_newton : {false, true}) {
    SCOPED_TRACE(is_newton ? "Newton, row cone" : "accelerated, CPG cone");
    OnlineSolver solver(is_newton ? rows.model : cpg.model);
    const OnlineSettings& cold = is_newton ? newton : accelerated;
    const auto ref = solver.solve(mu, cold);
    ASSERT_TRUE(ref.converged()) << ref.message;
    ASSERT_GT(ref.iterations, is_newton ? 2 : 1);
    OnlineSettings warm = cold;
    warm.start = Eigen::VectorXd(solver.N() + solver.R());
    *warm.start << ref.u_hat, ref.lambda_hat;
    const auto w = solver.solve(mu, warm);
    ASSERT_TRUE(w.converged()) << w.message;
    EXPECT_EQ(w.iterations, is_newton ? 2 : 1);
    EXPECT_LE((w.u_hat - ref.u_hat).norm(), 1e-9 * ref.u_hat.norm());
    EXPECT_LE((w.lambda_hat - ref.lambda_hat).norm(), 1e-9 * ref.lambda_hat.norm());
    EXPECT_NEAR(w.energy, ref.energy, 1e-12 * std::abs(ref.energy));
  }
  OnlineSolver solver(cpg.model);
  OnlineSettings wrong = accelerated;
  wrong.start = Eigen::VectorXd::Zero(solver.N() + solver.R() + 1);
  const std::string sizes = "size N + R = " + std::to_string(solver.N()) + " + " + std::to_string(solver.R()) + " = " +
                            std::to_string(solver.N() + solver.R()) + " (got " +
                            std::to_string(solver.N() + solver.R() + 1) + " entries)";
  try {
    solver.solve(mu, wrong);
    ADD_FAILURE() << "a start of the wrong size was accepted";
  } catch (const contactrb::Error& e) {
    EXPECT_NE(std::string(e.what()).find("OnlineSettings::start must be a finite [u_hat; lambda_hat] of " + sizes),
              std::string::npos)
        << e.what();
  }
  wrong.start = Eigen::VectorXd::Zero(solver.N() + solver.R());
  (*wrong.start)(0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solver.solve(mu, wrong), contactrb::Error);
  // The solver still answers after the refusals.
  EXPECT_TRUE(solver.solve(mu, accelerated).converged());
}

// The interpolated initial guess (the reduced solutions at the training values, linear in mu)
// reaches the same fixed point within the Kacanov tolerance in fewer steps than the zero start,
// and in one step at a training value, where it is the fixed point itself.
TEST_P(OfflineOnline, InterpolatedInitialGuessSavesStepsAndKeepsTheFixedPoint) {
  const SnapshotSet& set = snapshots(GetParam());
  const OfflineResult off = truncated_model(set, GetParam());
  ASSERT_EQ(off.model.training_mu.size(), set.snapshots.size());
  OnlineSolver solver(off.model);
  constexpr double kEps = 1e-3;
  const OnlineSettings fixed_point = reduced_fixed_point();
  OnlineSettings cold;
  cold.kacanov = contactrb::solve::KacanovSettings{1.0, kEps, 500};
  cold.iteration = contactrb::online::OnlineIteration::Accelerated;
  cold.initial_guess = contactrb::online::InitialGuess::Zero;
  OnlineSettings warm = cold;
  warm.initial_guess = contactrb::online::InitialGuess::Interpolated;
  int cold_steps = 0, warm_steps = 0;
  for (const double mu : verification_values().at(GetParam())) {
    const auto ref = solver.solve(mu, fixed_point);
    const auto c = solver.solve(mu, cold);
    const auto w = solver.solve(mu, warm);
    ASSERT_TRUE(ref.converged()) << "mu = " << mu << ": " << ref.message;
    ASSERT_TRUE(c.converged()) << "mu = " << mu << ": " << c.message;
    ASSERT_TRUE(w.converged()) << "mu = " << mu << ": " << w.message;
    EXPECT_LE(w.iterations, c.iterations) << "mu = " << mu;
    cold_steps += c.iterations;
    warm_steps += w.iterations;
    EXPECT_LT((w.u_hat - ref.u_hat).norm(), kEps * ref.u_hat.norm()) << "mu = " << mu;
    EXPECT_LT((w.lambda_hat - ref.lambda_hat).norm(), 10 * kEps * ref.lambda_hat.norm()) << "mu = " << mu;
  }
  std::printf("[ %s ] Kacanov steps over the verification values: zero start %d, interpolated %d\n",
              GetParam().c_str(), cold_steps, warm_steps);
  EXPECT_LT(warm_steps, cold_steps);
  // At a training value the guess is the reduced solution (snapshot tolerance 1e-10): one step.
  const double mu_train = set.snapshots[2].mu(0);
  const auto t = solver.solve(mu_train, warm);
  ASSERT_TRUE(t.converged());
  EXPECT_EQ(t.iterations, 1);
  EXPECT_LT((t.u_hat - solver.solve(mu_train, fixed_point).u_hat).norm(), 1e-8 * t.u_hat.norm());
}

// The accelerated iteration (OnlineIteration::Accelerated: undamped, Anderson-mixed,
// safeguarded) reaches the fixed point of the relaxed iteration (paper (12), alpha = 0.3)
// within the Kacanov tolerance, in fewer steps; at the verification values, truncated model.
TEST_P(OfflineOnline, AcceleratedIterationReachesTheRelaxedFixedPoint) {
  const SnapshotSet& set = snapshots(GetParam());
  const OfflineResult off = truncated_model(set, GetParam());
  OnlineSolver solver(off.model);
  constexpr double kEps = 1e-3;  // the paper's eps_KA
  const OnlineSettings fixed_point = reduced_fixed_point();
  OnlineSettings relaxed;
  relaxed.kacanov = contactrb::solve::KacanovSettings{0.3, kEps, 500};
  relaxed.iteration = contactrb::online::OnlineIteration::Relaxed;
  relaxed.initial_guess = contactrb::online::InitialGuess::Zero;  // both from the paper's start
  for (const double mu : verification_values().at(GetParam())) {
    const auto ref = solver.solve(mu, fixed_point);
    ASSERT_TRUE(ref.converged()) << ref.message;
    const auto r = solver.solve(mu, relaxed);
    ASSERT_TRUE(r.converged()) << r.message;
    for (int depth : {0, 1, 3}) {
      OnlineSettings accelerated = relaxed;
      accelerated.iteration = contactrb::online::OnlineIteration::Accelerated;
      accelerated.anderson_depth = depth;
      const auto a = solver.solve(mu, accelerated);
      ASSERT_TRUE(a.converged()) << "mu = " << mu << ", depth " << depth << ": " << a.message;
      // Residual test at alpha = 1: |G(u) - u| <= eps |u|, and G contracts; the relaxed
      // iterate's distance to the fixed point is of the same order.
      const double du = (a.u_hat - ref.u_hat).norm() / ref.u_hat.norm();
      const double dl = (a.lambda_hat - ref.lambda_hat).norm() / ref.lambda_hat.norm();
      std::printf("[ %s ] mu = %.4f depth %d: %d steps (relaxed %d); |u - u*|/|u*| %.2e (relaxed %.2e), lambda %.2e\n",
                  GetParam().c_str(), mu, depth, a.iterations, r.iterations, du,
                  (r.u_hat - ref.u_hat).norm() / ref.u_hat.norm(), dl);
      EXPECT_LT(du, kEps);
      EXPECT_LT(dl, 10 * kEps);
      EXPECT_LT(a.iterations, r.iterations);
      EXPECT_NEAR(a.energy, ref.energy, kEps * std::abs(ref.energy));
    }
    // Tight tolerance: the same fixed point to round-off.
    OnlineSettings tight = fixed_point;
    tight.iteration = contactrb::online::OnlineIteration::Accelerated;
    tight.kacanov->tolerance = 1e-10;
    const auto t = solver.solve(mu, tight);
    ASSERT_TRUE(t.converged()) << t.message;
    EXPECT_LT((t.u_hat - ref.u_hat).norm(), 1e-8 * ref.u_hat.norm());
    EXPECT_LT((t.lambda_hat - ref.lambda_hat).norm(), 1e-7 * ref.lambda_hat.norm());
  }
}

// Automatic: accelerated without explicit Kacanov settings, relaxed (the given alpha) with them.
TEST(OnlineSolver, AutomaticIterationHonoursAnExplicitAlpha) {
  const SnapshotSet& set = snapshots("hertz-b");
  const OfflineResult off =
      contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec("hertz-b"), untruncated(true));
  OnlineSolver solver(off.model);
  const double mu = verification_values().at("hertz-b")[1];
  OnlineSettings given;
  given.kacanov = contactrb::solve::KacanovSettings{0.3, 1e-6, 500};
  OnlineSettings relaxed = given;
  relaxed.iteration = contactrb::online::OnlineIteration::Relaxed;
  OnlineSettings accelerated = given;
  accelerated.iteration = contactrb::online::OnlineIteration::Accelerated;
  const auto a = solver.solve(mu, given);
  const auto b = solver.solve(mu, relaxed);
  const auto c = solver.solve(mu, accelerated);
  ASSERT_TRUE(a.converged() && b.converged() && c.converged());
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.u_hat, b.u_hat);
  EXPECT_LT(c.iterations, b.iterations);
  // Default settings: the model's (snapshot) tolerance 1e-10, accelerated.
  const auto d = solver.solve(mu);
  ASSERT_TRUE(d.converged()) << d.message;
  EXPECT_LT((d.u_hat - b.u_hat).norm(), 1e-5 * b.u_hat.norm());
  OnlineSettings bad;
  bad.anderson_depth = 9;
  EXPECT_THROW(solver.solve(mu, bad), contactrb::Error);
  bad.anderson_depth = -1;
  EXPECT_THROW(solver.solve(mu, bad), contactrb::Error);
}

TEST_P(OfflineOnline, LeadingSubBlocksEqualModelBuiltAtThoseSizes) {
  const SnapshotSet& set = snapshots(GetParam());
  const auto spec = contactrb::cases::builtin_case_spec(GetParam());
  // The POD part of the convention: supremizers come after every POD mode, so the leading
  // N = 3 block of an enriched basis holds no supremizer (tested apart below).
  OfflineSettings full_settings = untruncated(true);
  full_settings.supremizers = false;
  const OfflineResult full = contactrb::offline::build_reduced_model(set, spec, full_settings);
  OfflineSettings small = full_settings;
  small.pod_modes = 3;
  small.dual_size = 2;
  small.eim_k_size = 3;
  small.eim_g_size = 3;
  const OfflineResult part = contactrb::offline::build_reduced_model(set, spec, small);
  ASSERT_EQ(part.model.N_max, 3);
  ASSERT_EQ(part.model.R_max, 2);
  OnlineSolver from_blocks(full.model, OnlineSizes{3, 2, 3, 3});
  OnlineSolver from_part(part.model);
  OnlineSettings settings;
  settings.kacanov = contactrb::solve::KacanovSettings{0.5, 1e-9, 500};
  const Eigen::VectorXd mu = set.snapshots[2].mu;
  const auto a = from_blocks.solve(mu, settings);
  const auto b = from_part.solve(mu, settings);
  ASSERT_EQ(a.status, b.status);
  // POD modes are defined up to sign: compare the reconstructions.
  const Eigen::VectorXd ua = contactrb::online::reconstruct_displacement(full.reconstruction, mu, a.u_hat);
  const Eigen::VectorXd ub = contactrb::online::reconstruct_displacement(part.reconstruction, mu, b.u_hat);
  EXPECT_LT((ua - ub).norm(), 1e-8 * ub.norm());
  EXPECT_NEAR(a.energy, b.energy, 1e-8 * std::abs(b.energy));
}

TEST_P(OfflineOnline, ErrorsFallAsSizesGrow) {
  const SnapshotSet& set = snapshots(GetParam());
  const auto spec = contactrb::cases::builtin_case_spec(GetParam());
  const OfflineResult off = contactrb::offline::build_reduced_model(set, spec, untruncated(true));
  const auto& m = off.model;
  OnlineSettings settings;
  settings.kacanov = contactrb::solve::KacanovSettings{0.5, 1e-9, 1000};
  std::vector<OnlineSizes> levels{{2, 1, std::min(2, m.Mk_max), std::min(2, m.Mg_max)},
                                  {m.N_max, m.R_max, m.Mk_max, m.Mg_max}};
  std::vector<double> worst;
  for (const OnlineSizes& s : levels) {
    OnlineSolver solver(m, s);
    double w = 0.0;
    // Odd training points, so the loose model is not exact by construction.
    for (std::size_t p = 1; p < set.snapshots.size(); p += 2) w = std::max(w, compare(off, solver, set, p, settings).u);
    std::printf("[ %s ] N=%d R=%d Mk=%d Mg=%d: max rel err u %.3e\n", GetParam().c_str(), s.N, s.R, s.Mk, s.Mg, w);
    worst.push_back(w);
  }
  EXPECT_GT(worst[0], 10.0 * worst[1]);
}

TEST_P(OfflineOnline, ReportHoldsTheHistoriesAndTimes) {
  const SnapshotSet& set = snapshots(GetParam());
  const OfflineResult off =
      contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec(GetParam()), untruncated(true));
  const auto& rep = off.report;
  const auto& m = off.model;
  EXPECT_EQ(rep.singular_values.size(), static_cast<Eigen::Index>(set.snapshots.size()));
  EXPECT_EQ(rep.N, m.N_max);
  EXPECT_EQ(rep.R, m.R_max);
  EXPECT_EQ(rep.Mk, m.Mk_max);
  EXPECT_EQ(rep.Mg, m.Mg_max);
  ASSERT_EQ(rep.dual_errors.size(), static_cast<std::size_t>(rep.R + 1));
  for (std::size_t i = 1; i < rep.dual_errors.size(); ++i) EXPECT_LE(rep.dual_errors[i], rep.dual_errors[i - 1]);
  EXPECT_LE(rep.dual_errors.back(), 1e-10 * rep.dual_errors.front());
  EXPECT_EQ(rep.eim_kappa_errors.size(), static_cast<std::size_t>(rep.Mk + 1));
  EXPECT_EQ(rep.eim_gamma_errors.size(), static_cast<std::size_t>(rep.Mg + 1));
  EXPECT_GE(rep.dual_condition_number, 1.0);
  EXPECT_EQ(rep.R_kept, m.R_kept());
  EXPECT_EQ(rep.R_hf, m.surface.num_constraints);
  for (double t : {rep.assembly_s, rep.pod_s, rep.dual_s, rep.eim_kappa_s, rep.eim_gamma_s, rep.reduction_s}) {
    EXPECT_GE(t, 0.0);
    EXPECT_LE(t, rep.total_s);
  }
  std::printf("[ %s ] offline %.3f s (assembly %.3f, POD %.4f, dual %.4f, EIM k %.4f, EIM g %.4f, reduction %.4f)\n",
              GetParam().c_str(), rep.total_s, rep.assembly_s, rep.pod_s, rep.dual_s, rep.eim_kappa_s, rep.eim_gamma_s,
              rep.reduction_s);
}

TEST_P(OfflineOnline, ModelHoldsNoHighFidelitySizeArray) {
  const SnapshotSet& set = snapshots(GetParam());
  const auto spec = contactrb::cases::builtin_case_spec(GetParam());
  const OfflineResult off = contactrb::offline::build_reduced_model(set, spec, untruncated(true));
  const auto& m = off.model;
  const int n_free = static_cast<int>(set.free_dofs.size());
  const int n_c = static_cast<int>(set.contact_dofs.size());
  ASSERT_LT(n_c, n_free / 4);  // the contact surface is a small part of the mesh
  EXPECT_EQ(m.Theta_c.rows(), n_c);
  EXPECT_EQ(m.lift_c.rows(), n_c);
  EXPECT_EQ(m.Xi.rows(), m.R_kept());
  EXPECT_LE(m.R_kept(), m.surface.num_constraints);
  for (const auto& A : m.A_hat) EXPECT_EQ(A.rows(), m.N_max);
  for (const auto& C : m.C_kappa) EXPECT_EQ(C.rows(), m.R_max);
  EXPECT_EQ(m.surface.num_dofs(), n_c);
  // The initial-guess data: reduced coordinates per training value.
  EXPECT_EQ(m.training_u_hat.rows(), m.N_max);
  EXPECT_EQ(m.training_lambda_hat.rows(), m.R_max);
  EXPECT_EQ(m.training_u_hat.cols(), static_cast<Eigen::Index>(set.snapshots.size()));
  // Every array together is smaller than one HF displacement per reduced dimension.
  EXPECT_LT(contactrb::model::model_doubles(m),
            static_cast<long long>(n_c) * (m.N_max + m.R_max + m.J_lift() + 4) +
                50LL * (m.N_max + m.R_max + m.Mk_max + m.Mg_max + 1) * (m.N_max + m.R_max + m.Mk_max + m.Mg_max + 1));
  std::printf("[ %s ] model: %lld doubles; HF: %d DOFs, %d free, %d contact DOFs\n", GetParam().c_str(),
              contactrb::model::model_doubles(m), set.num_dofs, n_free, n_c);
}

INSTANTIATE_TEST_SUITE_P(Cases, OfflineOnline, ::testing::Values("hertz-a", "hertz-b"),
                         [](const auto& info) { return info.param == "hertz-a" ? "HertzA" : "HertzB"; });

TEST(OnlineSolver, RejectsSizesAboveTheMaximaAndMuOutsideTheDomain) {
  const SnapshotSet& set = snapshots("hertz-a");
  const OfflineResult off =
      contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec("hertz-a"), untruncated(true));
  EXPECT_THROW(OnlineSolver(off.model, OnlineSizes{off.model.N_max + 1, -1, -1, -1}), contactrb::Error);
  EXPECT_THROW(OnlineSolver(off.model, OnlineSizes{0, -1, -1, -1}), contactrb::Error);
  OnlineSolver solver(off.model);
  EXPECT_THROW(solver.solve(10.0), contactrb::Error);
  contactrb::model::ReducedModel broken = off.model;
  broken.C_kappa.pop_back();
  EXPECT_THROW(OnlineSolver{broken}, contactrb::Error);
}

// Huge EIM tolerances give M^k = M^g = 0: such a model is refused (its online answers would be
// undetermined).
TEST(OfflineBuilder, RefusesAModelWithoutEIMFunctions) {
  const SnapshotSet& set = snapshots("hertz-a");
  const auto spec = contactrb::cases::builtin_case_spec("hertz-a");
  const auto expect_refused = [&](const OfflineSettings& s, const std::string& words) {
    try {
      contactrb::offline::build_reduced_model(set, spec, s);
      ADD_FAILURE() << "no error for " << words;
    } catch (const contactrb::Error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  OfflineSettings loose_k = test_support::cpg_settings();
  loose_k.eps_eim_k = 1e9;
  expect_refused(loose_k, "M^k = 0");
  OfflineSettings loose_g = test_support::cpg_settings();
  loose_g.eps_eim_g = 1e9;
  expect_refused(loose_g, "M^g = 0");
  OfflineSettings zero_g = test_support::cpg_settings();
  zero_g.eim_g_size = 0;
  expect_refused(zero_g, "M^g = 0");
}

// Every failure path of the online solver returns defined outputs: a model stripped of its
// kappa interpolation (M^k = 0, as an older build wrote) fails at the first step; u_hat and
// lambda_hat are zero, energy and force those of u_hat = 0. Run twice on each iteration so that
// a reused heap block would show up.
// With supremizers, N below N_max cuts them (they are the last basis vectors). R > N then leaves
// the reduced pressure undetermined (Q = D A_hat^-1 D' has rank <= N < R): a non-converged
// status naming the sizes, never "converged"; the same R with the full N is an answer.
TEST(OnlineSolver, ATruncationThatLeavesThePressureUndeterminedIsNotConverged) {
  const SnapshotSet& set = snapshots("hertz-a");
  const OfflineResult off = truncated_model(set, "hertz-a");
  const auto& m = off.model;
  ASSERT_GT(m.N_supremizers, 0);
  ASSERT_GE(m.R_max, 2);
  const double mu = set.snapshots[1].mu(0);
  OnlineSolver cut(m, OnlineSizes{1, m.R_max, -1, -1});
  const contactrb::online::OnlineSolution s = cut.solve(mu);
  EXPECT_EQ(s.status, contactrb::solve::KacanovStatus::StepFailed);
  EXPECT_FALSE(s.converged());
  EXPECT_NE(s.message.find("the reduced pressure is not determined at N = 1, R = " + std::to_string(m.R_max)),
            std::string::npos)
      << s.message;
  EXPECT_FALSE(s.estimate.available);
  OnlineSolver full(m, OnlineSizes{-1, m.R_max, -1, -1});
  EXPECT_TRUE(full.solve(mu).converged());
  // R <= N with supremizers cut: determined (the pair keeps a positive inf-sup constant).
  OnlineSolver fewer(m, OnlineSizes{m.N_max - 1, 1, -1, -1});
  EXPECT_TRUE(fewer.solve(mu).converged());
}

// A model whose EIM contact operator (54) vanishes (every C_kappa zero): the first step fails,
// and the answer is zeros with the status and the reason, not garbage. Without an EIM of kappa at
// all (M^k = 0, as the row and registered cones) the EIM rows are refused before any step.
TEST(OnlineSolver, FailedFirstStepReturnsZerosNotGarbage) {
  const SnapshotSet& set = snapshots("hertz-a");
  OfflineResult off = truncated_model(set, "hertz-a");
  contactrb::model::ReducedModel m = off.model;
  ASSERT_NE(m.dual_method, contactrb::model::kRowCone);
  ASSERT_GT(m.Mk_max, 0);
  for (Eigen::MatrixXd& C : m.C_kappa) C.setZero();
  m.estimate = {};  // of the original C_kappa
  {
    contactrb::model::ReducedModel none = m;
    none.Mk_max = 0;
    none.kappa_row.clear();
    none.kappa_dof.clear();
    none.C_kappa.clear();
    none.B_kappa.resize(0, 0);
    OnlineSolver without(none);
    OnlineSettings eim;
    eim.contact_rows = contactrb::online::ContactRows::Eim;
    EXPECT_THROW(
        {
          try {
            (void)without.solve(0.3, eim);
          } catch (const contactrb::Error& e) {
            EXPECT_NE(std::string(e.what()).find("solved on the exact contact rows only"), std::string::npos) << e.what();
            throw;
          }
        },
        contactrb::Error);
  }
  OnlineSolver solver(m);
  for (auto iteration : {contactrb::online::OnlineIteration::Accelerated, contactrb::online::OnlineIteration::Relaxed,
                         contactrb::online::OnlineIteration::Accelerated}) {
    OnlineSettings s;
    s.iteration = iteration;
    if (iteration == contactrb::online::OnlineIteration::Relaxed) s.kacanov = contactrb::solve::KacanovSettings{};
    const contactrb::online::OnlineSolution sol = solver.solve(0.3, s);
    EXPECT_FALSE(sol.converged());
    EXPECT_EQ(sol.status, contactrb::solve::KacanovStatus::StepFailed);
    EXPECT_NE(sol.message.find("D^kappa vanishes"), std::string::npos) << sol.message;
    ASSERT_EQ(sol.u_hat.size(), solver.N());
    ASSERT_EQ(sol.lambda_hat.size(), solver.R());
    EXPECT_EQ(sol.u_hat.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(sol.lambda_hat.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(sol.contact_force, 0.0);
    EXPECT_TRUE(std::isfinite(sol.energy));
    // The energy of u = u_D(mu) alone: hertz-a has no body load, so 1/2 u_D' A u_D > 0.
    EXPECT_GT(sol.energy, 0.0);
  }
}

// A result whose energy or force is not finite is never "converged". The
// lift energy 1/2 u_D' A u_D enters only the energy, so a model whose lift_AA overflows (inf)
// solves as usual and converges; unchecked it would be reported as converged with energy inf
// (JSON null). A right-hand side scaled by 1e300 makes u_hat itself overflow the
// geometry: a failure status too.
TEST(OnlineSolver, NonFiniteResultsAreFlaggedNeverConverged) {
  const SnapshotSet& set = snapshots("hertz-a");
  const OfflineResult off = truncated_model(set, "hertz-a");
  OnlineSolver reference(off.model);
  const contactrb::online::OnlineSolution good = reference.solve(0.3);
  ASSERT_TRUE(good.converged()) << good.message;
  ASSERT_TRUE(std::isfinite(good.energy));

  contactrb::model::ReducedModel m = off.model;
  for (double& v : m.lift_AA) v = std::numeric_limits<double>::infinity();
  OnlineSolver huge_lift(m);
  const contactrb::online::OnlineSolution a = huge_lift.solve(0.3);
  EXPECT_EQ(a.status, contactrb::solve::KacanovStatus::NonFinite) << a.message;
  EXPECT_FALSE(a.converged());
  EXPECT_FALSE(std::isfinite(a.energy));
  EXPECT_NE(a.message.find("is not finite"), std::string::npos) << a.message;
  EXPECT_EQ(a.u_hat, good.u_hat);  // the solve itself is the same

  m = off.model;
  for (Eigen::VectorXd& f : m.f_hat) f *= 1e300;
  for (Eigen::VectorXd& f : m.A_lift_hat) f *= 1e300;
  OnlineSolver huge_load(m);
  const contactrb::online::OnlineSolution b = huge_load.solve(0.3);
  EXPECT_FALSE(b.converged()) << "energy " << b.energy;
  EXPECT_NE(b.status, contactrb::solve::KacanovStatus::Converged);
  EXPECT_FALSE(b.message.empty());
  std::printf("  lift_AA inf: %s: %s\n  f_hat 1e300: %s: %s\n", to_string(a.status), a.message.c_str(),
              to_string(b.status), b.message.c_str());
}

TEST(OfflineBuilder, RejectsFailedSnapshotsAndBadSettings) {
  SnapshotSet set = snapshots("hertz-a");
  const auto spec = contactrb::cases::builtin_case_spec("hertz-a");
  OfflineSettings bad;
  bad.eps_pod = -1.0;
  EXPECT_THROW(contactrb::offline::build_reduced_model(set, spec, bad), contactrb::Error);
  set.snapshots[1].converged = false;
  set.snapshots[1].status = "max_iterations";
  try {
    (void)contactrb::offline::build_reduced_model(set, spec);
    ADD_FAILURE() << "a failed snapshot was accepted";
  } catch (const contactrb::Error& e) {
    EXPECT_NE(std::string(e.what()).find("did not converge"), std::string::npos) << e.what();
  }
}

// The builder is a library entry point: a set that did not come through read_snapshot_file is
// checked before any index is used (an out-of-range free DOF would crash in setFromTriplets),
// and a repeated training value is refused (a set of one repeated value gives a model that
// answers a contact force 45 times the HF one, "converged").
TEST(OfflineBuilder, RefusesBadIndicesAndRepeatedTrainingValues) {
  const SnapshotSet good = snapshots("hertz-a");
  const auto spec = contactrb::cases::builtin_case_spec("hertz-a");
  const auto expect_refused = [&](const SnapshotSet& set, const std::string& words) {
    try {
      (void)contactrb::offline::build_reduced_model(set, spec);
      ADD_FAILURE() << "accepted; expected an error with '" << words << "'";
    } catch (const contactrb::Error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  SnapshotSet set = good;
  set.free_dofs[4] = good.num_dofs + 1000;
  expect_refused(set, "offline: inconsistent snapshot set: /discretization/free_dofs[4]");
  set = good;
  set.free_dofs[0] = -1;
  expect_refused(set, "/discretization/free_dofs[0] = -1 is outside");
  set = good;
  set.free_dofs[1] = set.free_dofs[0];
  expect_refused(set, "appears twice");
  set = good;
  set.master.back() = good.num_dofs;  // a node index: num_dofs / 2 nodes
  expect_refused(set, "/discretization/master[");
  set = good;
  set.snapshots[0].u0(3) = std::numeric_limits<double>::quiet_NaN();
  expect_refused(set, "/snapshots/000000/u0 holds a non-finite value");
  set = good;
  set.snapshots[2] = set.snapshots[1];
  expect_refused(set, "the training value mu = 0.21 appears twice (snapshots 1 and 2)");
}

}  // namespace

namespace {

// LAC rows (exactly integrated, lac_integration.hpp) on the triangle-free contact-surface mesh,
// a mapped slave body (ring radius): the untruncated model reproduces the training snapshots.
const SnapshotSet& ring_block_snapshots() {
  static const SnapshotSet set = [] {
    contactrb::offline::SnapshotRequest r = contactrb::offline::make_snapshot_request(
        contactrb::cases::builtin_case_spec("ring-block"), "training", 0, std::nullopt,
        contactrb::cases::points_1d({0.95, 1.0, 1.05, 1.1, 1.15}));
    r.settings.kacanov.alpha = 1.0;
    r.settings.kacanov.tolerance = kTightTolerance;
    contactrb::offline::SnapshotRunOptions options;
    options.jobs = 2;
    return contactrb::offline::generate_snapshots(r, options);
  }();
  return set;
}

TEST(OfflineOnlineRingBlock, UntruncatedLACModelReproducesTrainingSnapshots) {
  const auto spec = contactrb::cases::builtin_case_spec("ring-block");
  const SnapshotSet& set = ring_block_snapshots();
  ASSERT_EQ(set.num_failed(), 0) << set.snapshots[0].message;
  const OfflineResult off = contactrb::offline::build_reduced_model(set, spec, untruncated(true));
  OnlineSolver solver(off.model);
  double worst_u = 0.0, worst_l = 0.0;
  for (std::size_t p = 0; p < set.snapshots.size(); ++p) {
    const Errors e = compare(off, solver, set, p, tight_online());
    worst_u = std::max(worst_u, e.u);
    worst_l = std::max(worst_l, e.lambda);
  }
  std::printf("[ ring-block ] N=%d R=%d Mk=%d Mg=%d: max rel err u %.3e, lambda %.3e\n", off.model.N_max,
              off.model.R_max, off.model.Mk_max, off.model.Mg_max, worst_u, worst_l);
  EXPECT_LT(worst_u, 1e-6);
  EXPECT_LT(worst_l, 1e-6);
}

// Exactly integrated LAC: the restricted evaluation (the magic rows integrated from their own
// slave nodes, contact::integrate_lac_rows with a row list) against every row of the contact
// surface; same steps, same answer, at values between the training ones.
TEST(OfflineOnlineRingBlock, RestrictedLACRowsEqualFullRows) {
  const SnapshotSet& set = ring_block_snapshots();
  ASSERT_EQ(set.num_failed(), 0) << set.snapshots[0].message;
  OfflineSettings s = test_support::cpg_settings();
  s.eps_pod = 0.0;
  s.dual_size = 3;
  s.eim_k_size = 4;
  s.eim_g_size = 3;
  const OfflineResult off =
      contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec("ring-block"), s);
  ASSERT_EQ(off.model.Mk_max, 4);
  OnlineSolver solver(off.model);
  OnlineSettings full;
  full.restricted_rows = false;
  OnlineSettings restricted = full;
  restricted.restricted_rows = true;
  for (const double mu : {0.975, 1.075, 1.125}) {
    const auto a = solver.solve(mu, full);
    const auto b = solver.solve(mu, restricted);
    ASSERT_TRUE(a.converged()) << a.message;
    ASSERT_EQ(a.status, b.status);
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_LT((a.u_hat - b.u_hat).norm(), 1e-12 * a.u_hat.norm());
    EXPECT_LT((a.lambda_hat - b.lambda_hat).norm(), 1e-12 * std::max(1.0, a.lambda_hat.norm()));
  }
}

// Dual cone by NMF (fixed R: truncated NMF) builds and solves; the time of one online query
// at the paper's Kacanov settings is printed (no assertion on time: shared machines).
TEST(OfflineOnlineNMF, TruncatedNMFModelSolves) {
  const SnapshotSet& set = snapshots("hertz-b");
  OfflineSettings s = untruncated(true);
  s.dual_method = contactrb::offline::DualConeMethod::NMF;
  s.dual_size = 3;
  const OfflineResult off =
      contactrb::offline::build_reduced_model(set, contactrb::cases::builtin_case_spec("hertz-b"), s);
  EXPECT_EQ(off.model.R_max, 3);
  EXPECT_GE(off.model.Xi.minCoeff(), 0.0);
  OnlineSolver solver(off.model);
  OnlineSettings paper;
  paper.kacanov = contactrb::solve::KacanovSettings{0.3, 1e-3, 500};
  std::vector<double> times;
  for (int rep = 0; rep < 20; ++rep) {
    const auto sol = solver.solve(set.snapshots[3].mu, paper);
    ASSERT_TRUE(sol.converged()) << sol.message;
    times.push_back(sol.time_s);
  }
  std::sort(times.begin(), times.end());
  const Errors e = compare(off, solver, set, 3, paper);
  std::printf("[ hertz-b NMF R=3 ] rel err u %.3e, lambda %.3e; online median %.1f us, %d Kacanov iterations\n",
              e.u, e.lambda, 1e6 * times[times.size() / 2], solver.solve(set.snapshots[3].mu, paper).iterations);
  EXPECT_LT(e.u, 5e-2);
}

}  // namespace
