#pragma once
// Sparse Cholesky factorization computed once and reused for many right-hand sides
// (A(mu) is factorized once per mu; each Kacanov iteration only back-solves).
// The backend is chosen by measurement (docs/performance.md, "Why the defaults are what they are", "Sparse Cholesky backend").
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

namespace contactrb::fem {

enum class FactorStatus { Success, NotPositiveDefinite, InvalidInput };
const char* to_string(FactorStatus status);
FactorStatus factor_status_from_string(const std::string& name);  // throws contactrb::Error

// EigenSimplicial: Eigen::SimplicialLLT with AMD ordering; faster below about 2e4 DOFs
// (docs/performance.md, "FEM assembly and factorization").
// Cholmod: CHOLMOD supernodal LL' (SuiteSparse, through Eigen's CholmodSupport, default
// CHOLMOD ordering strategy: AMD, then METIS when AMD fills badly); faster at 1e6 DOFs, and
// much faster with an optimized BLAS.
// Automatic: EigenSimplicial below kCholmodMinRows rows, Cholmod from there on
// (with an optimized BLAS, CHOLMOD's supernodal factorization wins from about 2e4 DOFs;
// Eigen's simplicial one wins below: docs/performance.md, "Why the defaults are what they are", "Sparse Cholesky backend").
enum class CholeskyBackend { Automatic, Cholmod, EigenSimplicial };
inline constexpr int kCholmodMinRows = 20000;
const char* to_string(CholeskyBackend backend);
CholeskyBackend cholesky_backend_from_string(const std::string& name);  // throws contactrb::Error

class SparseCholesky {
 public:
  SparseCholesky();  // default backend (Automatic)
  explicit SparseCholesky(CholeskyBackend backend);
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  // Symbolic analysis and numeric factorization of a symmetric matrix (both triangles
  // stored). Returns the status; solve() requires Success. InvalidInput: not square,
  // not symmetric (relative tolerance kSymmetryTolerance), non-finite entries, or a
  // backend error (e.g. out of memory). NotPositiveDefinite: a pivot <= 0.
  FactorStatus compute(const Eigen::SparseMatrix<double>& A);
  static constexpr double kSymmetryTolerance = 1e-12;
  CholeskyBackend backend() const;
  FactorStatus status() const;
  int rows() const;
  // Throw contactrb::Error unless status() == Success and the sizes match.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  // Any dense expression (A * x, f - K * u, ...): evaluated, then solved as a vector when it
  // has one column at compile time, as a matrix otherwise.
  template <class Derived>
  auto solve(const Eigen::MatrixBase<Derived>& b) const {
    if constexpr (Derived::ColsAtCompileTime == 1) {
      return solve(Eigen::VectorXd(b));
    } else {
      return solve(Eigen::MatrixXd(b));
    }
  }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace contactrb::fem
