// DenseLU (LAPACK dgetrf / dgetrs / dgecon): solutions against the exact product, the condition
// estimate against the exact 1-norm condition number, singular and invalid input.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "contactrb/common/error.hpp"
#include "contactrb/solve/dense_lu.hpp"

using namespace contactrb;

namespace {
// A nonsymmetric matrix that needs row exchanges (small diagonal), fixed seed.
Eigen::MatrixXd test_matrix(int n) {
  Eigen::MatrixXd M(n, n);
  unsigned state = 12345u;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      state = state * 1664525u + 1013904223u;
      M(i, j) = static_cast<double>(state >> 8) / static_cast<double>(1u << 24) - 0.5;
    }
  }
  M.diagonal() *= 1e-3;
  M += Eigen::MatrixXd::Identity(n, n) * 0.01 * n;  // keeps it well conditioned
  return M;
}
}  // namespace

TEST(DenseLU, SolvesToRoundoffAndEstimatesTheCondition) {
  for (int n : {1, 7, 64, 300}) {  // 300: LAPACK's blocked path
    const Eigen::MatrixXd M = test_matrix(n);
    Eigen::VectorXd x(n);
    for (int i = 0; i < n; ++i) x(i) = std::sin(1.0 + i);
    const Eigen::VectorXd b = M * x;
    solve::DenseLU lu;
    ASSERT_TRUE(lu.compute(M)) << n;
    EXPECT_EQ(lu.rows(), n);
    const Eigen::VectorXd y = lu.solve(b);
    const double cond = M.cwiseAbs().colwise().sum().maxCoeff() * M.inverse().cwiseAbs().colwise().sum().maxCoeff();
    EXPECT_LT((y - x).norm() / x.norm(), 1e3 * cond * std::numeric_limits<double>::epsilon()) << n;
    // dgecon estimates 1 / cond_1 from below on |M^-1|_1 (within a factor of a few).
    EXPECT_GT(lu.rcond() * cond, 0.99) << n;
    EXPECT_LT(lu.rcond() * cond, 10.0) << n;
  }
}

TEST(DenseLU, SingularAndInvalidInput) {
  Eigen::MatrixXd S = test_matrix(5);
  S.row(3) = S.row(1);  // exactly singular after elimination: a zero pivot or rcond ~ eps
  solve::DenseLU lu;
  ASSERT_TRUE(lu.compute(S));
  EXPECT_LT(lu.rcond(), 1e-14);
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(4, 4);
  ASSERT_TRUE(lu.compute(Z));
  EXPECT_EQ(lu.rcond(), 0.0);
  EXPECT_THROW(lu.solve(Eigen::VectorXd::Ones(4)), Error);
  EXPECT_FALSE(lu.compute(Eigen::MatrixXd::Ones(3, 4)));
  Eigen::MatrixXd N = test_matrix(3);
  N(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(lu.compute(N));
  EXPECT_THROW(lu.solve(Eigen::VectorXd::Ones(3)), Error);
  ASSERT_TRUE(lu.compute(test_matrix(3)));
  EXPECT_THROW(lu.solve(Eigen::VectorXd::Ones(4)), Error);  // wrong size
  ASSERT_TRUE(lu.compute(Eigen::MatrixXd(0, 0)));
  EXPECT_EQ(lu.solve(Eigen::VectorXd(0)).size(), 0);
}
