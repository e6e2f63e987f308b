#pragma once
// Sparse LU factorization of a general square matrix, for the semi-smooth Newton systems
// (nonsymmetric saddle points [A + H, K_A'; -D_A, 0], docs/solvers.md). Like Eigen's
// solvers: compute() returns a status, solve() requires Success. Backends: UMFPACK (default)
// and Eigen's SparseLU (docs/solvers.md, "Newton linear algebra").
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

namespace contactrb::solve {

// Umfpack: UMFPACK (SuiteSparse, multifrontal, BLAS level 3, COLAMD/AMD ordering).
// EigenSparseLU: Eigen::SparseLU (supernodal, COLAMD ordering, no external BLAS).
enum class SparseLUBackend { Umfpack, EigenSparseLU };
const char* to_string(SparseLUBackend backend);
SparseLUBackend sparse_lu_backend_from_string(const std::string& name);  // "umfpack" | "eigen"

enum class SparseLUStatus { Success, Singular, InvalidInput };
const char* to_string(SparseLUStatus status);
SparseLUStatus sparse_lu_status_from_string(const std::string& name);  // throws contactrb::Error

class SparseLU {
 public:
  explicit SparseLU(SparseLUBackend backend = SparseLUBackend::Umfpack);
  ~SparseLU();
  SparseLU(SparseLU&&) noexcept;
  SparseLU& operator=(SparseLU&&) noexcept;

  // Ordering, symbolic and numeric factorization. InvalidInput: not square, empty, or a
  // non-finite entry. Singular: the backend found a zero pivot.
  SparseLUStatus compute(const Eigen::SparseMatrix<double>& M);
  SparseLUStatus status() const;
  SparseLUBackend backend() const;
  // Throws contactrb::Error unless status() == Success and b has the matrix's size.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace contactrb::solve
