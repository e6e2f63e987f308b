// online/affine_whitening.hpp: L L' = A_hat(mu) and L^-1 A L^-T = I for one, two (the simultaneous
// diagonalization) and three terms (the Cholesky form); the positive-definiteness verdict equal
// to the Cholesky factorization's, including a term of negative coefficient; an indefinite sum
// of two terms falls back to the Cholesky form.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "contactrb/online/affine_whitening.hpp"

namespace online = contactrb::online;

namespace {
Eigen::MatrixXd spd(int n, int seed, double shift) {
  std::srand(static_cast<unsigned>(seed));
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, n);
  return B * B.transpose() + shift * Eigen::MatrixXd::Identity(n, n);
}

// A semi-definite term of rank r: one body's stiffness seen by a basis of both bodies.
Eigen::MatrixXd low_rank(int n, int r, int seed) {
  std::srand(static_cast<unsigned>(seed));
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, r);
  return B * B.transpose();
}

Eigen::MatrixXd assemble(const std::vector<Eigen::MatrixXd>& terms, const Eigen::VectorXd& theta) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(terms[0].rows(), terms[0].cols());
  for (std::size_t j = 0; j < terms.size(); ++j) A += theta(static_cast<Eigen::Index>(j)) * terms[j];
  return A;
}

// L^-1 A L^-T from the whitening's two solves, column by column.
Eigen::MatrixXd whitened(const online::AffineWhitening& w, const Eigen::MatrixXd& A) {
  Eigen::MatrixXd X = A;
  w.solve_factor(X);  // L^-1 A
  Eigen::MatrixXd Y = X.transpose();
  w.solve_factor(Y);  // L^-1 (L^-1 A)' = L^-1 A L^-T (A symmetric)
  return Y;
}

void expect_identity(const online::AffineWhitening& w, const Eigen::MatrixXd& A) {
  const Eigen::MatrixXd I = whitened(w, A);
  EXPECT_LT((I - Eigen::MatrixXd::Identity(A.rows(), A.cols())).norm(), 1e-11);
  // L^-T L^-1 = A^-1: solve_factor then solve_factor_transpose is A^-1 x.
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  Eigen::VectorXd y = x;
  w.solve_factor(y);
  w.solve_factor_transpose(y);
  EXPECT_LT((A * y - x).norm(), 1e-10 * A.norm() * y.norm());
  Eigen::MatrixXd Ym = x;
  w.solve_factor(Ym);
  w.solve_factor_transpose(Ym);
  EXPECT_LT((Ym.col(0) - y).norm(), 1e-12 * y.norm());
}
}  // namespace

TEST(AffineWhitening, OneTermIsDiagonalAndWhitens) {
  const std::vector<Eigen::MatrixXd> terms{spd(12, 1, 1.0)};
  online::AffineWhitening w;
  w.setup(terms);
  ASSERT_TRUE(w.diagonal_available());
  for (const double t : {0.3, 1.0, 7.5}) {
    const Eigen::VectorXd theta = Eigen::VectorXd::Constant(1, t);
    ASSERT_TRUE(w.factor(theta, assemble(terms, theta)));
    expect_identity(w, assemble(terms, theta));
  }
}

TEST(AffineWhitening, TwoBodiesOfTwoModuliAreDiagonalizedTogether) {
  // Two semi-definite terms (each body's stiffness) whose sum is definite, as hertz-3p's.
  const int n = 20;
  const std::vector<Eigen::MatrixXd> terms{low_rank(n, 12, 2), low_rank(n, 12, 3)};
  ASSERT_LT(terms[0].selfadjointView<Eigen::Lower>().eigenvalues().minCoeff(), 1e-10 * terms[0].norm());
  online::AffineWhitening w;
  w.setup(terms);
  ASSERT_TRUE(w.diagonal_available());
  // V diagonalizes each term: V'A_jV diagonal.
  for (const Eigen::MatrixXd& Aj : terms) {
    Eigen::MatrixXd D = w.basis().transpose() * Aj * w.basis();
    D.diagonal().setZero();
    EXPECT_LT(D.norm(), 1e-10 * Aj.norm());
  }
  for (const Eigen::Vector2d& theta : {Eigen::Vector2d(1.0, 1.0), Eigen::Vector2d(0.05, 3.0), Eigen::Vector2d(20.0, 0.5)}) {
    const Eigen::MatrixXd A = assemble(terms, theta);
    ASSERT_TRUE(w.factor(theta, A));
    EXPECT_TRUE(w.diagonal());
    expect_identity(w, A);
    ASSERT_TRUE(w.factor(theta, A, false));  // the Cholesky form asked: the same factorization's job
    EXPECT_FALSE(w.diagonal());
    expect_identity(w, A);
  }
}

TEST(AffineWhitening, PositiveDefinitenessVerdictIsTheCholeskyOne) {
  const int n = 15;
  const std::vector<Eigen::MatrixXd> terms{spd(n, 4, 0.5), low_rank(n, 5, 5)};
  online::AffineWhitening w;
  w.setup(terms);
  ASSERT_TRUE(w.diagonal_available());
  // A negative coefficient of the second term: A(theta) is definite for small |theta_2| only.
  int definite = 0, indefinite = 0;
  for (double t2 = -2.0; t2 <= 0.5; t2 += 0.01) {
    const Eigen::Vector2d theta(1.0, t2);
    const Eigen::MatrixXd A = assemble(terms, theta);
    const bool cholesky = Eigen::LLT<Eigen::MatrixXd>(A).info() == Eigen::Success &&
                          A.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff() > 1e-9 * A.norm();
    const double lmin = A.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff();
    if (std::abs(lmin) < 1e-9 * A.norm()) continue;  // at the boundary either verdict is round-off
    EXPECT_EQ(w.factor(theta, A), cholesky) << "theta_2 = " << t2;
    (cholesky ? definite : indefinite) += 1;
  }
  EXPECT_GT(definite, 10);
  EXPECT_GT(indefinite, 10);
}

TEST(AffineWhitening, ThreeTermsOrAnIndefiniteSumUseCholesky) {
  const int n = 10;
  const std::vector<Eigen::MatrixXd> three{spd(n, 6, 1.0), spd(n, 7, 1.0), spd(n, 8, 1.0)};
  online::AffineWhitening w;
  w.setup(three);
  EXPECT_FALSE(w.diagonal_available());
  const Eigen::Vector3d theta(0.5, 2.0, 1.5);
  ASSERT_TRUE(w.factor(theta, assemble(three, theta)));
  expect_identity(w, assemble(three, theta));

  const std::vector<Eigen::MatrixXd> indefinite{spd(n, 9, 1.0), -2.0 * spd(n, 9, 1.0)};
  w.setup(indefinite);
  EXPECT_FALSE(w.diagonal_available());
  const Eigen::Vector2d t(3.0, 1.0);  // 3 A - 2 A = A: definite
  ASSERT_TRUE(w.factor(t, assemble(indefinite, t)));
  expect_identity(w, assemble(indefinite, t));
  const Eigen::Vector2d bad(1.0, 1.0);  // A - 2 A = -A
  EXPECT_FALSE(w.factor(bad, assemble(indefinite, bad)));
}
