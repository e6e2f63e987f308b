#include <gtest/gtest.h>

#include <cmath>

#include "contactrb/common/error.hpp"
#include "contactrb/offline/eim.hpp"
#include "contactrb/offline/eim_flatten.hpp"

using namespace contactrb::offline;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// f(mu, x) = sum of 3 separable terms: rank 3 exactly.
MatrixXd separable3(int n = 60, int P = 25) {
  MatrixXd F(n, P);
  for (int p = 0; p < P; ++p) {
    const double mu = 1.0 + 0.1 * p;
    for (int i = 0; i < n; ++i) {
      const double x = static_cast<double>(i) / (n - 1);
      F(i, p) = mu * std::sin(3.0 * x) + mu * mu * std::exp(-x) + std::cos(mu) * x * x;
    }
  }
  return F;
}

// A smooth non-affine family: f(mu, x) = 1 / (1 + mu x) on [0, 1], mu in [1, 10].
MatrixXd smooth_family(int n = 80, int P = 30) {
  MatrixXd F(n, P);
  for (int p = 0; p < P; ++p) {
    const double mu = 1.0 + 9.0 * p / (P - 1);
    for (int i = 0; i < n; ++i) F(i, p) = 1.0 / (1.0 + mu * static_cast<double>(i) / (n - 1));
  }
  return F;
}

}  // namespace

TEST(EIM, FirstStepIsTheGlobalMaximum) {
  const MatrixXd F = separable3();
  EIMSettings s;
  s.max_size = 1;
  const EIMResult r = eim(F, s);
  ASSERT_EQ(r.size(), 1);
  Eigen::Index i, p;
  F.cwiseAbs().maxCoeff(&i, &p);
  EXPECT_EQ(r.magic_points[0], i);
  EXPECT_EQ(r.selected[0], p);
  EXPECT_LT((r.Q.col(0) - F.col(p) / F(i, p)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(r.errors[0], F.cwiseAbs().maxCoeff());
  EXPECT_EQ(r.status, GreedyStatus::MaxSize);
}

TEST(EIM, ExactAfterTheRankForLowRankData) {
  const MatrixXd F = separable3();
  const EIMResult r = eim(F, EIMSettings{.tolerance = 0.0, .max_size = -1, .rank_tolerance = 1e-12});
  EXPECT_EQ(r.size(), 3);
  EXPECT_EQ(r.status, GreedyStatus::Exhausted);
  ASSERT_EQ(r.errors.size(), 4u);
  EXPECT_LT(r.errors[3], 1e-12 * r.errors[0]);
  // Every training column reproduced from its 3 magic-point values.
  for (Eigen::Index p = 0; p < F.cols(); ++p) {
    const VectorXd f = F.col(p);
    const VectorXd approx = r.evaluate(r.interpolate(r.restrict(f)));
    EXPECT_LT((approx - f).cwiseAbs().maxCoeff(), 1e-11 * F.cwiseAbs().maxCoeff()) << p;
  }
}

TEST(EIM, InterpolationExactAtMagicPointsAndBUnitLowerTriangular) {
  const MatrixXd F = smooth_family();
  EIMSettings s;
  s.tolerance = 1e-10;
  s.max_size = 12;
  const EIMResult r = eim(F, s);
  const int M = r.size();
  ASSERT_GE(M, 5);
  ASSERT_EQ(r.B.rows(), M);
  for (int i = 0; i < M; ++i) {
    EXPECT_EQ(r.B(i, i), 1.0);
    for (int j = i + 1; j < M; ++j) EXPECT_EQ(r.B(i, j), 0.0) << i << "," << j;
  }
  // Each q_j is 1 at x_j, and at most 1 in absolute value (x_j is the argmax of the residual).
  for (int j = 0; j < M; ++j) EXPECT_LE(r.Q.col(j).cwiseAbs().maxCoeff(), 1.0 + 1e-14);
  // Exact at the magic points for a parameter outside the training set, and for every m <= M.
  VectorXd f(F.rows());
  for (Eigen::Index i = 0; i < F.rows(); ++i) f(i) = 1.0 / (1.0 + 4.321 * static_cast<double>(i) / (F.rows() - 1));
  for (int m = 1; m <= M; ++m) {
    const VectorXd values = r.restrict(f).head(m);
    const VectorXd approx = r.evaluate(r.interpolate(values));
    for (int i = 0; i < m; ++i)
      EXPECT_NEAR(approx(r.magic_points[static_cast<std::size_t>(i)]), values(i), 1e-12) << "m = " << m;
  }
  // The LU factors (Remark 4) solve with B.
  const VectorXd b = VectorXd::LinSpaced(M, 1.0, 2.0);
  EXPECT_LT((r.B * r.lu.solve(b) - b).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(EIM, ErrorHistoryNonIncreasingOnTheTrainingSet) {
  const MatrixXd F = smooth_family();
  EIMSettings s;
  s.tolerance = 1e-11;
  const EIMResult r = eim(F, s);
  ASSERT_GE(r.errors.size(), 6u);
  for (std::size_t m = 1; m < r.errors.size(); ++m) EXPECT_LE(r.errors[m], r.errors[m - 1]) << "M = " << m;
  // The recorded error is the true training error of I_M.
  const int M = r.size();
  double worst = 0.0;
  for (Eigen::Index p = 0; p < F.cols(); ++p) {
    const VectorXd f = F.col(p);
    worst = std::max(worst, (r.evaluate(r.interpolate(r.restrict(f))) - f).cwiseAbs().maxCoeff());
  }
  EXPECT_NEAR(worst, r.errors[static_cast<std::size_t>(M)], 1e-12);
  if (r.status == GreedyStatus::ToleranceReached) {
    EXPECT_LE(r.errors.back(), s.tolerance);
  }
}

TEST(EIM, KappaRowsFlattenRowMajor) {
  // P matrices R x n_c of a trivariate map kappa(mu, r, n).
  const int R = 4, n_c = 6, P = 9;
  std::vector<MatrixXd> K;
  for (int p = 0; p < P; ++p) {
    MatrixXd k(R, n_c);
    for (int r = 0; r < R; ++r)
      for (int n = 0; n < n_c; ++n) k(r, n) = std::exp(-0.1 * (p + 1) * r) * std::cos(0.3 * n * (p + 2)) + r;
    K.push_back(k);
  }
  const MatrixXd F = flatten_columns(K);
  ASSERT_EQ(F.rows(), R * n_c);
  ASSERT_EQ(F.cols(), P);
  for (int p = 0; p < P; ++p)
    for (int r = 0; r < R; ++r)
      for (int n = 0; n < n_c; ++n) EXPECT_EQ(F(flatten_index(r, n, n_c), p), K[static_cast<std::size_t>(p)](r, n));
  for (int p = 0; p < P; ++p) EXPECT_EQ(unflatten_column(F.col(p), R, n_c), K[static_cast<std::size_t>(p)]);
  for (int row = 0; row < R * n_c; ++row) {
    const auto [r, n] = unflatten_index(row, n_c);
    EXPECT_EQ(flatten_index(r, n, n_c), row);
  }
  // A magic point of kappa is a pair (r, n) whose value is the map's entry there.
  const EIMResult e = eim(F, EIMSettings{.tolerance = 1e-10, .max_size = 5, .rank_tolerance = 1e-12});
  const auto [r0, n0] = unflatten_index(e.magic_points[0], n_c);
  EXPECT_EQ(std::abs(K[static_cast<std::size_t>(e.selected[0])](r0, n0)), F.cwiseAbs().maxCoeff());
  std::vector<MatrixXd> bad = K;
  bad[3] = MatrixXd::Zero(R, n_c + 1);
  EXPECT_THROW(flatten_columns(bad), contactrb::Error);
  EXPECT_THROW(unflatten_column(F.col(0), R, n_c + 1), contactrb::Error);
}

TEST(EIM, InvalidInputAndEdgeCases) {
  EXPECT_THROW(eim(MatrixXd::Ones(3, 3), EIMSettings{.tolerance = -1.0, .max_size = -1, .rank_tolerance = 1e-12}),
               contactrb::Error);
  MatrixXd nan = MatrixXd::Ones(3, 3);
  nan(1, 1) = std::nan("");
  EXPECT_THROW(eim(nan), contactrb::Error);
  const EIMResult z = eim(MatrixXd::Zero(4, 3));
  EXPECT_EQ(z.size(), 0);
  EXPECT_EQ(z.status, GreedyStatus::ToleranceReached);
  EXPECT_EQ(z.interpolate(VectorXd(0)).size(), 0);
  const EIMResult one = eim(MatrixXd::Ones(4, 3), EIMSettings{.tolerance = 0.0, .max_size = -1, .rank_tolerance = 1e-12});
  EXPECT_EQ(one.size(), 1);
  EXPECT_THROW(one.interpolate(VectorXd::Ones(2)), contactrb::Error);
}
