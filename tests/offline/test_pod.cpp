#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <Eigen/SparseCore>
#include <cmath>
#include <random>

#include "contactrb/common/error.hpp"
#include "contactrb/offline/pod.hpp"

using namespace contactrb::offline;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// A sparse SPD matrix: 1D stiffness (2, -1) plus a positive diagonal (an H1-like Gram matrix).
Eigen::SparseMatrix<double> h1_like(int n) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + 0.5 + 0.01 * i);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> M(n, n);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

// Snapshots with prescribed decay: S = U diag(d) V' with random U, V.
MatrixXd decaying_snapshots(int n, int P, double ratio, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N01;
  MatrixXd A = MatrixXd::NullaryExpr(n, P, [&] { return N01(rng); });
  MatrixXd B = MatrixXd::NullaryExpr(P, P, [&] { return N01(rng); });
  Eigen::HouseholderQR<MatrixXd> qa(A), qb(B);
  const MatrixXd U = qa.householderQ() * MatrixXd::Identity(n, P);
  const MatrixXd V = qb.householderQ() * MatrixXd::Identity(P, P);
  VectorXd d(P);
  for (int i = 0; i < P; ++i) d(i) = 10.0 * std::pow(ratio, i);
  return U * d.asDiagonal() * V.transpose();
}

double projection_error_sq(const MatrixXd& S, const Eigen::SparseMatrix<double>& M, const MatrixXd& Phi) {
  double sum = 0.0;
  for (Eigen::Index p = 0; p < S.cols(); ++p) {
    const VectorXd s = S.col(p);
    const VectorXd r = s - Phi * (Phi.transpose() * (M * s));
    sum += r.dot(M * r);
  }
  return sum;
}

// S = Phi diag(sigma) V' with Phi' M Phi = I (M-orthonormalized Gaussian columns), V orthogonal
// and sigma_i = 3 * 10^(-12 i / (P - 1)): snapshots whose M-singular values are sigma exactly.
MatrixXd snapshots_with_known_spectrum(const Eigen::SparseMatrix<double>& M, int P, VectorXd& sigma) {
  std::mt19937 rng(5);
  std::normal_distribution<double> N01;
  const MatrixXd A = MatrixXd::NullaryExpr(M.rows(), P, [&] { return N01(rng); });
  const Eigen::LLT<MatrixXd> llt(A.transpose() * (M * A));
  const MatrixXd Phi = llt.matrixU().solve<Eigen::OnTheRight>(A);  // Phi' M Phi = I
  EXPECT_LT((Phi.transpose() * (M * Phi) - MatrixXd::Identity(P, P)).cwiseAbs().maxCoeff(), 1e-13);
  Eigen::HouseholderQR<MatrixXd> qv(MatrixXd::NullaryExpr(P, P, [&] { return N01(rng); }));
  const MatrixXd V = qv.householderQ() * MatrixXd::Identity(P, P);
  sigma.resize(P);
  for (int i = 0; i < P; ++i) sigma(i) = 3.0 * std::pow(10.0, -12.0 * i / (P - 1));
  return Phi * sigma.asDiagonal() * V.transpose();
}

}  // namespace

TEST(POD, ProjectionErrorEqualsDiscardedSingularValues) {
  const int n = 40, P = 12;
  const auto M = h1_like(n);
  const MatrixXd S = decaying_snapshots(n, P, 0.5, 3);
  for (int N = 0; N <= P; ++N) {
    PODSettings s;
    s.max_modes = N;
    const PODResult r = pod(S, M, s);
    ASSERT_EQ(r.N, N);
    ASSERT_EQ(r.basis.cols(), N);
    const double err = projection_error_sq(S, M, r.basis);
    const double discarded = r.singular_values.tail(P - N).squaredNorm();
    EXPECT_NEAR(r.discarded_energy, discarded, 1e-14 * S.squaredNorm());
    // 1e-10 relative while the discarded part is not round-off of the total (the correlation
    // matrix carries an absolute error ~ 1e-16 |S|_M^2), 1e-13 of the total below that.
    const double total = r.singular_values.squaredNorm();
    if (discarded > 1e-4 * total)
      EXPECT_NEAR(err, discarded, 1e-10 * discarded) << "N = " << N;
    else
      EXPECT_NEAR(err, discarded, 1e-13 * total) << "N = " << N;
  }
}

TEST(POD, BasisIsMOrthonormalAndSingularValuesMatchWeightedSVD) {
  const int n = 30, P = 10;
  const auto M = h1_like(n);
  const MatrixXd S = decaying_snapshots(n, P, 0.2, 5);  // sigma down to 1e-6 relative
  PODSettings s;
  s.tolerance = 0.0;
  const PODResult r = pod(S, M, s);
  EXPECT_EQ(r.rank, P);
  EXPECT_EQ(r.N, P);
  const MatrixXd G = r.basis.transpose() * (M * r.basis);
  EXPECT_LT((G - MatrixXd::Identity(P, P)).cwiseAbs().maxCoeff(), 1e-12);
  // Independent truth: singular values of L' S with M = L L'.
  const MatrixXd Md = MatrixXd(M);
  const Eigen::LLT<MatrixXd> llt(Md);
  const MatrixXd LtS = llt.matrixU() * S;
  const VectorXd sv = Eigen::JacobiSVD<MatrixXd>(LtS).singularValues();
  for (int i = 0; i < P; ++i) EXPECT_NEAR(r.singular_values(i), sv(i), 1e-10 * sv(0)) << i;
  // Decreasing.
  for (int i = 1; i < P; ++i) EXPECT_LE(r.singular_values(i), r.singular_values(i - 1));
}

// One weight for several PODs (a greedy's builds) gives each the bits of pod(S, M); without the
// basis, the same singular values and truncation, and no modes.
TEST(POD, SharedWeightAndSingularValuesOnlyGiveTheSameBits) {
  const int n = 30;
  const auto M = h1_like(n);
  const PODWeight weight(M);
  PODSettings s;
  s.tolerance = 1e-3;
  for (int P : {4, 7, 10}) {
    const MatrixXd S = decaying_snapshots(n, P, 0.2, 7 + static_cast<unsigned>(P));
    const PODResult a = pod(S, M, s);
    const PODResult b = pod(S, weight, s);
    EXPECT_EQ(a.N, b.N);
    EXPECT_EQ(a.rank, b.rank);
    EXPECT_EQ((a.singular_values - b.singular_values).cwiseAbs().maxCoeff(), 0.0) << P;
    EXPECT_EQ((a.basis - b.basis).cwiseAbs().maxCoeff(), 0.0) << P;
    PODSettings values_only = s;
    values_only.basis = false;
    const PODResult c = pod(S, weight, values_only);
    EXPECT_EQ(c.N, a.N);
    EXPECT_EQ(c.threshold, a.threshold);
    EXPECT_EQ(c.discarded_energy, a.discarded_energy);
    EXPECT_EQ((c.singular_values - a.singular_values).cwiseAbs().maxCoeff(), 0.0) << P;
    EXPECT_EQ(c.basis.size(), 0);
  }
  Eigen::SparseMatrix<double> indefinite = M;
  indefinite.coeffRef(3, 3) = -1.0;
  EXPECT_THROW(PODWeight{indefinite}, contactrb::Error);
  EXPECT_THROW(pod(MatrixXd::Ones(n + 1, 2), weight, s), contactrb::Error);
}

TEST(POD, AbsoluteThresholdKeepsSingularValuesAboveIt) {
  const int n = 30, P = 10;
  const auto M = h1_like(n);
  const MatrixXd S = decaying_snapshots(n, P, 0.3, 7);
  for (double eps : {1e1, 1.0, 1e-1, 1e-2, 1e-3, 1e-5}) {
    PODSettings s;
    s.tolerance = eps;
    const PODResult r = pod(S, M, s);
    int expected = 0;
    for (int i = 0; i < P; ++i) expected += r.singular_values(i) > eps ? 1 : 0;
    EXPECT_EQ(r.N, expected) << "eps = " << eps;
    s.truncation = PODTruncation::ProjectionError;
    const PODResult e = pod(S, M, s);
    EXPECT_LE(std::sqrt(e.discarded_energy), eps);
    if (e.N > 0) {  // one mode fewer would exceed the tolerance
      const double more = e.discarded_energy + std::pow(e.singular_values(e.N - 1), 2);
      EXPECT_GT(std::sqrt(more), eps);
    }
    EXPECT_GE(e.N, r.N);  // sqrt(tail) >= largest discarded sigma, so no sigma > eps is discarded
  }
}

TEST(POD, RankDeficientSnapshotsGiveTheNumericalRank) {
  const int n = 25;
  const auto M = h1_like(n);
  const MatrixXd base = decaying_snapshots(n, 4, 0.5, 11);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  MatrixXd C = MatrixXd::NullaryExpr(4, 9, [&] { return U(rng); });
  MatrixXd S(n, 13);
  S << base, base * C;  // 13 snapshots of rank 4, plus duplicates below
  S.col(12) = S.col(0);
  PODSettings s;
  s.tolerance = 0.0;
  const PODResult r = pod(S, M, s);
  EXPECT_EQ(r.rank, 4);
  EXPECT_EQ(r.N, 4);
  EXPECT_TRUE(r.basis.allFinite());
  const MatrixXd G = r.basis.transpose() * (M * r.basis);
  EXPECT_LT((G - MatrixXd::Identity(4, 4)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(projection_error_sq(S, M, r.basis), 1e-20 * S.squaredNorm() + 1e-24);
  // A fixed N above the rank is capped.
  s.max_modes = 8;
  EXPECT_EQ(pod(S, M, s).N, 4);
}

// Snapshots S = Phi diag(sigma) V' with Phi M-orthonormal and V orthogonal have the M-singular
// values sigma exactly: here sigma_i / sigma_1 = 10^(-12 i / 15), i = 0 .. 15, down to 1e-12.
// The thin SVD recovers all of them (the method of snapshots, i.e. the eigenvalues of S' M S,
// loses those below about 1e-8 sigma_1); relative truncation is scale-free.
TEST(POD, ThinSVDRecoversSingularValuesDownTo1e12Relative) {
  const int n = 200, P = 16;
  const auto M = h1_like(n);
  VectorXd sigma;
  const MatrixXd S = snapshots_with_known_spectrum(M, P, sigma);

  PODSettings s;
  s.tolerance = 0.0;
  const PODResult r = pod(S, M, s);
  EXPECT_EQ(r.rank, P);
  for (int i = 0; i < P; ++i) {
    EXPECT_NEAR(r.singular_values(i), sigma(i), 2e-15 * sigma(0)) << "i = " << i;
  }
  // Relative truncation: keep sigma_i / sigma_1 > 1e-11, i.e. i <= 13 (10^(-12*13/15) = 1.6e-11,
  // 10^(-12*14/15) = 1.6e-12); the same N for snapshots scaled by 1e9 and by 1e-3.
  s.relative = true;
  s.tolerance = 1e-11;
  for (double scale : {1.0, 1e9, 1e-3}) {
    const PODResult t = pod(MatrixXd(scale * S), M, s);
    EXPECT_EQ(t.N, 14) << "scale " << scale;
    EXPECT_NEAR(t.threshold, 1e-11 * 3.0 * scale, 1e-24 * scale);
    const MatrixXd Gt = t.basis.transpose() * (M * t.basis);
    EXPECT_LT((Gt - MatrixXd::Identity(t.N, t.N)).cwiseAbs().maxCoeff(), 1e-12);
    // The projection error is the discarded energy sigma_14^2 + sigma_15^2 (relative to sigma_1^2:
    // 2.5e-24), to a few percent: the 14 modes are accurate far below 1e-8 sigma_1.
    const double discarded = scale * scale * (sigma(14) * sigma(14) + sigma(15) * sigma(15));
    EXPECT_NEAR(projection_error_sq(MatrixXd(scale * S), M, t.basis), discarded, 0.05 * discarded)
        << "scale " << scale;
  }
  // Discarded energy relative to the total (ProjectionError): sqrt(sum_{i>=N} sigma_i^2 / sum sigma^2)
  // is 4.0e-3 for N = 3 and 6.3e-4 for N = 4, so 1e-3 keeps N = 4.
  s.truncation = PODTruncation::ProjectionError;
  s.tolerance = 1e-3;
  EXPECT_EQ(pod(S, M, s).N, 4);
}

TEST(POD, IdentityInnerProductAndEdgeCases) {
  const MatrixXd S = decaying_snapshots(12, 5, 0.5, 13);
  PODSettings s;
  s.tolerance = 0.0;
  const PODResult r = pod(S, s);
  EXPECT_EQ(r.N, 5);
  EXPECT_LT((r.basis.transpose() * r.basis - MatrixXd::Identity(5, 5)).cwiseAbs().maxCoeff(), 1e-13);
  const VectorXd sv = Eigen::JacobiSVD<MatrixXd>(S).singularValues();
  EXPECT_LT((r.singular_values - sv).cwiseAbs().maxCoeff(), 1e-12 * sv(0));
  // Zero snapshots: rank 0, no mode.
  const PODResult z = pod(MatrixXd::Zero(6, 3), s);
  EXPECT_EQ(z.rank, 0);
  EXPECT_EQ(z.N, 0);
  EXPECT_EQ(z.basis.cols(), 0);
}

TEST(POD, InvalidInputThrows) {
  const MatrixXd S = MatrixXd::Ones(5, 3);
  EXPECT_THROW(pod(S, h1_like(4)), contactrb::Error);
  PODSettings bad;
  bad.tolerance = -1.0;
  EXPECT_THROW(pod(S, bad), contactrb::Error);
  bad = {};
  bad.max_modes = -2;
  EXPECT_THROW(pod(S, bad), contactrb::Error);
  MatrixXd nan = S;
  nan(0, 0) = std::nan("");
  EXPECT_THROW(pod(nan), contactrb::Error);
}

// The method of snapshots against the thin SVD, on snapshots with known M-singular values
// 3 * 10^(-12 i / 15): the same values down to about 1e-8 sigma_1, the same truncation at a
// relative 1e-3, the same subspace, an M-orthonormal basis; the numerical rank stops where the
// squared values reach round-off.
TEST(POD, CorrelationMethodAgreesWithTheThinSVDAboveItsAccuracy) {
  const int n = 200, P = 16;
  const auto M = h1_like(n);
  VectorXd sigma;
  const MatrixXd S = snapshots_with_known_spectrum(M, P, sigma);

  PODSettings s;
  s.relative = true;
  s.tolerance = 1e-3;
  const PODResult svd = pod(S, M, s);
  const PODResult cor = pod_by_correlation(S, M, s);
  EXPECT_EQ(svd.N, 4);  // sigma_i / sigma_1 = 10^(-0.8 i): 4.0e-3 at i = 3, 6.3e-4 at i = 4
  EXPECT_EQ(cor.N, svd.N);
  for (int i = 0; i < P; ++i) {
    if (sigma(i) > 1e-6 * sigma(0)) {
      EXPECT_NEAR(cor.singular_values(i), sigma(i), 1e-8 * sigma(0)) << "i = " << i;
    }
  }
  EXPECT_LT(cor.rank, P);  // sigma_15 = 3e-12: below the method's floor
  EXPECT_GE(cor.rank, 9);  // sigma_8 = 4.5e-7 sigma_1: above it
  const MatrixXd G = cor.basis.transpose() * (M * cor.basis);
  EXPECT_LT((G - MatrixXd::Identity(cor.N, cor.N)).cwiseAbs().maxCoeff(), 1e-12);
  // The same subspace: the M-projection of one basis onto the other keeps its norm.
  const MatrixXd C = svd.basis.transpose() * (M * cor.basis);
  EXPECT_NEAR(C.squaredNorm(), static_cast<double>(cor.N), 1e-8);
}
