// SelectedInverse: blocks of A^-1 by sparse substitutions agree with a dense inverse; the cache
// gives the same block whatever the order of the requests; statuses for bad input.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/solve/selected_inverse.hpp"

using namespace contactrb;

namespace {
// 2D five-point Laplacian plus identity on an m x m grid: SPD, with a nontrivial fill.
Eigen::SparseMatrix<double> grid_matrix(int m) {
  std::vector<Eigen::Triplet<double>> t;
  auto id = [m](int i, int j) { return i * m + j; };
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      t.emplace_back(id(i, j), id(i, j), 5.0 + 0.01 * (i + 2 * j));
      if (i + 1 < m) {
        t.emplace_back(id(i, j), id(i + 1, j), -1.0);
        t.emplace_back(id(i + 1, j), id(i, j), -1.0);
      }
      if (j + 1 < m) {
        t.emplace_back(id(i, j), id(i, j + 1), -1.0);
        t.emplace_back(id(i, j + 1), id(i, j), -1.0);
      }
    }
  }
  Eigen::SparseMatrix<double> A(m * m, m * m);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}
}  // namespace

TEST(SelectedInverse, BlocksAndSolvesMatchTheDenseInverse) {
  const Eigen::SparseMatrix<double> A = grid_matrix(15);
  const Eigen::MatrixXd inv = Eigen::MatrixXd(A).inverse();
  solve::SelectedInverse s;
  ASSERT_EQ(s.compute(A), solve::SelectedInverseStatus::Success);
  EXPECT_GT(s.factor_nonzeros(), A.nonZeros() / 2);
  const std::vector<int> first = {0, 7, 14, 112, 224};
  const std::vector<int> second = {224, 3, 7, 200};  // overlaps the first: 224 and 7 cached
  for (const auto& idx : {first, second}) {
    const Eigen::MatrixXd G = s.block(idx);
    for (std::size_t a = 0; a < idx.size(); ++a) {
      for (std::size_t b = 0; b < idx.size(); ++b) {
        EXPECT_NEAR(G(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)), inv(idx[a], idx[b]), 1e-14)
            << idx[a] << ", " << idx[b];
      }
    }
  }
  EXPECT_EQ(s.cached_columns(), 7);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  EXPECT_LT((s.solve(b) - inv * b).norm(), 1e-13 * (inv * b).norm());
}

// A 32 x 32 grid (1 024 rows): a deep supernodal tree, so the batched forward sweep scatters
// across many levels. One batch of 150 indices, then a batch that mixes cached and new ones;
// every entry equals the dense inverse's.
TEST(SelectedInverse, LargeBatchesMatchTheDenseInverse) {
  const Eigen::SparseMatrix<double> A = grid_matrix(32);
  const Eigen::MatrixXd inv = Eigen::MatrixXd(A).llt().solve(Eigen::MatrixXd::Identity(A.rows(), A.cols()));
  solve::SelectedInverse s;
  ASSERT_EQ(s.compute(A), solve::SelectedInverseStatus::Success);
  std::vector<int> first, second;
  for (int i = 0; i < 150; ++i) first.push_back((i * 37) % 1024);  // spread over the grid
  for (int i = 0; i < 120; ++i) second.push_back((i * 53 + 11) % 1024);
  second.push_back(first[3]);
  for (const auto& idx : {first, second}) {
    const Eigen::MatrixXd G = s.block(idx);
    double worst = 0.0;
    for (std::size_t a = 0; a < idx.size(); ++a) {
      for (std::size_t b = 0; b < idx.size(); ++b) {
        worst = std::max(worst, std::abs(G(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) - inv(idx[a], idx[b])));
      }
    }
    EXPECT_LT(worst, 1e-14 * inv.cwiseAbs().maxCoeff());
  }
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  EXPECT_LT((s.solve(b) - inv * b).norm(), 1e-13 * (inv * b).norm());
  // A sparse right-hand side on `first` (a repeated index adds up), the whole solution and
  // the solution on `second` only.
  std::vector<int> in(first.begin(), first.begin() + 40);
  in.push_back(in[0]);
  Eigen::VectorXd b_in = Eigen::VectorXd::LinSpaced(static_cast<Eigen::Index>(in.size()), 0.5, -3.0);
  Eigen::VectorXd b_full = Eigen::VectorXd::Zero(A.rows());
  for (std::size_t a = 0; a < in.size(); ++a) b_full(in[a]) += b_in(static_cast<Eigen::Index>(a));
  const Eigen::VectorXd x = inv * b_full;
  EXPECT_LT((s.solve_sparse(in, b_in) - x).norm(), 1e-13 * x.norm());
  const Eigen::VectorXd part = s.solve_sparse(in, b_in, &second);
  for (int i = 0; i < A.rows(); ++i) {
    const bool wanted = std::find(second.begin(), second.end(), i) != second.end();
    EXPECT_NEAR(part(i), wanted ? x(i) : 0.0, 1e-13 * x.cwiseAbs().maxCoeff()) << i;
  }
  // Twice in a row: the work vector is clean between calls.
  EXPECT_LT((s.solve_sparse(in, b_in, &second) - part).norm(), 1e-15 * x.norm());
  EXPECT_THROW(s.solve_sparse({0, 1}, Eigen::VectorXd::Ones(1)), Error);
  EXPECT_THROW(s.solve_sparse({static_cast<int>(A.rows())}, Eigen::VectorXd::Ones(1)), Error);
}

TEST(SelectedInverse, StatusesForBadInput) {
  solve::SelectedInverse s;
  EXPECT_EQ(s.compute(Eigen::SparseMatrix<double>(3, 4)), solve::SelectedInverseStatus::InvalidInput);
  EXPECT_THROW(s.solve(Eigen::VectorXd::Ones(3)), Error);
  Eigen::SparseMatrix<double> A = grid_matrix(4);
  A.coeffRef(5, 5) = -3.0;
  EXPECT_EQ(s.compute(A), solve::SelectedInverseStatus::NotPositiveDefinite);
  EXPECT_THROW(s.block({0}), Error);
  A.coeffRef(5, 5) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(s.compute(A), solve::SelectedInverseStatus::InvalidInput);
  ASSERT_EQ(s.compute(grid_matrix(4)), solve::SelectedInverseStatus::Success);
  EXPECT_THROW(s.block({16}), Error);
  EXPECT_THROW(s.solve(Eigen::VectorXd::Ones(3)), Error);
}
