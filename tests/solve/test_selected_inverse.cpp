// SelectedInverse: blocks of A^-1 by sparse substitutions agree with a dense inverse; the cache
// gives the same block whatever the order of the requests; statuses for bad input.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/solve/blas_threads.hpp"
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
// A 2-D elasticity-like matrix: 2 unknowns per node of an m x m grid (index 2 * node + c), each
// node coupled to its grid neighbours through a 2 x 2 block, so consecutive pairs of columns
// share their pattern (the supervariables of FactorOrdering::NodeMetis); then the rows and
// columns of `dropped` removed (nodes with one prescribed component: unpaired columns).
Eigen::SparseMatrix<double> vector_grid_matrix(int m, const std::vector<int>& dropped = {}) {
  std::vector<Eigen::Triplet<double>> t;
  auto id = [m](int i, int j) { return i * m + j; };
  auto couple = [&](int a, int b, double w) {  // w [2 -1; -1 2]-like coupling of nodes a, b
    for (int c = 0; c < 2; ++c) {
      for (int d = 0; d < 2; ++d) {
        const double v = (c == d ? -1.0 : 0.3) * w;
        t.emplace_back(2 * a + c, 2 * b + d, v);
        t.emplace_back(2 * b + d, 2 * a + c, v);
      }
    }
  };
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      const int a = id(i, j);
      t.emplace_back(2 * a, 2 * a, 9.0 + 0.01 * i);
      t.emplace_back(2 * a + 1, 2 * a + 1, 9.0 + 0.02 * j);
      t.emplace_back(2 * a, 2 * a + 1, 0.5);
      t.emplace_back(2 * a + 1, 2 * a, 0.5);
      if (i + 1 < m) couple(a, id(i + 1, j), 1.0);
      if (j + 1 < m) couple(a, id(i, j + 1), 1.0 + 0.001 * i);
    }
  }
  const int n = 2 * m * m;
  Eigen::SparseMatrix<double> full(n, n);
  full.setFromTriplets(t.begin(), t.end());
  std::vector<int> keep_index(static_cast<std::size_t>(n), 0);
  for (int d : dropped) keep_index[static_cast<std::size_t>(d)] = -1;
  int kept = 0;
  for (int k = 0; k < n; ++k) {
    if (keep_index[static_cast<std::size_t>(k)] == 0) keep_index[static_cast<std::size_t>(k)] = kept++;
  }
  std::vector<Eigen::Triplet<double>> r;
  for (int j = 0; j < n; ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(full, j); it; ++it) {
      const int a = keep_index[static_cast<std::size_t>(it.row())], b = keep_index[static_cast<std::size_t>(j)];
      if (a >= 0 && b >= 0) r.emplace_back(a, b, it.value());
    }
  }
  Eigen::SparseMatrix<double> A(kept, kept);
  A.setFromTriplets(r.begin(), r.end());
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

// METIS on the supervariable graph (the node pairs; unpaired columns where a component was
// dropped) is a valid ordering: blocks and solves equal the dense inverse's, and CHOLMOD's
// default ordering's to round-off; Auto picks it from kNodeMetisFrom rows on.
TEST(SelectedInverse, NodeMetisOrderingMatchesTheDenseInverseAndTheDefault) {
  const Eigen::SparseMatrix<double> A = vector_grid_matrix(14, {0, 5, 101, 230, 391});
  const Eigen::MatrixXd inv = Eigen::MatrixXd(A).inverse();
  solve::SelectedInverse metis, amd;
  ASSERT_EQ(metis.compute(A, solve::FactorOrdering::NodeMetis), solve::SelectedInverseStatus::Success);
  ASSERT_EQ(amd.compute(A, solve::FactorOrdering::Cholmod), solve::SelectedInverseStatus::Success);
  EXPECT_EQ(metis.ordering(), solve::FactorOrdering::NodeMetis);
  EXPECT_EQ(amd.ordering(), solve::FactorOrdering::Cholmod);
  const std::vector<int> idx = {0, 1, 2, 77, 200, 201, 386, static_cast<int>(A.rows()) - 1};
  const Eigen::MatrixXd G = metis.block(idx), H = amd.block(idx);
  for (std::size_t a = 0; a < idx.size(); ++a) {
    for (std::size_t b = 0; b < idx.size(); ++b) {
      const auto ea = static_cast<Eigen::Index>(a), eb = static_cast<Eigen::Index>(b);
      EXPECT_NEAR(G(ea, eb), inv(idx[a], idx[b]), 1e-14) << idx[a] << ", " << idx[b];
      EXPECT_NEAR(G(ea, eb), H(ea, eb), 1e-14) << idx[a] << ", " << idx[b];
    }
  }
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  EXPECT_LT((metis.solve(b) - inv * b).norm(), 1e-13 * (inv * b).norm());
  EXPECT_LT((metis.solve(b) - amd.solve(b)).norm(), 1e-13 * amd.solve(b).norm());
  const std::vector<int> in = {3, 200}, out = {1, 200, 300};
  const Eigen::VectorXd x = metis.solve_sparse(in, Eigen::Vector2d(1.0, -2.0), &out);
  for (int o : out) EXPECT_NEAR(x(o), inv(o, 3) - 2.0 * inv(o, 200), 1e-14) << o;
  // Auto: CHOLMOD's default below kNodeMetisFrom rows, NodeMetis from there on.
  solve::SelectedInverse small;
  ASSERT_EQ(small.compute(A), solve::SelectedInverseStatus::Success);
  EXPECT_EQ(small.ordering(), solve::FactorOrdering::Cholmod);
  EXPECT_EQ(solve::auto_ordering(solve::kNodeMetisFrom - 1), solve::FactorOrdering::Cholmod);
  EXPECT_EQ(solve::auto_ordering(solve::kNodeMetisFrom), solve::FactorOrdering::NodeMetis);
  // A larger one (20 402 rows: METIS's separators, not a few leaves) solves to round-off.
  solve::SelectedInverse large;
  const Eigen::SparseMatrix<double> B = vector_grid_matrix(101);
  ASSERT_EQ(large.compute(B, solve::FactorOrdering::NodeMetis), solve::SelectedInverseStatus::Success);
  EXPECT_EQ(large.ordering(), solve::FactorOrdering::NodeMetis);
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(B.rows(), 1.0, -3.0);
  EXPECT_LT((B * large.solve(c) - c).norm(), 1e-12 * c.norm());
}

// OpenBLAS threads (the Newton solver's blas_threads) change the order of the BLAS-3 sums only:
// the factorization with 2 threads gives the single-thread solution and inverse block to 1e-12,
// and the scope restores the previous count.
TEST(SelectedInverse, ThreadedFactorizationGivesTheSingleThreadAnswer) {
  if (!solve::blas_threads_settable()) GTEST_SKIP() << "the BLAS is not OpenBLAS: its threads cannot be set";
  const Eigen::SparseMatrix<double> A = vector_grid_matrix(90);  // 16 200 rows: top separators ~180 wide
  const int before = solve::blas_threads();
  solve::SelectedInverse one, two;
  std::vector<int> idx;
  for (int k = 0; k < 400; ++k) idx.push_back((k * 7919) % static_cast<int>(A.rows()));
  std::sort(idx.begin(), idx.end());
  idx.erase(std::unique(idx.begin(), idx.end()), idx.end());
  Eigen::MatrixXd G1, G2;
  {
    const solve::ScopedBlasThreads threads(1);
    EXPECT_EQ(solve::blas_threads(), 1);
    ASSERT_EQ(one.compute(A, solve::FactorOrdering::NodeMetis), solve::SelectedInverseStatus::Success);
    G1 = one.block(idx);
  }
  EXPECT_EQ(solve::blas_threads(), before);
  {
    const solve::ScopedBlasThreads threads(2);
    EXPECT_EQ(solve::blas_threads(), 2);
    ASSERT_EQ(two.compute(A, solve::FactorOrdering::NodeMetis), solve::SelectedInverseStatus::Success);
    G2 = two.block(idx);
  }
  EXPECT_EQ(solve::blas_threads(), before);
  EXPECT_LT((G1 - G2).cwiseAbs().maxCoeff(), 1e-12 * G1.cwiseAbs().maxCoeff());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd x1 = one.solve(b), x2 = two.solve(b);
  EXPECT_LT((x1 - x2).norm(), 1e-12 * x1.norm());
  EXPECT_LT((A * x1 - b).norm(), 1e-12 * b.norm());
}

// The full backward substitution on two threads (the two subtrees below the first fork of the
// elimination tree at once) does each supernode's arithmetic as the serial one: bitwise the
// same x, and A x = b.
TEST(SelectedInverse, TwoThreadSubstitutionIsBitwiseTheSerialOne) {
  const Eigen::SparseMatrix<double> A = vector_grid_matrix(40);
  const Eigen::MatrixXd dense = Eigen::MatrixXd(A);
  const solve::ScopedBlasThreads serial(1);
  for (const solve::FactorOrdering ordering : {solve::FactorOrdering::Cholmod, solve::FactorOrdering::NodeMetis}) {
    solve::SelectedInverse s;
    ASSERT_EQ(s.compute(A, ordering), solve::SelectedInverseStatus::Success);
    ASSERT_TRUE(s.has_substitution_fork()) << solve::to_string(ordering);
    const std::vector<int> in{3, 700, 1501, 2222, 3199};
    const Eigen::VectorXd b_in = (Eigen::VectorXd(5) << 1.0, -2.0, 0.5, 3.0, -1.5).finished();
    const Eigen::VectorXd x1 = s.solve_sparse(in, b_in);
    s.set_substitution_threads(2);
    const Eigen::VectorXd x2 = s.solve_sparse(in, b_in);
    s.set_substitution_threads(1);
    EXPECT_TRUE((x1.array() == x2.array()).all()) << solve::to_string(ordering);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(A.rows());
    for (std::size_t a = 0; a < in.size(); ++a) b(in[a]) = b_in(static_cast<Eigen::Index>(a));
    EXPECT_LT((dense * x2 - b).norm(), 1e-12 * b.norm()) << solve::to_string(ordering);
  }
}

// The symbolic counts of a FactorAnalysis: a tridiagonal matrix (a path graph, eliminated leaf
// first without fill) has nnz(L) = 2n - 1 and sum_j |L_j|^2 = 4(n - 1) + 1 flops (CHOLMOD's fl);
// on a grid with fill, nnz(L) lies between nnz(tril(A)) and the supernodal factor's count
// (which stores the zeros inside its supernodes).
TEST(SelectedInverse, AnalysisCountsTheFactorBeforeTheNumericWork) {
  const int n = 200;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> T(n, n);
  T.setFromTriplets(t.begin(), t.end());
  const solve::FactorAnalysis path = solve::FactorAnalysis::analyze(T, solve::FactorOrdering::Cholmod);
  ASSERT_TRUE(path.valid());
  EXPECT_EQ(path.factor_nonzeros(), 2.0 * n - 1.0);
  EXPECT_EQ(path.factor_flops(), 4.0 * (n - 1) + 1.0);

  const Eigen::SparseMatrix<double> A = vector_grid_matrix(30);
  for (const solve::FactorOrdering ordering : {solve::FactorOrdering::Cholmod, solve::FactorOrdering::NodeMetis}) {
    const solve::FactorAnalysis analysis = solve::FactorAnalysis::analyze(A, ordering);
    ASSERT_TRUE(analysis.valid());
    solve::SelectedInverse inv;
    ASSERT_EQ(inv.compute(A, analysis), solve::SelectedInverseStatus::Success);
    const double lower = static_cast<double>((A.nonZeros() + A.rows()) / 2);
    EXPECT_GT(analysis.factor_nonzeros(), lower) << solve::to_string(ordering);
    EXPECT_LE(analysis.factor_nonzeros(), static_cast<double>(inv.factor_nonzeros())) << solve::to_string(ordering);
    EXPECT_GT(analysis.factor_flops(), analysis.factor_nonzeros()) << solve::to_string(ordering);
  }
  EXPECT_EQ(solve::FactorAnalysis::analyze(Eigen::SparseMatrix<double>(3, 4)).factor_nonzeros(), 0.0);
}

// A FactorAnalysis of the pattern alone (zero values), made on another thread, gives the same
// factor as compute(A, ordering): bitwise the same solves and blocks, for both orderings; a
// matrix with another pattern falls back to its own analysis (still the right inverse).
TEST(SelectedInverse, AnalysisOfThePatternOnAnotherThreadGivesTheSameFactorBitwise) {
  const Eigen::SparseMatrix<double> A = vector_grid_matrix(30, {1, 62, 63, 500, 1201});
  Eigen::SparseMatrix<double> pattern = A;
  std::fill(pattern.valuePtr(), pattern.valuePtr() + pattern.nonZeros(), 0.0);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const std::vector<int> idx{0, 7, 99, 400, 1000, static_cast<int>(A.rows()) - 1};
  for (const solve::FactorOrdering ordering : {solve::FactorOrdering::Cholmod, solve::FactorOrdering::NodeMetis}) {
    auto future = std::async(std::launch::async, [&] { return solve::FactorAnalysis::analyze(pattern, ordering); });
    const solve::FactorAnalysis analysis = future.get();
    ASSERT_TRUE(analysis.valid());
    EXPECT_TRUE(analysis.matches(A));
    EXPECT_EQ(analysis.requested(), ordering);
    solve::SelectedInverse serial, given;
    ASSERT_EQ(serial.compute(A, ordering), solve::SelectedInverseStatus::Success);
    ASSERT_EQ(given.compute(A, analysis), solve::SelectedInverseStatus::Success);
    EXPECT_TRUE(given.used_analysis());
    EXPECT_FALSE(serial.used_analysis());
    EXPECT_EQ(given.ordering(), ordering);
    EXPECT_EQ(given.factor_nonzeros(), serial.factor_nonzeros());
    const Eigen::VectorXd x1 = serial.solve(b), x2 = given.solve(b);
    EXPECT_TRUE((x1.array() == x2.array()).all()) << solve::to_string(ordering);
    const Eigen::MatrixXd g1 = serial.block(idx), g2 = given.block(idx);
    EXPECT_TRUE((g1.array() == g2.array()).all()) << solve::to_string(ordering);
    // The analysis serves a second compute (it is copied, not consumed).
    solve::SelectedInverse again;
    ASSERT_EQ(again.compute(A, analysis), solve::SelectedInverseStatus::Success);
    EXPECT_TRUE(again.used_analysis());
    EXPECT_TRUE((again.solve(b).array() == x1.array()).all());
    // Another pattern: not matched, analysed on its own, the right solution.
    const Eigen::SparseMatrix<double> other = vector_grid_matrix(30, {1, 62, 63, 500});
    EXPECT_FALSE(analysis.matches(other));
    solve::SelectedInverse fallback;
    ASSERT_EQ(fallback.compute(other, analysis), solve::SelectedInverseStatus::Success);
    EXPECT_FALSE(fallback.used_analysis());
    const Eigen::VectorXd bo = Eigen::VectorXd::Ones(other.rows());
    EXPECT_LT((other * fallback.solve(bo) - bo).norm(), 1e-12 * bo.norm());
  }
  EXPECT_FALSE(solve::FactorAnalysis::analyze(Eigen::SparseMatrix<double>(3, 4)).valid());
}

// row_block: (V A^-1 V')[rows, rows] for sparse rows of V (several entries each, spread over the
// grid so that their chains part and join) equals the dense V A^-1 V'; asked again with cached
// and new rows, then after forget_rows() with V changed, it stays exact; block() is untouched.
TEST(SelectedInverse, RowBlocksMatchTheDenseProduct) {
  const Eigen::SparseMatrix<double> A = grid_matrix(32);
  const int n = static_cast<int>(A.rows());
  const Eigen::MatrixXd inv = Eigen::MatrixXd(A).llt().solve(Eigen::MatrixXd::Identity(n, n));
  auto rows_matrix = [n](double shift) {
    std::vector<Eigen::Triplet<double>> t;
    for (int r = 0; r < 40; ++r) {
      t.emplace_back(r, (r * 37) % n, 1.0 + shift);
      t.emplace_back(r, (r * 53 + 11) % n, -0.5 * r);
      t.emplace_back(r, (r * 101 + 500) % n, 0.25 + shift * r);
    }
    Eigen::SparseMatrix<double, Eigen::RowMajor> V(40, n);
    V.setFromTriplets(t.begin(), t.end());
    return V;
  };
  solve::SelectedInverse s;
  ASSERT_EQ(s.compute(A), solve::SelectedInverseStatus::Success);
  const std::vector<int> unit_idx = {3, 500, 1000};
  const Eigen::MatrixXd G_before = s.block(unit_idx);
  auto worst_error = [&](const Eigen::SparseMatrix<double, Eigen::RowMajor>& V, const std::vector<int>& rows) {
    std::vector<double> storage;
    const Eigen::MatrixXd Q = s.row_block(rows, V, storage);
    const Eigen::MatrixXd dense = Eigen::MatrixXd(V) * inv * Eigen::MatrixXd(V).transpose();
    double worst = 0.0;
    for (std::size_t a = 0; a < rows.size(); ++a) {
      for (std::size_t b = 0; b < rows.size(); ++b) {
        worst = std::max(worst, std::abs(Q(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) -
                                         dense(rows[a], rows[b])));
      }
    }
    return worst / dense.cwiseAbs().maxCoeff();
  };
  const auto V1 = rows_matrix(0.0), V2 = rows_matrix(0.3);
  EXPECT_LT(worst_error(V1, {0, 5, 7, 12, 30, 39}), 1e-14);
  EXPECT_LT(worst_error(V1, {39, 1, 5, 20, 21}), 1e-14);  // 39 and 5 cached
  s.forget_rows();
  EXPECT_LT(worst_error(V2, {0, 5, 7, 12, 30, 39}), 1e-14);
  EXPECT_EQ(s.cached_columns(), 3);
  EXPECT_EQ(Eigen::MatrixXd(s.block(unit_idx)), G_before);
  std::vector<double> storage;
  EXPECT_THROW(s.row_block({40}, V1, storage), Error);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> wrong(2, n + 1);
  EXPECT_THROW(s.row_block({0}, wrong, storage), Error);
}
