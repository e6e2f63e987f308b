#include "contactrb/solve/sparse_lu.hpp"

#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>
#include <cmath>
#include <string>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"

namespace contactrb::solve {

const char* to_string(SparseLUBackend backend) {
  switch (backend) {
    case SparseLUBackend::Umfpack: return "umfpack";
    case SparseLUBackend::EigenSparseLU: return "eigen";
  }
  return "unknown";
}

SparseLUBackend sparse_lu_backend_from_string(const std::string& name) {
  using enum SparseLUBackend;
  return enum_from_string(name, "sparse LU backend", std::array{Umfpack, EigenSparseLU});
}

const char* to_string(SparseLUStatus status) {
  switch (status) {
    case SparseLUStatus::Success: return "success";
    case SparseLUStatus::Singular: return "singular";
    case SparseLUStatus::InvalidInput: return "invalid_input";
  }
  return "unknown";
}

SparseLUStatus sparse_lu_status_from_string(const std::string& name) {
  using enum SparseLUStatus;
  return enum_from_string(name, "sparse LU status", std::array{Success, Singular, InvalidInput});
}

struct SparseLU::Impl {
  SparseLUBackend backend = SparseLUBackend::Umfpack;
  SparseLUStatus status = SparseLUStatus::InvalidInput;
  int rows = 0;
  std::unique_ptr<Eigen::UmfPackLU<Eigen::SparseMatrix<double>>> umfpack;
  std::unique_ptr<Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>> eigen;
};

SparseLU::SparseLU(SparseLUBackend backend) : impl_(std::make_unique<Impl>()) { impl_->backend = backend; }
SparseLU::~SparseLU() = default;
SparseLU::SparseLU(SparseLU&&) noexcept = default;
SparseLU& SparseLU::operator=(SparseLU&&) noexcept = default;

SparseLUStatus SparseLU::status() const { return impl_->status; }
SparseLUBackend SparseLU::backend() const { return impl_->backend; }

SparseLUStatus SparseLU::compute(const Eigen::SparseMatrix<double>& M) {
  Impl& m = *impl_;
  m.status = SparseLUStatus::InvalidInput;
  m.rows = 0;
  if (M.rows() != M.cols() || M.rows() == 0) return m.status;
  for (Eigen::Index k = 0; k < M.nonZeros(); ++k) {
    if (!std::isfinite(M.valuePtr()[k])) return m.status;
  }
  bool ok = false;
  if (m.backend == SparseLUBackend::Umfpack) {
    m.umfpack = std::make_unique<Eigen::UmfPackLU<Eigen::SparseMatrix<double>>>();
    m.umfpack->compute(M);
    ok = m.umfpack->info() == Eigen::Success;
  } else {
    m.eigen = std::make_unique<Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>>();
    m.eigen->compute(M);
    ok = m.eigen->info() == Eigen::Success;
  }
  m.status = ok ? SparseLUStatus::Success : SparseLUStatus::Singular;
  if (ok) m.rows = static_cast<int>(M.rows());
  return m.status;
}

Eigen::VectorXd SparseLU::solve(const Eigen::VectorXd& b) const {
  const Impl& m = *impl_;
  require(m.status == SparseLUStatus::Success,
          std::string("SparseLU::solve: no successful factorization (status ") + to_string(m.status) + ")");
  require(b.size() == m.rows, "SparseLU::solve: right-hand side of size " + std::to_string(b.size()) +
                                  " for a matrix of " + std::to_string(m.rows) + " rows");
  Eigen::VectorXd x = m.backend == SparseLUBackend::Umfpack ? Eigen::VectorXd(m.umfpack->solve(b))
                                                            : Eigen::VectorXd(m.eigen->solve(b));
  return x;
}

}  // namespace contactrb::solve
