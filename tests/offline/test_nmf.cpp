#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "contactrb/common/error.hpp"
#include "contactrb/offline/nmf.hpp"
#include "contactrb/offline/cone_projection.hpp"
#include "offline/offline_fixtures.hpp"

namespace {
constexpr int kExhaustedNmfIterations = 200;  // few enough that the ranks end at different local minima
}  // namespace

using namespace contactrb::offline;
using Eigen::MatrixXd;
using Eigen::VectorXd;

TEST(NMF, ObjectiveNonIncreasingAndFactorsNonNegative) {
  const MatrixXd T = offline_fixtures::hertz_like_snapshots();
  for (int R : {1, 3, 7}) {
    NMFSettings s;
    s.max_iterations = 300;
    s.tolerance = 0.0;
    const NMFResult r = nmf(T, R, s);
    ASSERT_EQ(r.objective.size(), static_cast<std::size_t>(r.iterations + 1));
    // tolerance 0: stops only at max_iterations or when the objective stops decreasing at all.
    EXPECT_LE(r.iterations, 300);
    if (r.status == NMFStatus::MaxIterations) {
      EXPECT_EQ(r.iterations, 300);
    }
    EXPECT_GE(r.iterations, 1);
    for (std::size_t k = 1; k < r.objective.size(); ++k)
      EXPECT_LE(r.objective[k], r.objective[k - 1] * (1.0 + 1e-12)) << "R = " << R << ", it " << k;
    EXPECT_GE(r.W.minCoeff(), 0.0);
    EXPECT_GE(r.H.minCoeff(), 0.0);
    EXPECT_NEAR((T - r.W * r.H).squaredNorm(), r.objective.back(), 1e-9 * T.squaredNorm());
    for (int j = 0; j < R; ++j) EXPECT_NEAR(r.W.col(j).norm(), 1.0, 1e-14);
  }
}

TEST(NMF, RecoversAnExactNonNegativeRank2Factorization) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const MatrixXd W0 = MatrixXd::NullaryExpr(20, 2, [&] { return U(rng); });
  const MatrixXd H0 = MatrixXd::NullaryExpr(2, 15, [&] { return U(rng); });
  const MatrixXd T = W0 * H0;
  NMFSettings s;
  s.max_iterations = 20000;
  s.tolerance = 1e-14;
  const NMFResult r = nmf(T, 2, s);
  EXPECT_LT(r.objective.back(), 1e-8 * T.squaredNorm());
  EXPECT_LT(r.objective.back(), r.objective.front());
}

TEST(NMF, ConeHistoryAndTruncatedNMF) {
  const MatrixXd T = offline_fixtures::hertz_like_snapshots(31, 12);
  DualConeSettings s;
  s.weights = offline_fixtures::collocation_weights(31);
  s.greedy.max_size = 4;  // truncated NMF, R = 4
  NMFSettings ns;
  ns.max_iterations = 200;
  const DualConeResult r = build_nmf_cone(T, s, ns);
  EXPECT_EQ(r.status, GreedyStatus::MaxSize);
  EXPECT_EQ(r.generators.cols(), 4);
  EXPECT_GE(r.generators.minCoeff(), 0.0);
  ASSERT_EQ(r.errors.size(), 5u);
  EXPECT_TRUE(r.selected.empty());
  EXPECT_EQ(r.qp_failures, 0);
  for (double e : r.errors) EXPECT_GE(e, 0.0);
  EXPECT_LT(r.errors.back(), r.errors.front());
  // A loose tolerance stops early with the error below it.
  s.greedy.max_size = -1;
  s.greedy.tolerance = 0.5 * r.errors[1];
  const DualConeResult t = build_nmf_cone(T, s, ns);
  EXPECT_EQ(t.status, GreedyStatus::ToleranceReached);
  EXPECT_LE(t.errors.back(), s.greedy.tolerance);
}

TEST(NMF, InvalidInputThrows) {
  EXPECT_THROW(nmf(MatrixXd::Ones(3, 3), 0), contactrb::Error);
  EXPECT_THROW(nmf(-MatrixXd::Ones(3, 3), 1), contactrb::Error);
  NMFSettings s;
  s.epsilon = 0.0;
  EXPECT_THROW(nmf(MatrixXd::Ones(3, 3), 1, s), contactrb::Error);
  s = {};
  s.max_iterations = 0;
  EXPECT_THROW(nmf(MatrixXd::Ones(3, 3), 1, s), contactrb::Error);
}

// Each rank is a separate factorization, and a larger rank may give a worse cone (hertz-a:
// R = 8 reaches 0.0087, R = 15 only 0.070). An exhausted NMF must keep the best: the smallest cone error over the ranks tried (smallest R on ties),
// recomputed here independently from the generators returned.
TEST(NMF, ExhaustedKeepsTheBestRankNotTheLast) {
  const MatrixXd T = offline_fixtures::hertz_like_snapshots(31, 12);
  const VectorXd w = offline_fixtures::collocation_weights(31);
  DualConeSettings s;
  s.weights = w;
  s.greedy.tolerance = 0.0;  // never reached: runs every rank up to min(31, 12)
  NMFSettings ns;
  ns.max_iterations = kExhaustedNmfIterations;
  const DualConeResult r = build_nmf_cone(T, s, ns);
  EXPECT_EQ(r.status, GreedyStatus::Exhausted);
  ASSERT_EQ(r.errors.size(), 13u);
  std::size_t best = 1;
  for (std::size_t R = 2; R < r.errors.size(); ++R)
    if (r.errors[R] < r.errors[best]) best = R;
  std::printf("[ report ] NMF cone errors by rank:");
  for (double e : r.errors) std::printf(" %.4g", e);
  std::printf("; best R = %zu\n", best);
  // The history is not monotone here, so the last and the best differ (else this test could not
  // tell the two rules apart).
  ASSERT_LT(best, r.errors.size() - 1);
  EXPECT_EQ(r.generators.cols(), static_cast<Eigen::Index>(best));
  EXPECT_NEAR(cone_projection_errors(T, r.generators, w).maxCoeff(), r.errors[best], 1e-12);
  // A fixed rank (truncated NMF) is still that rank.
  s.greedy.max_size = 12;
  EXPECT_EQ(build_nmf_cone(T, s, ns).generators.cols(), 12);
}
