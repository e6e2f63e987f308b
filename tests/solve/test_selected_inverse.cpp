// SelectedInverse: blocks of A^-1 by sparse substitutions agree with a dense inverse; the cache
// gives the same block whatever the order of the requests; statuses for bad input.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
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
