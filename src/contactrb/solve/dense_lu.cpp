#include "contactrb/solve/dense_lu.hpp"

#include <limits>
#include <string>

#include "contactrb/common/error.hpp"

// LAPACK, Fortran calling convention (column-major, every argument by pointer).
extern "C" {
void dgetrf_(const int* m, const int* n, double* a, const int* lda, int* ipiv, int* info);
void dgetrs_(const char* trans, const int* n, const int* nrhs, const double* a, const int* lda, const int* ipiv,
             double* b, const int* ldb, int* info);
void dgecon_(const char* norm, const int* n, const double* a, const int* lda, const double* anorm, double* rcond,
             double* work, int* iwork, int* info);
}

namespace contactrb::solve {

bool DenseLU::compute(Eigen::MatrixXd M) {
  ok_ = false;
  rcond_ = 0.0;
  lu_.resize(0, 0);
  if (M.rows() != M.cols() || !M.allFinite()) return false;
  if (M.rows() > std::numeric_limits<int>::max() / std::max<Eigen::Index>(1, M.rows())) return false;
  lu_ = std::move(M);
  const int n = static_cast<int>(lu_.rows());
  ok_ = true;
  if (n == 0) {
    rcond_ = 1.0;
    return true;
  }
  // 1-norm of M (max column sum) for dgecon, before dgetrf overwrites it.
  const double anorm = lu_.cwiseAbs().colwise().sum().maxCoeff();
  pivots_.assign(static_cast<std::size_t>(n), 0);
  int info = 0;
  dgetrf_(&n, &n, lu_.data(), &n, pivots_.data(), &info);
  if (info < 0) throw Error("DenseLU: dgetrf argument " + std::to_string(-info) + " invalid (internal)");
  if (info > 0) return true;  // U(info, info) == 0: exactly singular, rcond 0
  std::vector<double> work(4 * static_cast<std::size_t>(n));
  std::vector<int> iwork(static_cast<std::size_t>(n));
  const char norm = '1';
  dgecon_(&norm, &n, lu_.data(), &n, &anorm, &rcond_, work.data(), iwork.data(), &info);
  if (info != 0) rcond_ = 0.0;
  return true;
}

Eigen::VectorXd DenseLU::solve(const Eigen::VectorXd& b) const {
  require(ok_ && rcond_ > 0.0, "DenseLU::solve: no nonsingular factorization");
  require(b.size() == lu_.rows(), "DenseLU::solve: right-hand side has " + std::to_string(b.size()) +
                                      " entries for " + std::to_string(lu_.rows()) + " rows");
  Eigen::VectorXd x = b;
  const int n = static_cast<int>(lu_.rows());
  if (n == 0) return x;
  const int nrhs = 1;
  const char trans = 'N';
  int info = 0;
  dgetrs_(&trans, &n, &nrhs, lu_.data(), &n, pivots_.data(), x.data(), &n, &info);
  require(info == 0, "DenseLU::solve: dgetrs failed (info " + std::to_string(info) + ")");
  return x;
}

}  // namespace contactrb::solve
