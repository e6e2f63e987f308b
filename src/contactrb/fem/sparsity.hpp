#pragma once
// Sparsity pattern of the P1 vector matrices on a set of triangles, computed once in
// O(number of triangles); element matrices are then added in place (no triplets).
// Column 2*j + c holds rows 2*i and 2*i + 1 for every node i adjacent to node j
// (including j), in increasing order, so the matrix is compressed column-major.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "contactrb/fem/p1_element.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::fem {

class NodalSparsity {
 public:
  // Pattern of the triangles listed in `triangles` (indices into mesh.triangles).
  NodalSparsity(const mesh::Mesh& mesh, const std::vector<int>& triangles);

  int num_dofs() const { return 2 * num_nodes_; }
  Eigen::Index num_nonzeros() const { return 4 * static_cast<Eigen::Index>(neighbours_.size()); }
  // Zero values in pattern order, to accumulate into.
  std::vector<double> zero_values() const;
  // Adds an element matrix (local DOF 2*i + c) of triangle `tri` into `values`, an array of
  // num_nonzeros() entries in pattern order (a std::vector or a matrix's valuePtr()).
  void add(const std::array<int, 3>& tri, const ElementMatrix& element, double* values) const;
  void add(const std::array<int, 3>& tri, const ElementMatrix& element, std::vector<double>& values) const {
    add(tri, element, values.data());
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

// Triangle indices of one body (all triangles when body < 0).
std::vector<int> triangles_of_body(const mesh::Mesh& mesh, int body);

}  // namespace contactrb::fem
