// largest_constrained_eigenvalue (Lanczos on C_D M in the S inner product) against an independent
// dense computation: a basis Z of ker D (the SVD of D), then every eigenvalue of the dense pencil
// (Z'MZ, Z'SZ) with S = C^-1 formed explicitly. Indefinite, negative and rank-deficient M,
// dependent constraint rows, no constraint, M that vanishes on ker D, and invalid sizes. The
// function returns the positive part of that eigenvalue (its header).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/solve/constrained_eigenvalue.hpp"

using namespace contactrb;

namespace {

using Index = Eigen::Index;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

Eigen::MatrixXd random_matrix(Index rows, Index cols, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd X(rows, cols);
  for (Index j = 0; j < cols; ++j) {
    for (Index i = 0; i < rows; ++i) X(i, j) = normal(rng);
  }
  return X;
}

// S symmetric positive definite with condition about 1e3, as a Schur complement of a stiffness.
Eigen::MatrixXd spd(Index m, std::mt19937& rng) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(random_matrix(m, m, rng));
  const Eigen::MatrixXd U = qr.householderQ();
  Eigen::VectorXd d(m);
  for (Index i = 0; i < m; ++i) d(i) = std::pow(1e3, static_cast<double>(i) / static_cast<double>(m - 1));
  return U * d.asDiagonal() * U.transpose();
}

// Sparse symmetric M = sum of `terms` local symmetric blocks on 4 consecutive indices with
// eigenvalues of both signs (or only `sign` when nonzero): low rank, like a geometric stiffness.
Eigen::SparseMatrix<double> local_sum(Index m, int terms, int sign, std::mt19937& rng) {
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(m, m);
  std::uniform_int_distribution<Index> first(0, m - 4);
  for (int t = 0; t < terms; ++t) {
    const Eigen::MatrixXd b = random_matrix(4, 1, rng);
    const double s = sign != 0 ? sign : (t % 2 == 0 ? 1.0 : -1.0);
    const Index at = first(rng);
    dense.block(at, at, 4, 4) += s * b * b.transpose();
  }
  return dense.sparseView();
}

// Rows with a few entries each (a constraint row touches a slave node and a master segment).
RowSparse sparse_rows(Index a, Index m, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<Index> column(0, m - 1);
  std::vector<Eigen::Triplet<double>> t;
  for (Index r = 0; r < a; ++r) {
    for (int k = 0; k < 6; ++k) t.emplace_back(r, column(rng), normal(rng));
  }
  RowSparse D(a, m);
  D.setFromTriplets(t.begin(), t.end());
  return D;
}

// The dense truth: the positive part of the largest eigenvalue of (Z'MZ, Z'SZ), Z an orthonormal basis of ker D from the SVD.
double dense_largest(const Eigen::MatrixXd& S, const Eigen::MatrixXd& M, const Eigen::MatrixXd& D) {
  Eigen::MatrixXd Z = Eigen::MatrixXd::Identity(S.rows(), S.rows());
  if (D.rows() > 0) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(D, Eigen::ComputeFullV);
    const double cut = 1e-10 * svd.singularValues()(0);
    Index rank = 0;
    while (rank < svd.singularValues().size() && svd.singularValues()(rank) > cut) ++rank;
    Z = svd.matrixV().rightCols(S.rows() - rank);
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Z.transpose() * M * Z, Z.transpose() * S * Z,
                                                                      Eigen::EigenvaluesOnly);
  return std::max(0.0, eig.eigenvalues().maxCoeff());
}

struct Problem {
  Eigen::MatrixXd S, C;
  Eigen::SparseMatrix<double> M;
  RowSparse D;
};

Problem make_problem(Index m, Index a, int terms, int sign, unsigned seed) {
  std::mt19937 rng(seed);
  Problem p;
  p.S = spd(m, rng);
  p.C = p.S.inverse();
  p.M = local_sum(m, terms, sign, rng);
  p.D = sparse_rows(a, m, rng);
  return p;
}

}  // namespace

TEST(ConstrainedEigenvalue, EqualsTheDensePencilOnTheNullSpace) {
  struct Case {
    Index m, a;
    int terms, sign;
  };
  for (const Case c : {Case{60, 15, 12, 0}, Case{120, 30, 40, 0}, Case{120, 30, 40, 1}, Case{80, 0, 20, 0},
                       Case{200, 50, 30, -1}, Case{60, 10, 200, -1}}) {
    const Problem p = make_problem(c.m, c.a, c.terms, c.sign, static_cast<unsigned>(c.m + c.a + c.sign + 7));
    const double truth = dense_largest(p.S, Eigen::MatrixXd(p.M), Eigen::MatrixXd(p.D));
    const solve::ConstrainedEigenvalueResult r = solve::largest_constrained_eigenvalue(p.C, p.M, p.D);
    ASSERT_TRUE(r.converged) << c.m << " " << c.a;
    EXPECT_LE(r.residual, 1e-12);
    EXPECT_GT(r.iterations, 1);
    EXPECT_LE(r.iterations, c.m);
    if (c.sign < 0) {
      EXPECT_EQ(r.value, 0.0);  // M <= 0: its null space on ker D gives 0
    } else {
      EXPECT_GT(truth, 0.0);
      EXPECT_NEAR(r.value, truth, 1e-10 * truth) << "m " << c.m << " a " << c.a << " sign " << c.sign;
    }
  }
}

// Rows repeated and combined leave ker D, hence the eigenvalue, as they are: the pseudo-inverse
// of D C D' takes over from its Cholesky factor.
TEST(ConstrainedEigenvalue, DependentRowsKeepTheNullSpace) {
  const Problem p = make_problem(90, 20, 25, 0, 11);
  const Eigen::MatrixXd D = Eigen::MatrixXd(p.D);
  Eigen::MatrixXd dependent(D.rows() + 2, D.cols());
  dependent << D, D.row(3), 2.0 * D.row(0) - D.row(7);
  const RowSparse Dd = dependent.sparseView();
  const solve::ConstrainedEigenvalueResult a = solve::largest_constrained_eigenvalue(p.C, p.M, p.D);
  const solve::ConstrainedEigenvalueResult b = solve::largest_constrained_eigenvalue(p.C, p.M, Dd);
  ASSERT_TRUE(a.converged && b.converged);
  EXPECT_NEAR(b.value, a.value, 1e-9 * std::abs(a.value));
  EXPECT_NEAR(b.value, dense_largest(p.S, Eigen::MatrixXd(p.M), dependent), 1e-9 * std::abs(a.value));
}

// M = D'BD vanishes on ker D: every eigenvalue there is 0. M = 0 too.
TEST(ConstrainedEigenvalue, VanishesWhenMIsZeroOnTheNullSpace) {
  const Problem p = make_problem(50, 10, 5, 0, 5);
  std::mt19937 rng(9);
  const Eigen::MatrixXd X = random_matrix(10, 10, rng);
  const Eigen::MatrixXd B = X + X.transpose();
  const Eigen::SparseMatrix<double> M = (Eigen::MatrixXd(p.D.transpose()) * B * Eigen::MatrixXd(p.D)).sparseView();
  const solve::ConstrainedEigenvalueResult r = solve::largest_constrained_eigenvalue(p.C, M, p.D);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.value, 0.0);
  const Eigen::SparseMatrix<double> zero(50, 50);
  EXPECT_EQ(solve::largest_constrained_eigenvalue(p.C, zero, p.D).value, 0.0);
}

TEST(ConstrainedEigenvalue, RejectsSizesThatDoNotMatch) {
  const Problem p = make_problem(30, 5, 5, 0, 3);
  const Eigen::SparseMatrix<double> M29(29, 29);
  EXPECT_THROW(solve::largest_constrained_eigenvalue(p.C, M29, p.D), Error);
  const RowSparse D29(5, 29);
  EXPECT_THROW(solve::largest_constrained_eigenvalue(p.C, p.M, D29), Error);
  EXPECT_THROW(solve::largest_constrained_eigenvalue(p.C.leftCols(29), p.M, p.D), Error);
}
