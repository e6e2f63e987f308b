// Warm-started snapshot runs (SnapshotRunOptions::warm_start, docs/solvers.md "Warm start"): the same answers as
// cold starts to the solver tolerance, fewer iterations in total, and data independent of the
// number of threads (the schedule does not depend on it). hertz-a level 0, 9 values of mu.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/level_sequence.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "support/snapshot_fixtures.hpp"

using contactrb::io::SnapshotSet;
using contactrb::offline::generate_snapshots;
using contactrb::offline::SnapshotRequest;
using contactrb::offline::SnapshotRunOptions;

namespace {

SnapshotRequest request(contactrb::hf::HFMethod method) {
  std::vector<double> values;
  for (int i = 0; i <= 8; ++i) values.push_back(0.15 + 0.0375 * i);
  SnapshotRequest r = contactrb::offline::make_snapshot_request(
      contactrb::cases::builtin_case_spec("hertz-a"), "training", 0, std::nullopt, contactrb::cases::points_1d(values));
  r.settings.method = method;
  return r;
}

int total_iterations(const SnapshotSet& s) {
  int n = 0;
  for (const auto& snap : s.snapshots) n += snap.iterations;
  return n;
}

// Max over snapshots of |a - b|_inf / |b|_inf for u and lambda (a: warm or Kacanov, b: the reference).
void expect_close(const SnapshotSet& a, const SnapshotSet& b, double u_tol, double lambda_tol, const std::string& label) {
  ASSERT_EQ(a.snapshots.size(), b.snapshots.size());
  double du = 0.0, dl = 0.0;
  for (std::size_t i = 0; i < a.snapshots.size(); ++i) {
    ASSERT_TRUE(a.snapshots[i].converged) << label << " " << i << ": " << a.snapshots[i].message;
    ASSERT_TRUE(b.snapshots[i].converged) << label << " " << i << ": " << b.snapshots[i].message;
    du = std::max(du, (a.snapshots[i].u - b.snapshots[i].u).lpNorm<Eigen::Infinity>() /
                          b.snapshots[i].u.lpNorm<Eigen::Infinity>());
    dl = std::max(dl, (a.snapshots[i].lambda - b.snapshots[i].lambda).lpNorm<Eigen::Infinity>() /
                          b.snapshots[i].lambda.lpNorm<Eigen::Infinity>());
  }
  EXPECT_LT(du, u_tol) << label;
  EXPECT_LT(dl, lambda_tol) << label;
  std::cout << "[ info     ] " << label << ": max relative difference: u " << du << ", lambda " << dl
            << "; iterations " << total_iterations(a) << " against " << total_iterations(b) << "\n";
}

}  // namespace

TEST(SnapshotWarmStart, NewtonSameAnswerFewerIterationsIndependentOfJobs) {
  const SnapshotRequest r = request(contactrb::hf::HFMethod::Newton);
  SnapshotRunOptions cold;
  cold.warm_start = SnapshotRunOptions::WarmStart::Off;
  SnapshotRunOptions warm1, warm2;  // Automatic: on for Newton
  warm2.jobs = 2;
  const SnapshotSet c = generate_snapshots(r, cold);
  const SnapshotSet w1 = generate_snapshots(r, warm1);
  const SnapshotSet w2 = generate_snapshots(r, warm2);
  // Newton stops at a relative KKT residual of 1e-10.
  expect_close(w1, c, 1e-8, 1e-6, "newton");
  EXPECT_LT(total_iterations(w1), total_iterations(c));
  contactrb::test::expect_same_data(w1, w2, /*with_timings=*/false);
}

TEST(SnapshotWarmStart, KacanovSameAnswerToItsToleranceFewerIterations) {
  const SnapshotRequest r = request(contactrb::hf::HFMethod::Kacanov);
  SnapshotRunOptions cold;
  cold.warm_start = SnapshotRunOptions::WarmStart::Off;
  const SnapshotSet c = generate_snapshots(r, cold);
  SnapshotRunOptions on;  // Automatic would keep Kacanov cold
  on.warm_start = SnapshotRunOptions::WarmStart::On;
  const SnapshotSet w = generate_snapshots(r, on);
  contactrb::test::expect_same_data(generate_snapshots(r, SnapshotRunOptions{}), c, /*with_timings=*/false);
  // Kacanov stops on the relative increment eps_KA = 1e-3 (63) of the relaxed iteration: two
  // runs from different starts stop at different points of the same contraction.
  expect_close(w, c, 1e-2, 1e-2, "kacanov");
  EXPECT_LT(total_iterations(w), total_iterations(c));
}

// The two HF methods on one snapshot set (cold starts): the same u and lambda to Kacanov's
// tolerance (Newton's KKT residual 1e-10 makes it the reference), each set recording its method.
TEST(SnapshotSolver, NewtonAndKacanovAgreeToKacanovsTolerance) {
  SnapshotRunOptions cold;
  cold.warm_start = SnapshotRunOptions::WarmStart::Off;
  const SnapshotSet n = generate_snapshots(request(contactrb::hf::HFMethod::Newton), cold);
  const SnapshotSet k = generate_snapshots(request(contactrb::hf::HFMethod::Kacanov), cold);
  EXPECT_EQ(n.solver, "newton");
  EXPECT_EQ(k.solver, "kacanov");
  // eps_KA = 1e-3 on the relative increment of the relaxed iteration (63): u within 1e-2, as
  // two Kacanov runs from different starts (above).
  expect_close(k, n, 1e-2, 1e-2, "kacanov against newton");
  EXPECT_LT(total_iterations(n), total_iterations(k));
  for (const auto& snap : n.snapshots) EXPECT_LE(snap.iterations, 12);
}

// The method when none is asked for (docs/solvers.md, "Which solver for snapshots").
TEST(SnapshotSolver, DefaultIsKacanovOnlyOnThe2dLevel0Meshes) {
  using contactrb::cases::builtin_case_spec;
  using contactrb::hf::HFMethod;
  using contactrb::offline::make_snapshot_request;
  EXPECT_EQ(make_snapshot_request(builtin_case_spec("hertz-a"), "training").settings.method, HFMethod::Kacanov);
  EXPECT_EQ(make_snapshot_request(builtin_case_spec("hertz-a"), "training", 1).settings.method, HFMethod::Newton);
  EXPECT_EQ(make_snapshot_request(builtin_case_spec("patch-3d"), "training").settings.method, HFMethod::Newton);
  EXPECT_EQ(contactrb::offline::default_snapshot_method(3, 0), HFMethod::Newton);
  EXPECT_EQ(contactrb::offline::default_snapshot_method(2, 0), HFMethod::Kacanov);
  EXPECT_EQ(contactrb::offline::default_snapshot_method(2, 4), HFMethod::Newton);
}

// Grid sequencing of the cold solves (offline::set_snapshot_sequence, docs/solvers.md "Grid sequencing"):
// the answers of the unsequenced cold solves to Newton's tolerance, fewer iterations, data
// independent of the number of threads; in a warm sweep only the first wave is sequenced.
// hertz-a level 2 (coarse level 0), 7 values of mu.
TEST(SnapshotSequence, ColdSolvesStartFromTheCoarseLevel) {
  const std::vector<double> values{0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45};
  SnapshotRequest plain = contactrb::offline::make_snapshot_request(
      contactrb::cases::builtin_case_spec("hertz-a"), "training", 2, std::nullopt, contactrb::cases::points_1d(values));
  plain.settings.method = contactrb::hf::HFMethod::Newton;
  EXPECT_EQ(contactrb::offline::set_snapshot_sequence(plain, -1), 0);  // automatic: none below level 4
  EXPECT_FALSE(plain.coarse);
  SnapshotRequest sequenced = plain;
  EXPECT_EQ(contactrb::offline::set_snapshot_sequence(sequenced, 1), 1);
  ASSERT_TRUE(sequenced.coarse);
  EXPECT_EQ(sequenced.coarse->levels, std::vector<int>{0});
  EXPECT_THROW(contactrb::offline::set_snapshot_sequence(sequenced, -2), contactrb::Error);

  SnapshotRunOptions cold;
  cold.warm_start = SnapshotRunOptions::WarmStart::Off;
  const SnapshotSet c = generate_snapshots(plain, cold);
  const SnapshotSet s = generate_snapshots(sequenced, cold);
  expect_close(s, c, 1e-8, 1e-6, "sequenced against cold");
  EXPECT_LT(total_iterations(s), total_iterations(c));
  SnapshotRunOptions cold2 = cold;
  cold2.jobs = 2;
  contactrb::test::expect_same_data(s, generate_snapshots(sequenced, cold2), /*with_timings=*/false);

  // Warm (automatic with Newton): the first wave (the first point alone) starts from the coarse
  // level, exactly as in the sequenced cold run; the others from their neighbours.
  const SnapshotSet w = generate_snapshots(sequenced, SnapshotRunOptions{});
  EXPECT_EQ(w.snapshots[0].iterations, s.snapshots[0].iterations);
  EXPECT_EQ(w.snapshots[0].u, s.snapshots[0].u);
  EXPECT_EQ(w.snapshots[0].lambda, s.snapshots[0].lambda);
  expect_close(w, c, 1e-8, 1e-6, "warm and sequenced against cold");
}

// The automatic count of coarse levels, as `solve --sequence -1` (cases::default_sequence).
TEST(SnapshotSequence, AutomaticRuleIsSolves) {
  using contactrb::cases::default_sequence;
  using contactrb::hf::HFMethod;
  EXPECT_EQ(default_sequence(2, HFMethod::Newton, 4), 2);
  EXPECT_EQ(default_sequence(2, HFMethod::Newton, 7), 2);
  EXPECT_EQ(default_sequence(2, HFMethod::Newton, 3), 0);
  EXPECT_EQ(default_sequence(2, HFMethod::Kacanov, 6), 0);
  EXPECT_EQ(default_sequence(3, HFMethod::Newton, 2), 0);
  EXPECT_EQ(default_sequence(3, HFMethod::Newton, 3), 1);
  EXPECT_EQ(default_sequence(3, HFMethod::Newton, 4), 1);
  EXPECT_EQ(default_sequence(3, HFMethod::Kacanov, 4), 0);
  EXPECT_EQ(contactrb::cases::resolve_sequence(3, 2, HFMethod::Kacanov, 0), 3);
  EXPECT_THROW(contactrb::cases::resolve_sequence(-2, 2, HFMethod::Newton, 4), contactrb::Error);
}
