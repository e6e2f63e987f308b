// GMRES: a nonsymmetric system agrees with a dense LU solve; the preconditioner P = A gives the
// answer in one product; without convergence in the cap, converged is false and the residual
// reported is the true one.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "contactrb/solve/gmres.hpp"

using namespace contactrb;

namespace {
// A = I + 0.3 * (a fixed pseudo-random matrix, entries uniform in [-1, 1]) / sqrt(n): eigenvalues
// spread in a disc around 1, a few tens of GMRES iterations to 1e-13.
Eigen::MatrixXd test_matrix(int n) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  Eigen::MatrixXd A(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) A(i, j) = entry(rng);
  }
  return Eigen::MatrixXd::Identity(n, n) + 0.3 / std::sqrt(static_cast<double>(n)) * A;
}
}  // namespace

TEST(Gmres, MatchesADenseSolve) {
  const int n = 120;
  const Eigen::MatrixXd A = test_matrix(n);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -2.0, 5.0);
  const Eigen::VectorXd x_ref = A.partialPivLu().solve(b);
  auto apply = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return A * v; };
  auto identity = [](const Eigen::VectorXd& v) -> Eigen::VectorXd { return v; };
  // Restarted (every 10) and not: both reach the tolerance, with the true residual.
  for (int restart : {10, 200}) {
    const solve::GmresResult r = solve::gmres(apply, identity, b, 1e-13, 200, restart);
    ASSERT_TRUE(r.converged) << restart;
    EXPECT_LE(r.relative_residual, 1e-13);
    EXPECT_NEAR((b - A * r.x).norm() / b.norm(), r.relative_residual, 1e-15);
    EXPECT_LT((r.x - x_ref).norm(), 1e-11 * x_ref.norm());
    EXPECT_GT(r.iterations, 5);  // not trivially one step
  }
  // An exact preconditioner: one product.
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu = A.partialPivLu();
  auto exact = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return lu.solve(v); };
  const solve::GmresResult p = solve::gmres(apply, exact, b, 1e-13, 200);
  EXPECT_TRUE(p.converged);
  EXPECT_EQ(p.iterations, 1);
  // A cap of 3 products: not converged, and the residual is the true one.
  const solve::GmresResult capped = solve::gmres(apply, identity, b, 1e-13, 3);
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.iterations, 3);
  EXPECT_NEAR((b - A * capped.x).norm() / b.norm(), capped.relative_residual, 1e-14);
  EXPECT_GT(capped.relative_residual, 1e-6);
}

TEST(Gmres, ZeroAndNonFiniteRightHandSides) {
  auto identity = [](const Eigen::VectorXd& v) -> Eigen::VectorXd { return v; };
  const solve::GmresResult zero = solve::gmres(identity, identity, Eigen::VectorXd::Zero(4), 1e-12, 10);
  EXPECT_TRUE(zero.converged);
  EXPECT_EQ(zero.x, Eigen::VectorXd::Zero(4));
  Eigen::VectorXd bad = Eigen::VectorXd::Ones(4);
  bad(2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(solve::gmres(identity, identity, bad, 1e-12, 10).converged);
}
