#pragma once
// Sparse Cholesky factorization computed once and reused for many right-hand sides
// (A(mu) is factorized once per mu; each Kacanov iteration only back-solves).
// The backend is chosen by measurement (docs/benchmarks.md).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

namespace contactrb::fem {

enum class FactorStatus { Success, NotPositiveDefinite, InvalidInput };
const char* to_string(FactorStatus status);

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  // Symbolic analysis and numeric factorization of a symmetric matrix (both triangles
  // stored). Returns the status; solve() requires Success.
  FactorStatus compute(const Eigen::SparseMatrix<double>& A);
  FactorStatus status() const;
  int rows() const;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace contactrb::fem
