#pragma once
// Dirichlet lifting u = u_D + u_0 with u_0 in V_0 (DESIGN.md): constrained DOFs are
// eliminated; the free DOFs are numbered 0..num_free-1 in increasing global order.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/fem/elasticity.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::fem {

// Prescribed displacement on the nodes of a boundary group; a component left empty is free
// (uz: 3D meshes only).
struct DirichletCondition {
  std::string group;
  std::optional<double> ux;
  std::optional<double> uy;
  std::optional<double> uz = std::nullopt;  // an initializer: 2D call sites may omit it
};

class DofMap {
 public:
  DofMap() = default;
  // Throws contactrb::Error naming a missing group, a DOF prescribed twice with different
  // values, or uz given on a 2D mesh. Dim = 2, 3.
  template <int Dim>
  DofMap(const mesh::SimplexMesh<Dim>& mesh, const std::vector<DirichletCondition>& conditions);

  int num_dofs() const;
  int dim() const { return dim_; }  // of the mesh
  int num_free() const;
  const std::vector<int>& free_dofs() const;        // global index of each free DOF
  const std::vector<int>& constrained_dofs() const;  // sorted
  // Global vector with the prescribed values on constrained DOFs and 0 elsewhere (u_D).
  const Eigen::VectorXd& lift() const;

  Eigen::VectorXd restrict(const Eigen::VectorXd& global) const;  // free entries
  Eigen::VectorXd extend(const Eigen::VectorXd& free) const;      // zeros on constrained
  // A_00 (free x free) and A_0D applied to the lift: A_00 u_0 = f_0 - (A u_D)_0.
  SparseMatrix restrict_matrix(const SparseMatrix& A) const;
  // Right-hand side of the reduced system: restrict(f - A * lift()).
  Eigen::VectorXd restrict_rhs(const SparseMatrix& A, const Eigen::VectorXd& f) const;
  // Columns restricted to free DOFs (for K: R x num_dofs -> R x num_free).
  Eigen::SparseMatrix<double, Eigen::RowMajor> restrict_columns(
      const Eigen::SparseMatrix<double, Eigen::RowMajor>& K) const;

 private:
  int num_dofs_ = 0;
  int dim_ = 2;  // DOF d is component d % dim_ of node d / dim_
  std::vector<int> free_;
  std::vector<int> constrained_;
  std::vector<int> free_index_;  // global -> free index or -1
  Eigen::VectorXd lift_;
};

}  // namespace contactrb::fem
