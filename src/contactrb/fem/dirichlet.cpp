#include "contactrb/fem/dirichlet.hpp"

#include <sstream>

#include "contactrb/common/error.hpp"

namespace contactrb::fem {
namespace {

std::string dof_name(int dof, int dim) {
  std::ostringstream s;
  s << "DOF " << dof << " (node " << dof / dim << ", " << "xyz"[dof % dim] << ")";
  return s.str();
}

void check_size(Eigen::Index actual, int expected, const char* who, const char* what) {
  require(actual == expected, std::string("DofMap::") + who + ": " + what + " has " + std::to_string(actual) +
                                  " entries, expected " + std::to_string(expected));
}

}  // namespace

template <int Dim>
DofMap::DofMap(const mesh::SimplexMesh<Dim>& mesh, const std::vector<DirichletCondition>& conditions)
    : num_dofs_(mesh.num_dofs()), dim_(Dim) {
  const auto n = static_cast<std::size_t>(num_dofs_);
  std::vector<int> source(n, -1);  // condition that prescribed each DOF
  lift_ = Eigen::VectorXd::Zero(num_dofs_);
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    const DirichletCondition& condition = conditions[k];
    if (!mesh.has_boundary(condition.group)) {
      std::string present;
      for (const auto& [name, edges] : mesh.boundaries) present += (present.empty() ? "" : ", ") + name;
      throw Error("DofMap: Dirichlet group '" + condition.group + "' is not a boundary group of the mesh (groups: " +
                  (present.empty() ? std::string("none") : present) + ")");
    }
    require(Dim == 3 || !condition.uz, "DofMap: group '" + condition.group + "' prescribes uz on a 2D mesh");
    const std::optional<double> value[3] = {condition.ux, condition.uy, condition.uz};
    for (int node : mesh::boundary_nodes(mesh, condition.group)) {
      for (int c = 0; c < Dim; ++c) {
        if (!value[c]) continue;
        const int dof = Dim * node + c;
        if (dof < 0 || dof >= num_dofs_) {
          throw Error("DofMap: group '" + condition.group + "' has node " + std::to_string(node) +
                      " out of range (mesh has " + std::to_string(num_dofs_ / Dim) + " nodes)");
        }
        int& prev = source[static_cast<std::size_t>(dof)];
        if (prev >= 0 && lift_(dof) != *value[c]) {
          std::ostringstream s;
          s.precision(17);
          s << "DofMap: " << dof_name(dof, Dim) << " prescribed twice with different values: " << lift_(dof)
            << " by group '" << conditions[static_cast<std::size_t>(prev)].group << "' and " << *value[c]
            << " by group '" << condition.group << "'";
          throw Error(s.str());
        }
        prev = static_cast<int>(k);
        lift_(dof) = *value[c];
      }
    }
  }
  free_index_.assign(n, -1);
  for (int dof = 0; dof < num_dofs_; ++dof) {
    if (source[static_cast<std::size_t>(dof)] >= 0) {
      constrained_.push_back(dof);
    } else {
      free_index_[static_cast<std::size_t>(dof)] = static_cast<int>(free_.size());
      free_.push_back(dof);
    }
  }
}

template DofMap::DofMap(const mesh::Mesh&, const std::vector<DirichletCondition>&);
template DofMap::DofMap(const mesh::Mesh3&, const std::vector<DirichletCondition>&);

int DofMap::num_dofs() const { return num_dofs_; }
int DofMap::num_free() const { return static_cast<int>(free_.size()); }
const std::vector<int>& DofMap::free_dofs() const { return free_; }
const std::vector<int>& DofMap::constrained_dofs() const { return constrained_; }
const Eigen::VectorXd& DofMap::lift() const { return lift_; }

Eigen::VectorXd DofMap::restrict(const Eigen::VectorXd& global) const {
  check_size(global.size(), num_dofs_, "restrict", "global vector");
  Eigen::VectorXd r(num_free());
  for (int k = 0; k < num_free(); ++k) r(k) = global(free_[static_cast<std::size_t>(k)]);
  return r;
}

Eigen::VectorXd DofMap::extend(const Eigen::VectorXd& free) const {
  check_size(free.size(), num_free(), "extend", "free vector");
  Eigen::VectorXd g = Eigen::VectorXd::Zero(num_dofs_);
  for (int k = 0; k < num_free(); ++k) g(free_[static_cast<std::size_t>(k)]) = free(k);
  return g;
}

SparseMatrix DofMap::restrict_matrix(const SparseMatrix& A) const {
  require(A.rows() == num_dofs_ && A.cols() == num_dofs_,
          "DofMap::restrict_matrix: matrix is " + std::to_string(A.rows()) + " x " + std::to_string(A.cols()) +
              ", expected " + std::to_string(num_dofs_) + " x " + std::to_string(num_dofs_));
  // Count, then fill the compressed columns directly (free DOFs keep their order).
  SparseMatrix R(num_free(), num_free());
  Eigen::Index nnz = 0;
  for (int dof : free_) {
    for (SparseMatrix::InnerIterator it(A, dof); it; ++it) nnz += free_index_[static_cast<std::size_t>(it.row())] >= 0;
  }
  R.resizeNonZeros(nnz);
  int pos = 0;
  R.outerIndexPtr()[0] = 0;
  for (int k = 0; k < num_free(); ++k) {
    for (SparseMatrix::InnerIterator it(A, free_[static_cast<std::size_t>(k)]); it; ++it) {
      const int row = free_index_[static_cast<std::size_t>(it.row())];
      if (row < 0) continue;
      R.innerIndexPtr()[pos] = row;
      R.valuePtr()[pos] = it.value();
      ++pos;
    }
    R.outerIndexPtr()[k + 1] = pos;
  }
  return R;
}

Eigen::VectorXd DofMap::restrict_rhs(const SparseMatrix& A, const Eigen::VectorXd& f) const {
  require(A.rows() == num_dofs_ && A.cols() == num_dofs_,
          "DofMap::restrict_rhs: matrix is " + std::to_string(A.rows()) + " x " + std::to_string(A.cols()) +
              ", expected " + std::to_string(num_dofs_) + " x " + std::to_string(num_dofs_));
  check_size(f.size(), num_dofs_, "restrict_rhs", "load vector");
  return restrict(f - A * lift_);
}

Eigen::SparseMatrix<double, Eigen::RowMajor> DofMap::restrict_columns(
    const Eigen::SparseMatrix<double, Eigen::RowMajor>& K) const {
  require(K.cols() == num_dofs_, "DofMap::restrict_columns: matrix has " + std::to_string(K.cols()) +
                                     " columns, expected " + std::to_string(num_dofs_));
  using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  RowMatrix R(K.rows(), num_free());
  Eigen::Index nnz = 0;
  for (int r = 0; r < K.outerSize(); ++r) {
    for (RowMatrix::InnerIterator it(K, r); it; ++it) nnz += free_index_[static_cast<std::size_t>(it.col())] >= 0;
  }
  R.resizeNonZeros(nnz);
  int pos = 0;
  R.outerIndexPtr()[0] = 0;
  for (int r = 0; r < K.outerSize(); ++r) {
    for (RowMatrix::InnerIterator it(K, r); it; ++it) {
      const int col = free_index_[static_cast<std::size_t>(it.col())];
      if (col < 0) continue;
      R.innerIndexPtr()[pos] = col;
      R.valuePtr()[pos] = it.value();
      ++pos;
    }
    R.outerIndexPtr()[r + 1] = pos;
  }
  return R;
}

}  // namespace contactrb::fem
