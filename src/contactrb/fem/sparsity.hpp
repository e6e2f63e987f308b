#pragma once
// Sparsity pattern of the P1 vector matrices on a set of cells (triangles, tetrahedra), computed
// once in O(number of cells); element matrices are then added in place (no triplets).
// Column Dim*j + c holds rows Dim*i, ..., Dim*i + Dim - 1 for every node i adjacent to node j
// (including j), in increasing order, so the matrix is compressed column-major.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "contactrb/fem/p1_element.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::fem {

template <int Dim>
class SimplexSparsity {
 public:
  // Pattern of the cells listed in `cells` (indices into mesh.cells()).
  SimplexSparsity(const mesh::SimplexMesh<Dim>& mesh, const std::vector<int>& cells);

  int num_dofs() const { return Dim * num_nodes_; }
  Eigen::Index num_nonzeros() const { return Dim * Dim * static_cast<Eigen::Index>(neighbours_.size()); }
  // Zero values in pattern order, to accumulate into.
  std::vector<double> zero_values() const;
  // Adds an element matrix (local DOF Dim*i + c) of cell `cell` into `values`, an array of
  // num_nonzeros() entries in pattern order (a std::vector or a matrix's valuePtr()).
  void add(const std::array<int, Dim + 1>& cell, const SimplexElementMatrix<Dim>& element, double* values) const;
  void add(const std::array<int, Dim + 1>& cell, const SimplexElementMatrix<Dim>& element,
           std::vector<double>& values) const {
    add(cell, element, values.data());
  }
  // The compressed matrix with this pattern and zero values, to accumulate into in place.
  Eigen::SparseMatrix<double> zero_matrix() const;
  // The compressed matrix with this pattern and the given values (size num_nonzeros()).
  Eigen::SparseMatrix<double> matrix(const std::vector<double>& values) const;
  // The pattern restricted to the DOFs `kept` (global indices, each once), compressed by columns
  // (outer: kept.size() + 1 entries; inner: rows as positions in `kept`): what
  // DofMap::restrict_matrix(zero_matrix()) stores for kept = free_dofs(), without the values (the
  // pattern of A_00, analysed while the values are assembled: hf::HFSolver).
  void restricted_pattern(const std::vector<int>& kept, std::vector<int>& outer, std::vector<int>& inner) const;

 private:
  int num_nodes_ = 0;
  std::vector<int> start_;       // node j -> first neighbour in neighbours_ (size num_nodes + 1)
  std::vector<int> neighbours_;  // sorted unique adjacent nodes, node by node
};

using NodalSparsity = SimplexSparsity<2>;
using NodalSparsity3 = SimplexSparsity<3>;
extern template class SimplexSparsity<2>;
extern template class SimplexSparsity<3>;

// Cell indices of one body (all cells when body < 0).
template <int Dim>
std::vector<int> cells_of_body(const mesh::SimplexMesh<Dim>& mesh, int body);
// The 2D name of cells_of_body.
std::vector<int> triangles_of_body(const mesh::Mesh& mesh, int body);

}  // namespace contactrb::fem
