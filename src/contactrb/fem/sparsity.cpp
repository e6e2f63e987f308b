#include "contactrb/fem/sparsity.hpp"

#include <algorithm>
#include <string>

#include "contactrb/common/error.hpp"

namespace contactrb::fem {

template <int Dim>
SimplexSparsity<Dim>::SimplexSparsity(const mesh::SimplexMesh<Dim>& mesh, const std::vector<int>& triangles)
    : num_nodes_(mesh.num_nodes()) {
  const auto n = static_cast<std::size_t>(num_nodes_);
  const std::string cell = mesh::SimplexNames<Dim>::cell;
  // Each incident cell contributes its Dim + 1 vertices to a node's neighbour list.
  std::vector<int> count(n + 1, 0);
  for (int t : triangles) {
    // Messages are built only on failure (hot path).
    if (t < 0 || t >= mesh.num_cells()) {
      throw Error("NodalSparsity: " + cell + " index " + std::to_string(t) + " out of range (mesh has " +
                  std::to_string(mesh.num_cells()) + " " + cell + "s)");
    }
    for (int v : mesh.cells()[static_cast<std::size_t>(t)]) {
      if (v < 0 || v >= num_nodes_) {
        throw Error("NodalSparsity: node index " + std::to_string(v) + " of " + cell + " " + std::to_string(t) +
                    " out of range (mesh has " + std::to_string(num_nodes_) + " nodes)");
      }
      count[static_cast<std::size_t>(v) + 1] += Dim + 1;
    }
  }
  std::vector<int> raw_start(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) raw_start[i + 1] = raw_start[i] + count[i + 1];
  std::vector<int> raw(static_cast<std::size_t>(raw_start[n]));
  std::vector<int> fill(raw_start.begin(), raw_start.end() - 1);
  for (int t : triangles) {
    const auto& tri = mesh.cells()[static_cast<std::size_t>(t)];
    for (int v : tri) {
      for (int w : tri) raw[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = w;
    }
  }
  start_.assign(n + 1, 0);
  neighbours_.reserve(raw.size() / 2);
  for (std::size_t i = 0; i < n; ++i) {
    auto first = raw.begin() + raw_start[i], last = raw.begin() + raw_start[i + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    neighbours_.insert(neighbours_.end(), first, last);
    start_[i + 1] = static_cast<int>(neighbours_.size());
  }
}

template <int Dim>
std::vector<double> SimplexSparsity<Dim>::zero_values() const {
  return std::vector<double>(static_cast<std::size_t>(num_nonzeros()), 0.0);
}

template <int Dim>
void SimplexSparsity<Dim>::add(const std::array<int, Dim + 1>& cell, const SimplexElementMatrix<Dim>& element,
                               double* values) const {
  for (int jb = 0; jb < Dim + 1; ++jb) {
    const int col_node = cell[static_cast<std::size_t>(jb)];
    const int first = start_[static_cast<std::size_t>(col_node)];
    const int degree = start_[static_cast<std::size_t>(col_node) + 1] - first;
    const int* begin = neighbours_.data() + first;
    // Column Dim*col_node + c starts at Dim^2 first + Dim degree c.
    std::array<std::size_t, Dim> col;
    for (int c = 0; c < Dim; ++c) {
      col[static_cast<std::size_t>(c)] = Dim * Dim * static_cast<std::size_t>(first) + Dim * static_cast<std::size_t>(degree) * c;
    }
    for (int ia = 0; ia < Dim + 1; ++ia) {
      const int row_node = cell[static_cast<std::size_t>(ia)];
      int p = 0;
      while (begin[p] != row_node) ++p;  // present by construction; degrees are small
      const std::size_t offset = Dim * static_cast<std::size_t>(p);
      for (int c = 0; c < Dim; ++c) {
        for (int r = 0; r < Dim; ++r) {
          values[col[static_cast<std::size_t>(c)] + offset + r] += element(Dim * ia + r, Dim * jb + c);
        }
      }
    }
  }
}

template <int Dim>
Eigen::SparseMatrix<double> SimplexSparsity<Dim>::matrix(const std::vector<double>& values) const {
  require(static_cast<Eigen::Index>(values.size()) == num_nonzeros(),
          "NodalSparsity::matrix: " + std::to_string(values.size()) + " values for " +
              std::to_string(num_nonzeros()) + " pattern entries");
  Eigen::SparseMatrix<double> A = zero_matrix();
  std::copy(values.begin(), values.end(), A.valuePtr());
  return A;
}

template <int Dim>
Eigen::SparseMatrix<double> SimplexSparsity<Dim>::zero_matrix() const {
  const int ndofs = num_dofs();
  Eigen::SparseMatrix<double> A(ndofs, ndofs);
  A.resizeNonZeros(num_nonzeros());
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < num_nodes_; ++j) {
    const int first = start_[static_cast<std::size_t>(j)];
    const int degree = start_[static_cast<std::size_t>(j) + 1] - first;
    for (int c = 0; c < Dim; ++c) {
      int pos = Dim * Dim * first + Dim * degree * c;
      for (int p = 0; p < degree; ++p) {
        const int i = neighbours_[static_cast<std::size_t>(first + p)];
        for (int r = 0; r < Dim; ++r) inner[pos++] = Dim * i + r;
      }
      outer[Dim * j + c + 1] = pos;
    }
  }
  std::fill(A.valuePtr(), A.valuePtr() + num_nonzeros(), 0.0);
  return A;
}

template <int Dim>
void SimplexSparsity<Dim>::restricted_pattern(const std::vector<int>& kept, std::vector<int>& outer,
                                       std::vector<int>& inner) const {
  std::vector<int> position(static_cast<std::size_t>(num_dofs()), -1);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const int dof = kept[k];
    require(dof >= 0 && dof < num_dofs() && position[static_cast<std::size_t>(dof)] < 0,
            "NodalSparsity::restricted_pattern: DOF " + std::to_string(dof) + " out of range or repeated");
    position[static_cast<std::size_t>(dof)] = static_cast<int>(k);
  }
  // Column of DOF Dim j + c: rows Dim i + r for the neighbours i of node j, ascending (zero_matrix).
  auto for_rows = [&](int dof, auto&& visit) {
    const std::size_t node = static_cast<std::size_t>(dof / Dim);
    for (int q = start_[node]; q < start_[node + 1]; ++q) {
      const int i = neighbours_[static_cast<std::size_t>(q)];
      for (int c = 0; c < Dim; ++c) {
        const int row = position[static_cast<std::size_t>(Dim * i + c)];
        if (row >= 0) visit(row);
      }
    }
  };
  outer.assign(kept.size() + 1, 0);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    int count = 0;
    for_rows(kept[k], [&](int) { ++count; });
    outer[k + 1] = outer[k] + count;
  }
  inner.resize(static_cast<std::size_t>(outer.back()));
  std::size_t pos = 0;
  for (int dof : kept) for_rows(dof, [&](int row) { inner[pos++] = row; });
}

template <int Dim>
std::vector<int> cells_of_body(const mesh::SimplexMesh<Dim>& mesh, int body) {
  const std::string cells = std::string(mesh::SimplexNames<Dim>::cell) + "s";
  require(mesh.body.size() == mesh.cells().size(), "cells_of_body: " + std::to_string(mesh.body.size()) +
                                                       " body ids for " + std::to_string(mesh.cells().size()) +
                                                       " " + cells);
  std::vector<int> list;
  list.reserve(mesh.cells().size());
  for (int t = 0; t < mesh.num_cells(); ++t) {
    if (body < 0 || mesh.body[static_cast<std::size_t>(t)] == body) list.push_back(t);
  }
  return list;
}

std::vector<int> triangles_of_body(const mesh::Mesh& mesh, int body) { return cells_of_body(mesh, body); }

template class SimplexSparsity<2>;
template class SimplexSparsity<3>;
template std::vector<int> cells_of_body<2>(const mesh::Mesh&, int);
template std::vector<int> cells_of_body<3>(const mesh::Mesh3&, int);

}  // namespace contactrb::fem
