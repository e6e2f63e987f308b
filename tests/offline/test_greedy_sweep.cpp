// The lazy estimate sweep of the greedy (offline/greedy_sweep.hpp), on a hertz-a model and its 61
// training values: with valid bounds (each point's last estimate at least its new one) the lazy
// sweep finds the same largest estimates as the full sweep, at the same values, and solves fewer
// points; saturation +inf is the full sweep; an exact bound of every point costs one chunk.
// The greedy with the lazy sweep stops only when every training point is below the tolerance,
// checked here by an independent loop of online solves. Warm starts (each point from its last
// answer, carried into the extended model's coordinates) keep the picks and save steps. The
// row-cone sweep's accelerated iteration keeps the reduced Newton's picks; where it does not
// converge, the fallback answers as the Newton alone does.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/parameter.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/greedy_sweep.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/offline_greedy.hpp"
#include "contactrb/model/reconstruction.hpp"
#include "contactrb/online/online_solver.hpp"

namespace {

using contactrb::offline::GreedyDistribution;
using contactrb::offline::GreedyEstimates;
using contactrb::offline::SweepContext;

const contactrb::cases::CaseSpec& spec() {
  static const contactrb::cases::CaseSpec s = contactrb::cases::builtin_case_spec("hertz-a");
  return s;
}

std::vector<contactrb::cases::Mu> training() {
  std::vector<contactrb::cases::Mu> points;
  for (int i = 0; i < 61; ++i) points.push_back(contactrb::cases::Mu::Constant(1, 0.15 + 0.3 * i / 60.0));
  return points;
}

const contactrb::offline::SnapshotRequest& request() {
  static const contactrb::offline::SnapshotRequest r =
      contactrb::offline::make_snapshot_request(spec(), "training", 0, std::nullopt, training());
  return r;
}

// A small model (budget 3) whose estimates vary over the training set.
const contactrb::offline::GreedyOfflineResult& small_greedy() {
  static const contactrb::offline::GreedyOfflineResult g = [] {
    contactrb::offline::GreedyOfflineSettings s;
    s.max_hf = 3;
    s.tolerance = 1e-12;
    return contactrb::offline::run_offline_greedy(spec(), request(), s);
  }();
  return g;
}

contactrb::online::OnlineSettings sweep_settings() {
  contactrb::online::OnlineSettings online;
  online.error_estimate = true;
  return online;
}

// The indices of the `k` largest values, largest first (ties to the smaller index).
std::vector<std::size_t> top(const std::vector<double>& v, std::size_t k) {
  std::vector<std::size_t> idx(v.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return v[a] > v[b]; });
  idx.resize(k);
  return idx;
}

TEST(GreedySweep, ValidBoundsGiveTheFullSweepsLargestEstimates) {
  const auto& model = small_greedy().offline.model;
  const auto mus = training();
  const auto online = sweep_settings();
  const GreedyDistribution one_process;
  const std::vector<char> skip(mus.size(), 0), eligible(mus.size(), 1);
  const SweepContext context{model, mus, online, 1, one_process, skip};
  GreedyEstimates full(mus.size());
  contactrb::offline::sweep_every_point(context, full);
  ASSERT_EQ(full.solves, 61);
  for (double v : full.value) ASSERT_TRUE(std::isfinite(v) && v > 0.0);

  // Bounds: each true value times a random factor in [1, 3] (a model that only improves).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> factor(1.0, 3.0);
  GreedyEstimates lazy(mus.size());
  for (std::size_t i = 0; i < mus.size(); ++i) lazy.value[i] = full.value[i] * factor(rng);
  contactrb::offline::sweep_largest(context, eligible, 3, 1.0, lazy);
  EXPECT_LT(lazy.solves, 61);
  for (std::size_t i : top(full.value, 3)) {
    EXPECT_TRUE(lazy.fresh[i]) << i;
    EXPECT_EQ(lazy.value[i], full.value[i]) << i;  // the same online solve
  }
  EXPECT_EQ(top(lazy.value, 3), top(full.value, 3));

  // Exact bounds: the first chunk (16 points) holds the 3 largest, nothing after it is solved.
  GreedyEstimates exact(mus.size());
  exact.value = full.value;
  contactrb::offline::sweep_largest(context, eligible, 3, 1.0, exact);
  EXPECT_EQ(exact.solves, 16);

  // Saturation +inf: every point.
  GreedyEstimates every(mus.size());
  every.value = full.value;
  contactrb::offline::sweep_largest(context, eligible, 1, std::numeric_limits<double>::infinity(), every);
  EXPECT_EQ(every.solves, 61);
  EXPECT_EQ(every.value, full.value);
}

// The points a lazy sweep solves do not depend on the thread count (so neither do the greedy's
// picks): the same bounds on 1, 2 and 3 threads solve the same points to the same values.
TEST(GreedySweep, LazySweepSolvesTheSamePointsWhateverTheThreads) {
  const auto& model = small_greedy().offline.model;
  const auto mus = training();
  const auto online = sweep_settings();
  const GreedyDistribution one_process;
  const std::vector<char> skip(mus.size(), 0), eligible(mus.size(), 1);
  GreedyEstimates reference(mus.size());
  contactrb::offline::sweep_every_point(SweepContext{model, mus, online, 1, one_process, skip}, reference);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> factor(1.0, 3.0);
  std::vector<double> bounds(mus.size());
  for (std::size_t i = 0; i < mus.size(); ++i) bounds[i] = reference.value[i] * factor(rng);
  std::vector<GreedyEstimates> runs;
  for (int jobs : {1, 2, 3}) {
    GreedyEstimates e(mus.size());
    e.value = bounds;
    contactrb::offline::sweep_largest(SweepContext{model, mus, online, jobs, one_process, skip}, eligible, 2, 1.0, e);
    runs.push_back(e);
  }
  ASSERT_LT(runs[0].solves, 61);
  for (std::size_t k = 1; k < runs.size(); ++k) {
    EXPECT_EQ(runs[k].solves, runs[0].solves) << "run " << k;
    EXPECT_EQ(runs[k].fresh, runs[0].fresh) << "run " << k;
    EXPECT_EQ(runs[k].value, runs[0].value) << "run " << k;
  }
}

TEST(GreedySweep, SkippedPointsAreNeverSolved) {
  const auto& model = small_greedy().offline.model;
  const auto mus = training();
  const auto online = sweep_settings();
  const GreedyDistribution one_process;
  std::vector<char> skip(mus.size(), 0);
  for (std::size_t i = 0; i < mus.size(); i += 2) skip[i] = 1;
  const SweepContext context{model, mus, online, 2, one_process, skip};
  GreedyEstimates e(mus.size());
  contactrb::offline::sweep_every_point(context, e);
  EXPECT_EQ(e.solves, 30);
  for (std::size_t i = 0; i < mus.size(); ++i) EXPECT_EQ(e.fresh[i] != 0, skip[i] == 0) << i;
}

// The greedy stops on the tolerance only when every training point is below it: an independent
// loop over the 61 values with the returned model.
TEST(GreedySweep, LazyGreedyStopsOnlyBelowTheToleranceEverywhere) {
  contactrb::offline::GreedyOfflineSettings s;
  s.tolerance = 1e-3;
  s.max_hf = 20;
  const auto g = contactrb::offline::run_offline_greedy(spec(), request(), s);
  ASSERT_EQ(g.status, contactrb::offline::GreedyOfflineStatus::ToleranceReached);
  ASSERT_EQ(g.model_step, static_cast<int>(g.steps.size()));
  EXPECT_EQ(g.steps.front().sweep_solves, 61);
  EXPECT_GE(g.steps.back().sweep_solves, 61);  // the stop is checked on every point
  int total = 0;
  for (const auto& step : g.steps) total += step.sweep_solves;
  EXPECT_LT(total, 61 * static_cast<int>(g.steps.size()));
  contactrb::online::OnlineSolver solver(g.offline.model);
  auto online = sweep_settings();
  online.iteration = contactrb::online::OnlineIteration::Newton;
  online.kacanov = contactrb::solve::KacanovSettings{1.0, contactrb::offline::kRowConeSweepTolerance,
                                                     contactrb::offline::kRowConeSweepIterations};
  double worst = 0.0;
  for (const auto& mu : training()) {
    const auto answer = solver.solve(mu, online);
    ASSERT_TRUE(answer.converged());
    worst = std::max(worst, contactrb::offline::relative_estimate(g.offline.model, mu, answer));
  }
  EXPECT_LE(worst, s.tolerance);
  // The sweep started each point from its last answer (warm starts): the same estimate to the
  // solver's tolerance (1e-10 on the increments), not to the last bit.
  EXPECT_NEAR(worst, g.steps.back().max_estimate, 1e-8 * worst);
}

// The row cone's extension builds keep every basis column and every generator: the map carries
// a reduced solution of the smaller model to the same HF field and pressures in the larger one
// (bit for bit: only zeros are added). A POD rebuild has no such map.
TEST(GreedySweep, CoordinateMapCarriesTheSameFieldIntoTheExtendedModel) {
  const auto& g = small_greedy();
  ASSERT_EQ(g.snapshots.snapshots.size(), 3u);
  contactrb::offline::OfflineSettings extend = contactrb::offline::GreedyOfflineSettings{}.offline;
  extend.extend_basis = true;
  contactrb::offline::OfflineBuildCache cache;
  contactrb::io::SnapshotSet two = g.snapshots;
  two.snapshots.pop_back();
  const auto small = contactrb::offline::build_reduced_model(two, spec(), extend, &cache);
  const auto large = contactrb::offline::build_reduced_model(g.snapshots, spec(), extend, &cache);
  const auto map = contactrb::offline::coordinate_map(small, large);
  ASSERT_TRUE(map.has_value());
  const int N0 = small.model.N_max, R0 = small.model.online_R_max();
  ASSERT_EQ(map->N, large.model.N_max);
  ASSERT_EQ(map->R, large.model.online_R_max());
  ASSERT_LT(N0, map->N);  // the third snapshot added a direction
  contactrb::online::OnlineSolver solver(small.model);
  auto online = sweep_settings();
  online.iteration = contactrb::online::OnlineIteration::Newton;
  const auto answer = solver.solve(training()[10], online);
  ASSERT_TRUE(answer.converged()) << answer.message;
  GreedyEstimates e(1);
  e.start.assign(1, Eigen::VectorXd(N0 + R0));
  e.start[0] << answer.u_hat, answer.lambda_hat;
  contactrb::offline::carry_starts(map, e);
  ASSERT_EQ(e.start[0].size(), map->N + map->R);
  const Eigen::VectorXd u_small = small.reconstruction.Theta * answer.u_hat;
  const Eigen::VectorXd u_large = large.reconstruction.Theta * e.start[0].head(map->N);
  EXPECT_EQ((u_small - u_large).cwiseAbs().maxCoeff(), 0.0);
  // The pressures on the HF rows (the row cone: lambda_hat is the pressure on the kept rows).
  const auto on_rows = [](const contactrb::model::ReducedReconstruction& r, const Eigen::VectorXd& l) {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(r.num_constraints);
    const Eigen::VectorXd kept = r.Xi * l;
    for (std::size_t i = 0; i < r.kept_rows.size(); ++i) p(r.kept_rows[i]) = kept(static_cast<Eigen::Index>(i));
    return p;
  };
  EXPECT_EQ(on_rows(small.reconstruction, answer.lambda_hat), on_rows(large.reconstruction, e.start[0].tail(map->R)));
  // A POD rebuild: new directions everywhere, no map; the starts are dropped.
  const auto rebuilt =
      contactrb::offline::build_reduced_model(g.snapshots, spec(), contactrb::offline::GreedyOfflineSettings{}.offline);
  EXPECT_FALSE(contactrb::offline::coordinate_map(small, rebuilt).has_value());
  contactrb::offline::carry_starts(std::nullopt, e);
  EXPECT_EQ(e.start[0].size(), 0);
}

// Warm starts change the sweep's path, not its answers: the same picks and estimates (to the
// sweep's tolerance) as the solves from the model's own start, in fewer reduced steps. The
// accelerated iteration stops at a fixed-point residual of 1e-10: two starts give answers 1e-10
// apart and, at estimates near 1e-3, relative estimates about 1e-7 apart.
TEST(GreedySweep, WarmStartsKeepThePicksInFewerSteps) {
  contactrb::offline::GreedyOfflineSettings s;
  s.tolerance = 1e-3;
  s.max_hf = 20;
  const auto warm = contactrb::offline::run_offline_greedy(spec(), request(), s);
  s.sweep_warm_start = false;
  const auto cold = contactrb::offline::run_offline_greedy(spec(), request(), s);
  ASSERT_EQ(warm.selected, cold.selected);
  ASSERT_EQ(warm.steps.size(), cold.steps.size());
  long long warm_steps = 0, cold_steps = 0;
  for (std::size_t k = 0; k < warm.steps.size(); ++k) {
    const auto &w = warm.steps[k], &c = cold.steps[k];
    EXPECT_EQ(w.argmax, c.argmax) << "step " << k + 1;
    EXPECT_EQ(w.sweep_solves, c.sweep_solves) << "step " << k + 1;
    EXPECT_NEAR(w.max_estimate, c.max_estimate, 1e-6 * c.max_estimate) << "step " << k + 1;
    warm_steps += w.sweep_iterations;
    cold_steps += c.sweep_iterations;
  }
  std::printf("[ hertz-a ] sweep: %lld reduced steps from warm starts, %lld from the model's start\n",
              warm_steps, cold_steps);
  EXPECT_LT(warm_steps, cold_steps);
}

// The row-cone sweep's iteration: the accelerated one (the default's estimates are bit for bit
// those of a greedy that asks for it), with the picks of the reduced Newton's sweep and its
// estimates to 1e-6 relative (the accelerated iteration stops at a fixed-point residual of 1e-10,
// the Newton at round-off), in cheaper steps.
TEST(GreedySweep, AcceleratedSweepKeepsTheNewtonPicks) {
  using contactrb::offline::GreedyOfflineSettings;
  using contactrb::online::OnlineIteration;
  GreedyOfflineSettings s;
  s.tolerance = 1e-3;
  s.max_hf = 20;
  const auto fast = contactrb::offline::run_offline_greedy(spec(), request(), s);
  GreedyOfflineSettings newton_settings = s, accelerated_settings = s;
  newton_settings.online.iteration = OnlineIteration::Newton;
  newton_settings.online.kacanov = contactrb::solve::KacanovSettings{1.0, contactrb::offline::kRowConeSweepTolerance,
                                                                      contactrb::offline::kRowConeSweepIterations};
  accelerated_settings.online.iteration = OnlineIteration::Accelerated;
  accelerated_settings.online.kacanov =
      contactrb::solve::KacanovSettings{1.0, contactrb::offline::kRowConeSweepAcceleratedTolerance,
                                        contactrb::offline::kRowConeSweepAcceleratedIterations};
  const auto newton = contactrb::offline::run_offline_greedy(spec(), request(), newton_settings);
  const auto accelerated = contactrb::offline::run_offline_greedy(spec(), request(), accelerated_settings);
  ASSERT_EQ(fast.status, contactrb::offline::GreedyOfflineStatus::ToleranceReached);
  ASSERT_EQ(fast.selected, newton.selected);
  ASSERT_EQ(fast.steps.size(), newton.steps.size());
  ASSERT_EQ(fast.steps.size(), accelerated.steps.size());
  EXPECT_EQ(fast.model_step, newton.model_step);
  for (std::size_t k = 0; k < fast.steps.size(); ++k) {
    const auto &f = fast.steps[k], &n = newton.steps[k], &a = accelerated.steps[k];
    EXPECT_EQ(f.argmax, n.argmax) << "step " << k + 1;
    EXPECT_EQ(f.sweep_solves, n.sweep_solves) << "step " << k + 1;
    EXPECT_NEAR(f.max_estimate, n.max_estimate, 1e-6 * n.max_estimate) << "step " << k + 1;
    EXPECT_EQ(f.max_estimate, a.max_estimate) << "step " << k + 1;
    EXPECT_EQ(f.sweep_iterations, a.sweep_iterations) << "step " << k + 1;
  }
}

// A point where the first iteration does not converge is answered by the fallback, from the
// same start: the fallback's answer, its steps counted after the first iteration's. Without a
// fallback the point stays a failure.
TEST(GreedySweep, FallbackAnswersWhereTheFirstIterationDoesNot) {
  const auto& model = small_greedy().offline.model;
  const auto mus = training();
  // From u_hat = 0 (the model's own guess is its converged answer at its training values) one
  // accelerated step never meets the tolerance.
  contactrb::online::OnlineSettings stalls = sweep_settings();
  stalls.initial_guess = contactrb::online::InitialGuess::Zero;
  contactrb::online::OnlineSettings newton = stalls;
  stalls.iteration = contactrb::online::OnlineIteration::Accelerated;
  stalls.kacanov = contactrb::solve::KacanovSettings{1.0, contactrb::offline::kRowConeSweepAcceleratedTolerance, 1};
  newton.iteration = contactrb::online::OnlineIteration::Newton;
  newton.kacanov = contactrb::solve::KacanovSettings{1.0, contactrb::offline::kRowConeSweepTolerance,
                                                     contactrb::offline::kRowConeSweepIterations};
  contactrb::online::OnlineSolver solver(model), reference(model);
  const auto& mu = mus[20];
  auto first = stalls;
  ASSERT_FALSE(contactrb::offline::solve_point(solver, mu, first, nullptr, nullptr).converged());
  auto fallback = newton;
  const auto answered = contactrb::offline::solve_point(solver, mu, first, &fallback, nullptr);
  const auto alone = reference.solve(mu, newton);
  ASSERT_TRUE(alone.converged()) << alone.message;
  ASSERT_TRUE(answered.converged()) << answered.message;
  EXPECT_EQ(answered.iterations, 1 + alone.iterations);
  EXPECT_EQ(answered.u_hat, alone.u_hat);
  EXPECT_EQ(answered.estimate.energy, alone.estimate.energy);

  // A sweep whose every point stalls: each is answered as the Newton sweep answers it.
  const GreedyDistribution one_process;
  const std::vector<char> skip(mus.size(), 0);
  SweepContext with_fallback{model, mus, stalls, 2, one_process, skip};
  with_fallback.fallback = &newton;
  const SweepContext newton_only{model, mus, newton, 2, one_process, skip};
  GreedyEstimates e(mus.size()), n(mus.size());
  contactrb::offline::sweep_every_point(with_fallback, e);
  contactrb::offline::sweep_every_point(newton_only, n);
  EXPECT_EQ(std::count(e.failed.begin(), e.failed.end(), 1), 0);
  EXPECT_EQ(e.value, n.value);
  EXPECT_EQ(e.iterations, n.iterations + static_cast<long long>(mus.size()));
  const SweepContext without{model, mus, stalls, 2, one_process, skip};
  GreedyEstimates f(mus.size());
  contactrb::offline::sweep_every_point(without, f);
  EXPECT_EQ(std::count(f.failed.begin(), f.failed.end(), 1), static_cast<long>(mus.size()));
}

}  // namespace
