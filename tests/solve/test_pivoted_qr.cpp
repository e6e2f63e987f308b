// solve::pivoted_qr (LAPACK dgeqp3) against its defining identities: A P = Q R with Q
// orthonormal, so |A y| = |R P' y|; the rank rule; and against Eigen's unblocked
// ColPivHouseholderQR, an independent implementation of the same factorization.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <random>

#include "contactrb/common/error.hpp"
#include "contactrb/solve/blas_threads.hpp"
#include "contactrb/solve/pivoted_qr.hpp"

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

MatrixXd random_matrix(Index m, Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N01;
  return MatrixXd::NullaryExpr(m, n, [&] { return N01(rng); });
}

VectorXd apply_RPt(const contactrb::solve::PivotedQR& qr, const VectorXd& y) {
  VectorXd Pty(y.size());
  for (std::size_t k = 0; k < qr.permutation.size(); ++k) Pty(static_cast<Index>(k)) = y(qr.permutation[k]);
  return qr.R * Pty;
}

TEST(PivotedQR, KeepsEveryNormOfAWideAndATallMatrix) {
  for (const auto& [m, n] : {std::pair<Index, Index>{40, 300}, {300, 40}}) {
    const MatrixXd A = random_matrix(m, n, 3);
    const auto qr = contactrb::solve::pivoted_qr(A, 1e-13);
    EXPECT_EQ(qr.R.rows(), std::min(m, n));
    EXPECT_EQ(qr.R.cols(), n);
    EXPECT_DOUBLE_EQ(qr.R.bottomLeftCorner(qr.R.rows() - 1, 1).cwiseAbs().maxCoeff(), 0.0);  // upper trapezoidal
    for (unsigned s = 0; s < 5; ++s) {
      const VectorXd y = random_matrix(n, 1, 10 + s);
      EXPECT_NEAR(apply_RPt(qr, y).norm(), (A * y).norm(), 1e-13 * (A * y).norm()) << m << " x " << n;
    }
    // Pivoting: the diagonal of R does not increase in magnitude.
    for (Index k = 1; k < qr.R.rows(); ++k) EXPECT_LE(std::abs(qr.R(k, k)), std::abs(qr.R(k - 1, k - 1)) * (1 + 1e-12));
  }
}

TEST(PivotedQR, DropsTheRowsOfARankDeficientMatrixAsEigenDoes) {
  const MatrixXd A = random_matrix(60, 7, 5) * random_matrix(7, 90, 6);  // rank 7
  const auto qr = contactrb::solve::pivoted_qr(A, 1e-13);
  Eigen::ColPivHouseholderQR<MatrixXd> eigen_qr(A);
  eigen_qr.setThreshold(1e-13);
  EXPECT_EQ(qr.R.rows(), 7);
  EXPECT_EQ(eigen_qr.rank(), 7);
  // Same |R_kk| (the pivoted QR is unique up to the signs of Q's columns when the pivots differ
  // by more than round-off).
  for (Index k = 0; k < 7; ++k) {
    EXPECT_NEAR(std::abs(qr.R(k, k)), std::abs(eigen_qr.matrixQR()(k, k)), 1e-10 * std::abs(qr.R(0, 0)));
  }
  const VectorXd y = random_matrix(90, 1, 7);
  EXPECT_NEAR(apply_RPt(qr, y).norm(), (A * y).norm(), 1e-12 * (A * y).norm());
}

// The same factor bit for bit whatever the BLAS thread count of the caller (OpenBLAS threads its
// matrix products, whose sums then round differently).
TEST(PivotedQR, SameBitsWhateverTheBlasThreads) {
  const MatrixXd A = random_matrix(600, 1500, 9);
  contactrb::solve::PivotedQR one, two;
  {
    const contactrb::solve::ScopedBlasThreads threads(1);
    one = contactrb::solve::pivoted_qr(A, 1e-13);
  }
  {
    const contactrb::solve::ScopedBlasThreads threads(2);
    two = contactrb::solve::pivoted_qr(A, 1e-13);
  }
  EXPECT_EQ(one.permutation, two.permutation);
  ASSERT_EQ(one.R.rows(), two.R.rows());
  EXPECT_TRUE((one.R.array() == two.R.array()).all());
}

TEST(PivotedQR, ZeroMatrixKeepsOneRowAndNonFiniteIsAnError) {
  const auto qr = contactrb::solve::pivoted_qr(MatrixXd::Zero(5, 8), 1e-13);
  EXPECT_EQ(qr.R.rows(), 1);
  EXPECT_DOUBLE_EQ(qr.R.norm(), 0.0);
  MatrixXd bad = random_matrix(4, 4, 1);
  bad(2, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(contactrb::solve::pivoted_qr(bad, 1e-13), contactrb::Error);
}

}  // namespace
