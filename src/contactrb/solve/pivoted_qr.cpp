#include "contactrb/solve/pivoted_qr.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/solve/blas_threads.hpp"

// LAPACK, Fortran calling convention (column-major, every argument by pointer).
extern "C" {
void dgeqp3_(const int* m, const int* n, double* a, const int* lda, int* jpvt, double* tau, double* work,
             const int* lwork, int* info);
}

namespace contactrb::solve {

PivotedQR pivoted_qr(Eigen::MatrixXd A, double threshold) {
  require(A.allFinite(), "pivoted_qr: the matrix has non-finite entries");
  const Eigen::Index m_ = A.rows(), n_ = A.cols();
  require(m_ < std::numeric_limits<int>::max() && n_ < std::numeric_limits<int>::max(),
          "pivoted_qr: the matrix is too large for LAPACK");
  const int m = static_cast<int>(m_), n = static_cast<int>(n_), lda = std::max(1, m);
  const int k = std::min(m, n);
  PivotedQR out;
  if (k == 0) {
    out.R = Eigen::MatrixXd::Zero(std::min<Eigen::Index>(1, m_), n_);
    for (Eigen::Index j = 0; j < n_; ++j) out.permutation.push_back(j);
    return out;
  }
  // One BLAS thread: the factor is then the same bit for bit whatever the process's thread count
  // (a serial run against MPI ranks; the greedy's files are compared byte for byte).
  const ScopedBlasThreads serial(1);
  std::vector<int> jpvt(static_cast<std::size_t>(n), 0);
  std::vector<double> tau(static_cast<std::size_t>(k));
  int info = 0, lwork = -1;
  double query = 0.0;
  dgeqp3_(&m, &n, A.data(), &lda, jpvt.data(), tau.data(), &query, &lwork, &info);
  require(info == 0, "pivoted_qr: dgeqp3 workspace query failed (info " + std::to_string(info) + ")");
  lwork = std::max(1, static_cast<int>(query));
  std::vector<double> work(static_cast<std::size_t>(lwork));
  dgeqp3_(&m, &n, A.data(), &lda, jpvt.data(), tau.data(), work.data(), &lwork, &info);
  require(info == 0, "pivoted_qr: dgeqp3 failed (info " + std::to_string(info) + ")");
  const double largest = std::abs(A(0, 0));
  Eigen::Index rank = 0;
  while (rank < k && std::abs(A(rank, rank)) > threshold * largest) ++rank;
  rank = std::max<Eigen::Index>(1, rank);
  out.R = A.topRows(rank).triangularView<Eigen::Upper>();
  out.permutation.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) out.permutation[static_cast<std::size_t>(j)] = jpvt[static_cast<std::size_t>(j)] - 1;
  return out;
}

}  // namespace contactrb::solve
