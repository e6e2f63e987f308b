// Weak greedy on the error estimate (offline/offline_greedy.hpp): on hertz-a level 0
// with 61 equispaced training values the max relative estimate falls (trend asserted, a few
// non-monotone steps allowed), the greedy stops at its tolerance with fewer HF solves than
// training values, the estimate at each chosen point is not below the true error measured there
// against the new HF snapshot, and the final model meets the tolerance on the verification set
// (e_displ of the evaluation module). Also: the reduced energy norm against the HF-size one, a
// deterministic result whatever the number of threads, the Budget status, builds from 1, 2 and 3
// snapshots, the start point, and the bad settings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/parameter.hpp"
#include "contactrb/cases/theta.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/study/evaluation.hpp"
#include "contactrb/offline/dual_cone.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/offline_greedy.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/reconstruction.hpp"

namespace {

using contactrb::offline::GreedyOfflineResult;
using contactrb::offline::GreedyOfflineSettings;
using contactrb::offline::GreedyOfflineStatus;

// A tolerance the hertz-a estimate reaches in about 25 steps (its floor is near 1.4e-2 at the
// default offline tolerances: docs/offline-online.md, "Greedy sampling").
constexpr double kTolerance = 5e-2;
constexpr int kTrainingSize = 61;

const contactrb::cases::CaseSpec& spec() {
  static const contactrb::cases::CaseSpec s = contactrb::cases::builtin_case_spec("hertz-a");
  return s;
}

std::vector<contactrb::cases::Mu> dense_training() {
  std::vector<double> v = contactrb::cases::arithmetic_set(0.15, 0.3 / (kTrainingSize - 1), kTrainingSize);
  v.back() = 0.45;
  std::vector<contactrb::cases::Mu> points;
  for (double x : v) points.push_back(contactrb::cases::Mu::Constant(1, x));
  return points;
}

const contactrb::offline::SnapshotRequest& request() {
  static const contactrb::offline::SnapshotRequest r =
      contactrb::offline::make_snapshot_request(spec(), "training", 0, std::nullopt, dense_training());
  return r;
}

// The paper's cone (CPG, EIM estimate) at the POD tolerance the figures below were measured at;
// the row-cone test sets its cone itself.
GreedyOfflineSettings cpg_greedy() {
  GreedyOfflineSettings s;
  s.offline.dual_method = contactrb::offline::DualConeMethod::CPG;
  s.offline.eps_pod = 3e-5;
  return s;
}

const GreedyOfflineResult& greedy() {
  static std::unique_ptr<GreedyOfflineResult> result;
  if (!result) {
    GreedyOfflineSettings s = cpg_greedy();
    s.tolerance = kTolerance;
    s.jobs = 2;
    result = std::make_unique<GreedyOfflineResult>(contactrb::offline::run_offline_greedy(spec(), request(), s));
  }
  return *result;
}

TEST(OfflineGreedy, EstimateFallsAndStopsAtTheTolerance) {
  const GreedyOfflineResult& g = greedy();
  ASSERT_EQ(g.status, GreedyOfflineStatus::ToleranceReached);
  ASSERT_GE(g.steps.size(), 3u);
  const double first = g.steps.front().max_estimate, last = g.steps.back().max_estimate;
  EXPECT_LE(last, kTolerance);
  for (std::size_t k = 0; k + 1 < g.steps.size(); ++k) EXPECT_GT(g.steps[k].max_estimate, kTolerance) << k;
  // Trend: a tenth of the first max at least, at most 3 steps where the max grows.
  EXPECT_LT(last, first / 10.0);
  int rises = 0;
  for (std::size_t k = 1; k < g.steps.size(); ++k) rises += g.steps[k].max_estimate > g.steps[k - 1].max_estimate;
  EXPECT_LE(rises, 3);
  // Fewer HF solves than training values; one snapshot per converged solve, distinct points.
  EXPECT_LT(g.hf_solves, kTrainingSize / 2);
  EXPECT_EQ(g.hf_solves, static_cast<int>(g.selected.size() + g.excluded.size()));
  EXPECT_EQ(g.snapshots.snapshots.size(), g.selected.size());
  EXPECT_EQ(g.offline.model.training_mu.size(), g.selected.size());
  std::vector<int> sorted = g.selected;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
  // The start: the training value nearest the domain centre 0.3.
  EXPECT_NEAR(request().mu[static_cast<std::size_t>(g.start)](0), 0.3, 1e-12);
  // Sizes grow with the snapshots; the step's model is the one the table reports.
  EXPECT_EQ(g.steps.back().N, g.offline.model.N_max);
  EXPECT_EQ(g.steps.back().snapshots, static_cast<int>(g.selected.size()));
}

// With the row cone the sweep solves with the reduced Newton to 1e-10 and the estimate has no
// floor: the greedy reaches 1e-3 in a few HF solves (measured: 6 of the 61 values), where the CPG
// greedy stops near 1.5e-2, and the model meets it on the verification set against HF solves
// (measured e_displ 5.2e-4, e_press 1.7e-3).
// The row-cone model's start and preconditioner points: its snapshot points first, then the
// other training values (61 < the default 256: every one that converges), each with its
// Jacobian; at such a point the online solve starts at its own answer. Farthest first: one more
// point for a model that holds the snapshot points only is the training value farthest from them.
void expect_preconditioner_points(const GreedyOfflineResult& g) {
  const contactrb::model::ReducedModel& m = g.offline.model;
  const Eigen::Index S = static_cast<Eigen::Index>(g.snapshots.snapshots.size());
  ASSERT_GT(m.training_mu.cols(), S);
  EXPECT_LE(m.training_mu.cols(), kTrainingSize);
  for (Eigen::Index p = 0; p < S; ++p) EXPECT_EQ(m.training_mu(0, p), g.snapshots.snapshots[static_cast<std::size_t>(p)].mu(0));
  std::vector<double> values(m.training_mu.data(), m.training_mu.data() + m.training_mu.size());
  std::sort(values.begin(), values.end());
  EXPECT_EQ(std::adjacent_find(values.begin(), values.end()), values.end());
  for (double v : values) {
    EXPECT_TRUE(std::any_of(request().mu.begin(), request().mu.end(), [&](const auto& t) { return t(0) == v; })) << v;
  }
  EXPECT_EQ(m.training_jacobian.cols(), m.N_max * m.training_mu.cols());
  contactrb::online::OnlineSolver solver(m);
  const contactrb::cases::Mu added = m.training_mu.col(S);
  const contactrb::online::OnlineSolution at_added = solver.solve(added);
  ASSERT_TRUE(at_added.converged());
  EXPECT_LE(at_added.iterations, 2);

  contactrb::model::ReducedModel snapshots_only = m;
  snapshots_only.training_mu = m.training_mu.leftCols(S);
  snapshots_only.training_u_hat = m.training_u_hat.leftCols(S);
  snapshots_only.training_lambda_hat = m.training_lambda_hat.leftCols(S);
  snapshots_only.training_jacobian = m.training_jacobian.leftCols(m.N_max * S);
  contactrb::offline::add_preconditioner_points(snapshots_only, request().mu, static_cast<int>(S));
  EXPECT_EQ(snapshots_only.training_mu.cols(), S);  // as many as it holds: unchanged
  contactrb::offline::add_preconditioner_points(snapshots_only, request().mu, static_cast<int>(S) + 1);
  ASSERT_EQ(snapshots_only.training_mu.cols(), S + 1);
  EXPECT_EQ(snapshots_only.training_jacobian.size(), 0);  // for add_training_jacobians to compute again
  double farthest = -1.0, chosen = 0.0;
  for (const auto& t : request().mu) {
    double nearest = std::numeric_limits<double>::infinity();
    for (Eigen::Index p = 0; p < S; ++p) nearest = std::min(nearest, std::abs(t(0) - m.training_mu(0, p)));
    if (nearest > farthest) {
      farthest = nearest;
      chosen = t(0);
    }
  }
  EXPECT_EQ(snapshots_only.training_mu(0, S), chosen);

  // Shared out over threads: the same points, answers and Jacobians, bit for bit.
  contactrb::model::ReducedModel one = m, three = m;
  for (contactrb::model::ReducedModel* x : {&one, &three}) {
    x->training_mu = m.training_mu.leftCols(S);
    x->training_u_hat = m.training_u_hat.leftCols(S);
    x->training_lambda_hat = m.training_lambda_hat.leftCols(S);
    x->training_jacobian.resize(0, 0);
    x->training_u_sensitivity.resize(0, 0);
  }
  contactrb::offline::add_preconditioner_points(one, request().mu, kTrainingSize, 1);
  contactrb::offline::add_training_jacobians(one, 1);
  contactrb::offline::add_preconditioner_points(three, request().mu, kTrainingSize, 3);
  contactrb::offline::add_training_jacobians(three, 3);
  ASSERT_GT(one.training_mu.cols(), S);
  EXPECT_EQ(one.training_mu, three.training_mu);
  EXPECT_EQ(one.training_u_hat, three.training_u_hat);
  EXPECT_EQ(one.training_lambda_hat, three.training_lambda_hat);
  EXPECT_EQ(one.training_jacobian, three.training_jacobian);
  EXPECT_EQ(one.training_u_sensitivity, three.training_u_sensitivity);
}

TEST(OfflineGreedy, RowConeGreedyReachesATightTolerance) {
  GreedyOfflineSettings s = cpg_greedy();
  s.tolerance = 1e-3;
  s.max_hf = 20;
  s.jobs = 2;
  s.offline.dual_method = contactrb::offline::DualConeMethod::Rows;
  const GreedyOfflineResult g = contactrb::offline::run_offline_greedy(spec(), request(), s);
  ASSERT_EQ(g.status, GreedyOfflineStatus::ToleranceReached);
  EXPECT_LE(g.hf_solves, 12);
  EXPECT_EQ(g.offline.model.dual_method, "rows");
  contactrb::study::EvaluationOptions options;
  options.online_repeats = 1;
  options.jobs = 2;
  const auto ev = contactrb::study::evaluate_model(g.offline.model, g.offline.reconstruction, spec(),
                                                   spec().set("verification"), options);
  EXPECT_EQ(ev.summary.rb_failures, 0);
  EXPECT_LE(ev.summary.max_e_displ, 1e-3);
  EXPECT_LE(ev.summary.max_e_press, 5e-3);
  expect_preconditioner_points(g);
}

TEST(OfflineGreedy, EstimateAtTheChosenPointIsNotBelowTheTrueError) {
  // The true error comes from the new HF snapshot (|u_rb - u_hf|_A / |u_hf|_A), the estimate from
  // reduced quantities only; the docs measured effectivities >= 0.98 (the lambda_rb in place of
  // lambda makes it an estimate, not a bound: 10 % slack). It also falls: the last chosen point's
  // true error is a tenth of the first's at least.
  const GreedyOfflineResult& g = greedy();
  double first = std::numeric_limits<double>::quiet_NaN(), last = first;
  for (const auto& r : g.steps) {
    if (r.chosen < 0) continue;
    ASSERT_TRUE(r.hf_converged) << r.step;
    ASSERT_TRUE(std::isfinite(r.true_error)) << r.step;
    EXPECT_GT(r.true_error, 0.0) << r.step;
    EXPECT_LE(r.true_error, 1.1 * r.max_estimate) << "step " << r.step;
    EXPECT_TRUE(std::isfinite(r.true_e_press)) << r.step;
    if (std::isnan(first)) first = r.true_error;
    last = r.true_error;
  }
  EXPECT_LT(last, first / 10.0);
}

TEST(OfflineGreedy, ModelMeetsTheToleranceOnTheVerificationSet) {
  const GreedyOfflineResult& g = greedy();
  contactrb::study::EvaluationOptions options;
  options.online_repeats = 1;
  options.jobs = 2;
  const auto ev = contactrb::study::evaluate_model(g.offline.model, g.offline.reconstruction, spec(),
                                                   spec().set("verification"), options);
  EXPECT_EQ(ev.summary.rb_failures, 0);
  EXPECT_EQ(ev.summary.hf_failures, 0);
  // e_displ (65) is an H1 error, the tolerance is on the energy-norm estimate: measured 5e-3 for
  // 5e-2; asserted below the tolerance itself.
  EXPECT_LE(ev.summary.max_e_displ, kTolerance);
  EXPECT_LE(ev.summary.max_e_displ, 1e-2);
}

TEST(OfflineGreedy, ReducedEnergyNormEqualsTheHighFidelityOne) {
  // |u_D(mu) + P Theta u_hat|_A(mu) from the model's reduced arrays against sqrt(u'A u) with the
  // reconstructed HF-size u and A assembled independently on the reference mesh.
  const GreedyOfflineResult& g = greedy();
  const auto& model = g.offline.model;
  const auto mesh = contactrb::cases::reference_mesh(spec(), 0);
  const auto terms = contactrb::cases::assemble_affine_terms(spec(), mesh);
  const auto thetas = contactrb::cases::theta_functions(spec());
  contactrb::online::OnlineSolver solver(model);
  for (double value : {0.152, 0.3, 0.447}) {
    const contactrb::cases::Mu mu = contactrb::cases::Mu::Constant(1, value);
    const auto s = solver.solve(mu);
    ASSERT_TRUE(s.converged());
    const Eigen::VectorXd u = contactrb::online::reconstruct_displacement(g.offline.reconstruction, mu, s.u_hat);
    const auto A = contactrb::cases::combine(terms.A, contactrb::cases::evaluate(thetas.a, mu));
    const double hf = std::sqrt(u.dot(A * u));
    EXPECT_NEAR(contactrb::offline::reduced_energy_norm(model, mu, s.u_hat), hf, 1e-10 * hf) << value;
    // The criterion is the estimate over that norm.
    EXPECT_NEAR(contactrb::offline::relative_estimate(model, mu, s), s.estimate.energy / hf, 1e-10) << value;
  }
  contactrb::online::OnlineSolution failed;  // not converged: +inf, picked first
  EXPECT_EQ(contactrb::offline::relative_estimate(model, contactrb::cases::Mu::Constant(1, 0.3), failed),
            std::numeric_limits<double>::infinity());
}

TEST(OfflineGreedy, SameResultWhateverTheThreadsAndBudgetStatus) {
  // Budget 3: the builds from 1, 2 and 3 snapshots, then a stop with status Budget.
  GreedyOfflineSettings s = cpg_greedy();
  s.tolerance = 1e-6;
  s.max_hf = 3;
  s.jobs = 1;
  const GreedyOfflineResult a = contactrb::offline::run_offline_greedy(spec(), request(), s);
  s.jobs = 3;
  const GreedyOfflineResult b = contactrb::offline::run_offline_greedy(spec(), request(), s);
  EXPECT_EQ(a.status, GreedyOfflineStatus::Budget);
  EXPECT_EQ(a.hf_solves, 3);
  ASSERT_EQ(a.steps.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.steps[static_cast<std::size_t>(k)].snapshots, k + 1);
    EXPECT_GE(a.steps[static_cast<std::size_t>(k)].N, k + 1);
    EXPECT_GE(a.steps[static_cast<std::size_t>(k)].R, 1);
  }
  EXPECT_EQ(a.steps.back().chosen, -1);  // stopped: no HF solve in the last step
  EXPECT_EQ(a.selected, b.selected);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(a.steps[k].max_estimate, b.steps[k].max_estimate) << k;  // bitwise: same solves
    EXPECT_EQ(a.steps[k].argmax, b.steps[k].argmax) << k;
  }
  // The first greedy run chose the same first three points.
  ASSERT_GE(greedy().selected.size(), 3u);
  EXPECT_EQ(std::vector<int>(greedy().selected.begin(), greedy().selected.begin() + 3), a.selected);
}

// One process takes each new snapshot's geometric ratio from its own HF solver's factor of
// A_00(mu_p); a distribution without GreedyDistribution::max (here one process sharing with
// itself) leaves the ratios to the builds, which factor A_00(mu_p) again. The same picks, ratios
// and estimates to round-off.
TEST(OfflineGreedy, RatiosFromTheHfSolversEqualTheBuildsOwn) {
  GreedyOfflineSettings s = cpg_greedy();
  s.offline.dual_method = contactrb::offline::DualConeMethod::Rows;
  s.tolerance = 1e-6;
  s.max_hf = 6;
  const GreedyOfflineResult held = contactrb::offline::run_offline_greedy(spec(), request(), s);
  s.distribution.share = [](const auto& solve, const contactrb::offline::SnapshotRequest& step) { return solve(step); };
  const GreedyOfflineResult fresh = contactrb::offline::run_offline_greedy(spec(), request(), s);
  ASSERT_EQ(held.steps.size(), 6u);
  EXPECT_EQ(held.selected, fresh.selected);
  ASSERT_EQ(held.steps.size(), fresh.steps.size());
  for (std::size_t k = 0; k < held.steps.size(); ++k) {
    EXPECT_EQ(held.steps[k].argmax, fresh.steps[k].argmax) << k;
    EXPECT_NEAR(held.steps[k].max_estimate, fresh.steps[k].max_estimate, 1e-10 * fresh.steps[k].max_estimate) << k;
  }
  const double eta = fresh.offline.model.estimate.geometric_ratio;
  EXPECT_GT(eta, 0.0);
  EXPECT_NEAR(held.offline.model.estimate.geometric_ratio, eta, 1e-10 * eta);
}

// The returned model is the best step's: no step has fewer online failures, or as many and a
// smaller max estimate; its sizes and snapshots are that step's.
void expect_best_model_returned(const GreedyOfflineResult& g) {
  ASSERT_GE(g.model_step, 1);
  ASSERT_LE(g.model_step, static_cast<int>(g.steps.size()));
  const auto& best = g.steps[static_cast<std::size_t>(g.model_step - 1)];
  for (const auto& r : g.steps) {
    EXPECT_GE(r.online_failures, best.online_failures) << "step " << r.step;
    if (r.online_failures == best.online_failures) {
      EXPECT_GE(r.max_estimate, best.max_estimate) << "step " << r.step;
    }
    EXPECT_TRUE(r.online_failures > 0 || std::isfinite(r.max_estimate)) << "step " << r.step;
  }
  EXPECT_EQ(g.offline.model.N_max, best.N);
  EXPECT_EQ(g.offline.model.R_max, best.R);
  EXPECT_EQ(g.offline.model.training_mu.cols(), best.snapshots);
}

TEST(OfflineGreedy, ReturnsTheBestModelItBuilt) {
  expect_best_model_returned(greedy());
  GreedyOfflineSettings s = cpg_greedy();
  s.tolerance = 1e-6;
  s.max_hf = 8;
  const GreedyOfflineResult budget = contactrb::offline::run_offline_greedy(spec(), request(), s);
  EXPECT_EQ(budget.status, GreedyOfflineStatus::Budget);
  expect_best_model_returned(budget);
}

TEST(OfflineGreedy, BatchSolvesTheLargestEstimatesWithinTheBudgetWhateverTheThreads) {
  // Batch 3, budget 6: the start, a step of 3 solves, a step capped at 2, then a stop (Budget).
  GreedyOfflineSettings s = cpg_greedy();
  s.tolerance = 1e-6;
  s.max_hf = 6;
  s.batch = 3;
  s.jobs = 1;
  const GreedyOfflineResult a = contactrb::offline::run_offline_greedy(spec(), request(), s);
  s.jobs = 3;  // the step's solves in parallel
  const GreedyOfflineResult b = contactrb::offline::run_offline_greedy(spec(), request(), s);
  EXPECT_EQ(a.status, GreedyOfflineStatus::Budget);
  EXPECT_EQ(a.hf_solves, 6);
  ASSERT_EQ(a.steps.size(), 3u);
  EXPECT_EQ(a.steps[0].snapshots, 1);
  EXPECT_EQ(a.steps[1].snapshots, 4);
  EXPECT_EQ(a.steps[2].snapshots, 6);
  EXPECT_EQ(a.steps[0].batch_points.size(), 3u);
  EXPECT_EQ(a.steps[1].batch_points.size(), 2u);
  EXPECT_TRUE(a.steps[2].batch_points.empty());
  ASSERT_EQ(a.selected.size(), 6u);
  for (std::size_t k = 0; k < 2; ++k) {
    const auto& step = a.steps[k];
    EXPECT_EQ(step.batch_failures, 0);
    EXPECT_EQ(step.batch_points.front(), step.chosen);  // the largest estimate first
    // The batch: distinct points, none selected before the step.
    for (std::size_t i = 0; i < step.batch_points.size(); ++i) {
      const auto end = a.selected.begin() + step.snapshots;
      EXPECT_EQ(std::find(a.selected.begin(), end, step.batch_points[i]), end) << k << " " << i;
      for (std::size_t j = 0; j < i; ++j) EXPECT_NE(step.batch_points[i], step.batch_points[j]);
    }
  }
  // The first batch starts where the one-at-a-time greedy goes first (the same model and sweep).
  ASSERT_GE(greedy().selected.size(), 2u);
  EXPECT_EQ(a.steps[0].chosen, greedy().selected[1]);
  // ... and its snapshot there is the same cold HF solve, bit for bit.
  EXPECT_EQ(a.snapshots.snapshots[1].u, greedy().snapshots.snapshots[1].u);
  EXPECT_EQ(a.snapshots.snapshots[1].lambda, greedy().snapshots.snapshots[1].lambda);
  // Threads change nothing.
  EXPECT_EQ(a.selected, b.selected);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(a.steps[k].max_estimate, b.steps[k].max_estimate) << k;
    EXPECT_EQ(a.steps[k].batch_points, b.steps[k].batch_points) << k;
  }
  for (std::size_t k = 0; k < a.snapshots.snapshots.size(); ++k) {
    EXPECT_EQ(a.snapshots.snapshots[k].u, b.snapshots.snapshots[k].u) << k;
  }
}

TEST(OfflineGreedy, StartIsTheTrainingPointNearestTheCentre) {
  using contactrb::cases::Mu;
  contactrb::cases::ParameterSpec p;
  p.min = 1.0;
  p.max = 3.0;
  const std::vector<contactrb::cases::ParameterSpec> one{p};
  const auto pt = [](double a) { return Mu::Constant(1, a); };
  EXPECT_EQ(contactrb::offline::greedy_start_index(one, {pt(1.0), pt(1.5), pt(2.4), pt(2.6)}), 2);
  EXPECT_EQ(contactrb::offline::greedy_start_index(one, {pt(1.5), pt(2.5)}), 0);  // a tie: the smallest index
  EXPECT_EQ(contactrb::offline::greedy_start_index(one, {pt(3.0)}), 0);
  EXPECT_THROW(contactrb::offline::greedy_start_index(one, {}), contactrb::Error);
  // Two parameters on different scales: the distance is taken in [0, 1]^2 (centre (2, 150)).
  contactrb::cases::ParameterSpec q;
  q.min = 100.0;
  q.max = 200.0;
  const std::vector<contactrb::cases::ParameterSpec> two{p, q};
  const auto pt2 = [](double a, double b) { return Mu(Eigen::Vector2d(a, b)); };
  // (2.5, 150): scaled distance 0.25; (2.0, 180): 0.3 (unscaled, 30 against 0.5, it would lose).
  EXPECT_EQ(contactrb::offline::greedy_start_index(two, {pt2(2.0, 180.0), pt2(2.5, 150.0)}), 1);
  EXPECT_THROW(contactrb::offline::greedy_start_index(two, {pt(2.0)}), contactrb::Error);  // wrong size
}

TEST(OfflineGreedy, BadSettingsAreRefused) {
  const auto refused = [](const GreedyOfflineSettings& s, const std::string& words) {
    try {
      contactrb::offline::check_settings(s);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const contactrb::Error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  GreedyOfflineSettings s = cpg_greedy();
  s.tolerance = 0.0;
  refused(s, "tolerance");
  s.tolerance = std::numeric_limits<double>::quiet_NaN();
  refused(s, "tolerance");
  s.tolerance = std::numeric_limits<double>::infinity();
  refused(s, "tolerance");
  s = {};
  s.max_hf = 0;
  refused(s, "budget");
  s = {};
  s.jobs = 0;
  refused(s, "jobs");
  s = {};
  s.batch = 0;
  refused(s, "batch");
  s = {};
  s.preconditioner_points = -1;
  refused(s, "preconditioner points");
  s = {};
  s.online.start = Eigen::VectorXd::Zero(3);
  refused(s, "may not carry a start (OnlineSettings::start)");
  s = {};
  s.offline.eps_pod = -1.0;
  refused(s, "eps_pod");
  // An empty training set, before any HF solve.
  contactrb::offline::SnapshotRequest empty = request();
  empty.mu.clear();
  try {
    contactrb::offline::run_offline_greedy(spec(), empty, {});
    ADD_FAILURE() << "an empty training set was accepted";
  } catch (const contactrb::Error& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
  }
}

}  // namespace
