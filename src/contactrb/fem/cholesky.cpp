#include "contactrb/fem/cholesky.hpp"

#include <Eigen/SparseCholesky>
#include <cmath>
#include <string>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"

#if __has_include(<cholmod.h>)
#include <Eigen/CholmodSupport>
#define CONTACTRB_HAVE_CHOLMOD 1
#else
#define CONTACTRB_HAVE_CHOLMOD 0
#endif

namespace contactrb::fem {
namespace {

using Matrix = Eigen::SparseMatrix<double>;
using EigenLLT = Eigen::SimplicialLLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>>;
#if CONTACTRB_HAVE_CHOLMOD
using CholmodLLT = Eigen::CholmodSupernodalLLT<Matrix, Eigen::Lower>;
#endif

// Chosen by bench/bench_fem.cpp (docs/performance.md, "Sparse Cholesky backend"): Eigen's simplicial LL' is fastest up
// to about 1e4 DOFs; CHOLMOD's supernodal LL' (METIS ordering, BLAS-3 on OpenBLAS) is about
// 3 times faster at 1e5 DOFs.
constexpr CholeskyBackend kDefaultBackend = CholeskyBackend::Automatic;

// InvalidInput unless A is square with finite entries and symmetric to a relative tolerance.
bool valid_symmetric(const Matrix& A) {
  if (A.rows() != A.cols()) return false;
  double largest = 0.0;
  for (int j = 0; j < A.outerSize(); ++j) {
    for (Matrix::InnerIterator it(A, j); it; ++it) {
      if (!std::isfinite(it.value())) return false;
      largest = std::max(largest, std::abs(it.value()));
    }
  }
  const Matrix T = A.transpose();
  const double tolerance = SparseCholesky::kSymmetryTolerance * largest;
  // Both are compressed column-major; walk the columns of A and A' together.
  for (int j = 0; j < A.outerSize(); ++j) {
    Matrix::InnerIterator a(A, j), t(T, j);
    while (a || t) {
      if (a && t && a.row() == t.row()) {
        if (std::abs(a.value() - t.value()) > tolerance) return false;
        ++a;
        ++t;
      } else if (a && (!t || a.row() < t.row())) {
        if (std::abs(a.value()) > tolerance) return false;
        ++a;
      } else {
        if (std::abs(t.value()) > tolerance) return false;
        ++t;
      }
    }
  }
  return true;
}

}  // namespace

struct SparseCholesky::Impl {
  CholeskyBackend backend = kDefaultBackend;
  CholeskyBackend used = CholeskyBackend::EigenSimplicial;  // resolved by compute()
  FactorStatus status = FactorStatus::InvalidInput;
  int rows = 0;
  bool computed = false;
  std::unique_ptr<EigenLLT> eigen;
#if CONTACTRB_HAVE_CHOLMOD
  std::unique_ptr<CholmodLLT> cholmod;
#endif
};

const char* to_string(FactorStatus status) {
  switch (status) {
    case FactorStatus::Success:
      return "success";
    case FactorStatus::NotPositiveDefinite:
      return "not positive definite";
    case FactorStatus::InvalidInput:
      return "invalid input";
  }
  return "unknown";
}

FactorStatus factor_status_from_string(const std::string& name) {
  using enum FactorStatus;
  return enum_from_string(name, "factorization status", std::array{Success, NotPositiveDefinite, InvalidInput});
}

const char* to_string(CholeskyBackend backend) {
  switch (backend) {
    case CholeskyBackend::Automatic:
      return "automatic";
    case CholeskyBackend::Cholmod:
      return "cholmod";
    case CholeskyBackend::EigenSimplicial:
      return "eigen-simplicial";
  }
  return "unknown";
}

CholeskyBackend cholesky_backend_from_string(const std::string& name) {
  using enum CholeskyBackend;
  return enum_from_string(name, "Cholesky backend", std::array{Automatic, Cholmod, EigenSimplicial});
}

SparseCholesky::SparseCholesky() : SparseCholesky(kDefaultBackend) {}

SparseCholesky::SparseCholesky(CholeskyBackend backend) : impl_(std::make_unique<Impl>()) {
  require(backend != CholeskyBackend::Cholmod || CONTACTRB_HAVE_CHOLMOD,
          "SparseCholesky: this build has no CHOLMOD backend");
  impl_->backend = backend;
}

SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

FactorStatus SparseCholesky::compute(const Eigen::SparseMatrix<double>& A) {
  if (!impl_) impl_ = std::make_unique<Impl>();  // moved-from object
  Impl& s = *impl_;
  s.computed = true;
  s.rows = static_cast<int>(A.rows());
  if (!valid_symmetric(A)) return s.status = FactorStatus::InvalidInput;
  if (A.rows() == 0) return s.status = FactorStatus::Success;
  s.used = s.backend;
  if (s.used == CholeskyBackend::Automatic) {
    s.used = (CONTACTRB_HAVE_CHOLMOD && A.rows() >= kCholmodMinRows) ? CholeskyBackend::Cholmod
                                                                      : CholeskyBackend::EigenSimplicial;
  }
  if (s.used == CholeskyBackend::EigenSimplicial) {
    if (!s.eigen) s.eigen = std::make_unique<EigenLLT>();
    s.eigen->compute(A);
    s.status = s.eigen->info() == Eigen::Success ? FactorStatus::Success : FactorStatus::NotPositiveDefinite;
    return s.status;
  }
#if CONTACTRB_HAVE_CHOLMOD
  if (!s.cholmod) {
    s.cholmod = std::make_unique<CholmodLLT>();
    s.cholmod->cholmod().print = 0;  // statuses are returned, not printed
  }
  s.cholmod->compute(A);
  if (s.cholmod->cholmod().status < 0) {
    s.status = FactorStatus::InvalidInput;  // CHOLMOD error (out of memory, too large)
  } else {
    s.status = s.cholmod->info() == Eigen::Success ? FactorStatus::Success : FactorStatus::NotPositiveDefinite;
  }
  return s.status;
#else
  return s.status = FactorStatus::InvalidInput;
#endif
}

CholeskyBackend SparseCholesky::backend() const { return impl_ ? impl_->backend : kDefaultBackend; }
FactorStatus SparseCholesky::status() const { return impl_ ? impl_->status : FactorStatus::InvalidInput; }
int SparseCholesky::rows() const { return impl_ ? impl_->rows : 0; }

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) const {
  const Eigen::MatrixXd x = solve(Eigen::MatrixXd(b));
  return x.col(0);
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  require(impl_ && impl_->computed, "SparseCholesky::solve: compute() was not called");
  require(impl_->status == FactorStatus::Success,
          std::string("SparseCholesky::solve: factorization status is '") + to_string(impl_->status) + "'");
  require(B.rows() == impl_->rows, "SparseCholesky::solve: right-hand side has " + std::to_string(B.rows()) +
                                       " rows, matrix has " + std::to_string(impl_->rows));
  if (B.rows() == 0 || B.cols() == 0) return Eigen::MatrixXd(B.rows(), B.cols());
  if (impl_->used == CholeskyBackend::EigenSimplicial) return impl_->eigen->solve(B);
#if CONTACTRB_HAVE_CHOLMOD
  return impl_->cholmod->solve(B);
#else
  return Eigen::MatrixXd();
#endif
}

}  // namespace contactrb::fem
