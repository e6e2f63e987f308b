#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "contactrb/common/error.hpp"
#include "contactrb/offline/angle_greedy.hpp"
#include "contactrb/offline/cone_projection.hpp"
#include "contactrb/offline/cpg.hpp"
#include "contactrb/offline/row_cone.hpp"
#include "offline/offline_fixtures.hpp"

using namespace contactrb::offline;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// The training set (59) of Remark 6, columns e1 .. e4.
MatrixXd remark6(double zeta) {
  MatrixXd L(3, 4);
  L.col(0) << std::cos(zeta), std::sin(zeta), 0.0;
  L.col(1) << 2.0 * std::cos(2 * zeta), 2.0 * std::sin(2 * zeta), 0.0;
  L.col(2) << 1.5 * std::cos(3 * zeta), 1.5 * std::sin(3 * zeta), 0.0;
  L.col(3) << std::cos(2 * zeta), std::sin(2 * zeta), std::sin(zeta / 2);
  return L.cwiseMax(0.0);  // cos(pi/2) rounds to +6e-17; clamp any -0 noise
}

Eigen::Index argmax(const VectorXd& v) {
  Eigen::Index i = 0;
  v.maxCoeff(&i);
  return i;
}

void expect_non_increasing(const std::vector<double>& h, double slack) {
  for (std::size_t k = 1; k < h.size(); ++k) EXPECT_LE(h[k], h[k - 1] + slack) << "step " << k;
}

}  // namespace

TEST(Remark6, CPGSelectsE1AngleGreedySelectsE4) {
  for (double zeta : {std::numbers::pi / 6, std::numbers::pi / 12, 0.1}) {
    const MatrixXd L = remark6(zeta);
    CPGProblem cpg(L);
    cpg.extend(1);  // K2 = span+{e2, e3}
    cpg.extend(2);
    const VectorXd e_cpg = cpg.evaluate();
    EXPECT_EQ(argmax(e_cpg), 0) << "zeta = " << zeta;
    EXPECT_NEAR(e_cpg(0), std::sin(zeta), 1e-12);      // e1 is at angle zeta from the ray of e2
    EXPECT_NEAR(e_cpg(3), std::sin(zeta / 2), 1e-12);  // e4 = e2 / 2 + sin(zeta/2) e_z

    AngleGreedyProblem angle(L);
    angle.extend(1);
    angle.extend(2);
    const VectorXd e_lin = angle.evaluate();
    EXPECT_EQ(argmax(e_lin), 3) << "zeta = " << zeta;
    EXPECT_NEAR(e_lin(0), 0.0, 1e-14);  // e1 lies in span{e2, e3}
    EXPECT_NEAR(e_lin(3), std::sin(zeta / 2), 1e-12);
  }
}

TEST(CPG, FirstPickIsTheLargestAndHistoryDecreasesToZero) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const MatrixXd S = MatrixXd::NullaryExpr(20, 8, [&] { return U(rng); });
  const VectorXd w = VectorXd::LinSpaced(20, 0.5, 1.5);
  DualConeSettings s;
  s.weights = w;
  const DualConeResult r = build_cpg(S, s);
  ASSERT_EQ(r.selected.size(), 8u);  // independent snapshots: all needed for a zero error
  EXPECT_EQ(r.status, GreedyStatus::ToleranceReached);
  // (56): the first pick maximizes the Lambda norm.
  VectorXd norms(8);
  for (int p = 0; p < 8; ++p) norms(p) = weighted_norm(S.col(p), w);
  EXPECT_EQ(r.selected[0], argmax(norms));
  EXPECT_NEAR(r.errors[0], norms.maxCoeff(), 1e-14);
  ASSERT_EQ(r.errors.size(), 9u);
  expect_non_increasing(r.errors, 1e-12);
  EXPECT_EQ(r.errors.back(), 0.0);
  // The generators are the selected snapshots, hence non-negative.
  ASSERT_EQ(r.generators.cols(), 8);
  for (int j = 0; j < 8; ++j) EXPECT_EQ(r.generators.col(j), S.col(r.selected[j]));
  EXPECT_EQ(r.qp_failures, 0);
  // The recorded errors are the true cone errors of the nested selections.
  for (int R = 1; R <= 8; ++R) {
    const VectorXd e = cone_projection_errors(S, r.generators.leftCols(R), w);
    EXPECT_NEAR(r.errors[static_cast<std::size_t>(R)], e.maxCoeff(), 1e-10) << R;
  }
}

TEST(CPG, StopsOnAbsoluteRelativeToleranceOrFixedR) {
  const MatrixXd S = offline_fixtures::hertz_like_snapshots();
  const VectorXd w = offline_fixtures::collocation_weights();
  DualConeSettings s;
  s.weights = w;
  s.greedy.tolerance = 1e-2;
  const DualConeResult a = build_cpg(S, s);
  EXPECT_EQ(a.status, GreedyStatus::ToleranceReached);
  EXPECT_LE(a.errors.back(), 1e-2);
  EXPECT_GT(a.errors[a.errors.size() - 2], 1e-2);  // (58) failed one step earlier
  EXPECT_EQ(a.generators.cols(), static_cast<Eigen::Index>(a.selected.size()));
  expect_non_increasing(a.errors, 1e-12);

  s.greedy.relative = true;
  s.greedy.tolerance = 1e-2;
  const DualConeResult rel = build_cpg(S, s);
  EXPECT_LE(rel.relative_errors.back(), 1e-2);
  EXPECT_GT(rel.relative_errors[rel.relative_errors.size() - 2], 1e-2);

  s.greedy = {};
  s.greedy.max_size = 3;
  const DualConeResult fixed = build_cpg(S, s);
  EXPECT_EQ(fixed.status, GreedyStatus::MaxSize);
  EXPECT_EQ(fixed.generators.cols(), 3);
  EXPECT_EQ(fixed.errors.size(), 4u);
}

TEST(AngleGreedy, TrueConeErrorIsAtLeastTheLinearError) {
  const MatrixXd S = offline_fixtures::hertz_like_snapshots();
  DualConeSettings s;
  s.weights = offline_fixtures::collocation_weights();
  s.greedy.max_size = 15;
  const DualConeResult r = build_angle_greedy(S, s);
  ASSERT_EQ(r.errors.size(), r.linear_errors.size());
  ASSERT_EQ(r.errors.size(), r.selected.size() + 1);
  EXPECT_EQ(r.errors[0], r.linear_errors[0]);
  for (std::size_t k = 0; k < r.errors.size(); ++k)
    EXPECT_GE(r.errors[k], r.linear_errors[k] - 1e-12) << "R = " << k;
  expect_non_increasing(r.linear_errors, 1e-12);
  expect_non_increasing(r.errors, 1e-12);  // nested cones
  for (int j = 0; j < r.generators.cols(); ++j) EXPECT_EQ(r.generators.col(j), S.col(r.selected[j]));
  // Without the cone history, only the linear one.
  s.cone_history = false;
  const DualConeResult q = build_angle_greedy(S, s);
  EXPECT_TRUE(q.errors.empty());
  EXPECT_EQ(q.selected, r.selected);
}

TEST(DualCone, InvalidInputThrows) {
  MatrixXd S = MatrixXd::Ones(4, 3);
  S(1, 1) = -0.5;
  EXPECT_THROW(build_cpg(S), contactrb::Error);
  EXPECT_THROW(build_angle_greedy(S), contactrb::Error);
  DualConeSettings s;
  s.weights = VectorXd::Ones(3);
  EXPECT_THROW(build_cpg(MatrixXd::Ones(4, 3), s), contactrb::Error);
  s = {};
  s.greedy.tolerance = -1.0;
  EXPECT_THROW(build_cpg(MatrixXd::Ones(4, 3), s), contactrb::Error);
  const MatrixXd ones = MatrixXd::Ones(4, 3);
  CPGProblem p(ones);
  EXPECT_THROW(p.extend(3), contactrb::Error);
  EXPECT_THROW(p.extend(-1), contactrb::Error);
  AngleGreedyProblem a(ones);
  EXPECT_THROW(a.extend(3), contactrb::Error);
}

// The angle-greedy must stop on its true cone error, not its linear error, which can say
// "tolerance reached" while the cone it hands to the online stage is far from eps_DU. Here the linear error vanishes after
// two picks ({(1,1), (1,0)} span R^2), but (0,1) is at distance sin(45 deg) = 0.7071 from
// span+{(1,1), (1,0)} (its projection is on the ray of (1,1)).
TEST(AngleGreedy, StopsOnTheTrueConeErrorNotTheLinearOne) {
  MatrixXd S(2, 3);
  S << 1.0, 1.0, 0.0,  //
      1.0, 0.0, 1.0;
  DualConeSettings s;
  s.greedy.tolerance = 0.1;
  const DualConeResult r = build_angle_greedy(S, s);
  EXPECT_EQ(r.selected, (std::vector<int>{0, 1}));  // (56): the largest first; then the tie, index 1
  EXPECT_NEAR(r.linear_errors.back(), 0.0, 1e-15);
  ASSERT_EQ(r.errors.size(), 3u);
  EXPECT_NEAR(r.errors.back(), std::sqrt(0.5), 1e-12);
  EXPECT_EQ(r.status, GreedyStatus::Exhausted);  // not ToleranceReached: eps_DU was not met
  // Relative: the same (|(0,1)| = 1).
  s.greedy.relative = true;
  const DualConeResult rel = build_angle_greedy(S, s);
  EXPECT_EQ(rel.status, GreedyStatus::Exhausted);
  EXPECT_NEAR(rel.relative_errors.back(), std::sqrt(0.5), 1e-12);
  // A tolerance above the cone error is reached, and then by the cone error.
  s.greedy.relative = false;
  s.greedy.tolerance = 0.75;
  const DualConeResult ok = build_angle_greedy(S, s);
  EXPECT_EQ(ok.status, GreedyStatus::ToleranceReached);
  EXPECT_LE(ok.errors.back(), 0.75);
  // Without the cone errors there is no true stopping test: refused unless tolerance 0.
  s.cone_history = false;
  EXPECT_THROW(build_angle_greedy(S, s), contactrb::Error);
}

// On the Hertz-like fixture, whenever the angle-greedy says ToleranceReached its cone error
// (recomputed independently from its generators) is below eps_DU, and one step earlier it was not.
TEST(AngleGreedy, ToleranceReachedMeansTheConeErrorReachedIt) {
  const MatrixXd S = offline_fixtures::hertz_like_snapshots();
  const VectorXd w = offline_fixtures::collocation_weights();
  for (double eps : {1e-1, 3e-2, 1e-2}) {
    DualConeSettings s;
    s.weights = w;
    s.greedy.tolerance = eps;
    const DualConeResult r = build_angle_greedy(S, s);
    const Eigen::Index R = r.generators.cols();
    const double cone = cone_projection_errors(S, r.generators, w).maxCoeff();
    if (r.status == GreedyStatus::ToleranceReached) {
      EXPECT_LE(cone, eps) << "eps " << eps;
      const double before = cone_projection_errors(S, r.generators.leftCols(R - 1), w).maxCoeff();
      EXPECT_GT(before, eps) << "eps " << eps;
    } else {
      EXPECT_EQ(r.status, GreedyStatus::Exhausted) << "eps " << eps;
      EXPECT_GT(cone, eps) << "eps " << eps;
    }
    EXPECT_NEAR(r.errors.back(), cone, 1e-10) << "eps " << eps;
  }
}

// In relative mode every relative error of the empty cone is 1, so argmax would pick index 0
// (the smallest snapshot here); (56) picks argmax |lambda|.
TEST(CPG, RelativeModeStartsAtTheLargestSnapshot) {
  const MatrixXd S = offline_fixtures::hertz_like_snapshots();
  const VectorXd w = offline_fixtures::collocation_weights();
  VectorXd norms(S.cols());
  for (Eigen::Index p = 0; p < S.cols(); ++p) norms(p) = weighted_norm(S.col(p), w);
  const Eigen::Index largest = argmax(norms);
  ASSERT_NE(largest, 0);  // otherwise the test could not tell the two rules apart
  DualConeSettings s;
  s.weights = w;
  s.greedy.relative = true;
  s.greedy.tolerance = 1e-2;
  const DualConeResult cpg = build_cpg(S, s);
  ASSERT_FALSE(cpg.selected.empty());
  EXPECT_EQ(cpg.selected[0], largest);
  EXPECT_LE(cpg.relative_errors.back(), 1e-2);
  const DualConeResult angle = build_angle_greedy(S, s);
  ASSERT_FALSE(angle.selected.empty());
  EXPECT_EQ(angle.selected[0], largest);
}

TEST(RowCone, GeneratorsAreTheRowsAndErrorsAreThoseOfTheConeProjection) {
  // The generators are the unit vectors of the kept rows; errors[k] is the max over the snapshots
  // of the distance to the cone of the first k of them, checked against the QP projection.
  const MatrixXd S = offline_fixtures::hertz_like_snapshots(21, 9);
  const VectorXd w = offline_fixtures::collocation_weights(21);
  DualConeSettings settings;
  settings.weights = w;
  const DualConeResult cone = build_row_cone(S, settings);
  EXPECT_EQ(cone.method, DualConeMethod::Rows);
  ASSERT_EQ(cone.generators.rows(), 21);
  ASSERT_EQ(cone.generators.cols(), 21);
  EXPECT_TRUE(cone.generators.isIdentity(0.0));
  ASSERT_EQ(cone.errors.size(), 22u);
  EXPECT_EQ(cone.errors.back(), 0.0);
  for (int k : {1, 5, 10, 20}) {
    double worst = 0.0, worst_relative = 0.0;
    for (Eigen::Index p = 0; p < S.cols(); ++p) {
      const ConeProjection pr = project_onto_cone(cone.generators.leftCols(k), S.col(p), w);
      const double e = weighted_norm(S.col(p) - cone.generators.leftCols(k) * pr.coefficients, w);
      worst = std::max(worst, e);
      worst_relative = std::max(worst_relative, e / weighted_norm(S.col(p), w));
    }
    EXPECT_NEAR(cone.errors[static_cast<std::size_t>(k)], worst, 1e-12 * (1.0 + worst)) << k;
    EXPECT_NEAR(cone.relative_errors[static_cast<std::size_t>(k)], worst_relative, 1e-12) << k;
  }
  double largest = 0.0;
  for (Eigen::Index p = 0; p < S.cols(); ++p) largest = std::max(largest, weighted_norm(S.col(p), w));
  EXPECT_NEAR(cone.errors.front(), largest, 1e-14 * largest);
}
