#include "contactrb/fem/sparsity.hpp"

#include <algorithm>
#include <string>

#include "contactrb/common/error.hpp"

namespace contactrb::fem {

NodalSparsity::NodalSparsity(const mesh::Mesh& mesh, const std::vector<int>& triangles)
    : num_nodes_(mesh.num_nodes()) {
  const auto n = static_cast<std::size_t>(num_nodes_);
  // Each incident triangle contributes its three vertices to a node's neighbour list.
  std::vector<int> count(n + 1, 0);
  for (int t : triangles) {
    // Messages are built only on failure (hot path).
    if (t < 0 || t >= mesh.num_triangles()) {
      throw Error("NodalSparsity: triangle index " + std::to_string(t) + " out of range (mesh has " +
                  std::to_string(mesh.num_triangles()) + " triangles)");
    }
    for (int v : mesh.triangles[static_cast<std::size_t>(t)]) {
      if (v < 0 || v >= num_nodes_) {
        throw Error("NodalSparsity: node index " + std::to_string(v) + " of triangle " + std::to_string(t) +
                    " out of range (mesh has " + std::to_string(num_nodes_) + " nodes)");
      }
      count[static_cast<std::size_t>(v) + 1] += 3;
    }
  }
  std::vector<int> raw_start(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) raw_start[i + 1] = raw_start[i] + count[i + 1];
  std::vector<int> raw(static_cast<std::size_t>(raw_start[n]));
  std::vector<int> fill(raw_start.begin(), raw_start.end() - 1);
  for (int t : triangles) {
    const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
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

std::vector<double> NodalSparsity::zero_values() const {
  return std::vector<double>(static_cast<std::size_t>(num_nonzeros()), 0.0);
}

void NodalSparsity::add(const std::array<int, 3>& tri, const ElementMatrix& element, double* values) const {
  for (int jb = 0; jb < 3; ++jb) {
    const int col_node = tri[static_cast<std::size_t>(jb)];
    const int first = start_[static_cast<std::size_t>(col_node)];
    const int degree = start_[static_cast<std::size_t>(col_node) + 1] - first;
    const int* begin = neighbours_.data() + first;
    // Column 2*col_node + c starts at 4*first + 2*degree*c.
    const std::size_t col0 = 4 * static_cast<std::size_t>(first);
    const std::size_t col1 = col0 + 2 * static_cast<std::size_t>(degree);
    for (int ia = 0; ia < 3; ++ia) {
      const int row_node = tri[static_cast<std::size_t>(ia)];
      int p = 0;
      while (begin[p] != row_node) ++p;  // present by construction; degrees are small
      const std::size_t offset = 2 * static_cast<std::size_t>(p);
      values[col0 + offset] += element(2 * ia, 2 * jb);
      values[col0 + offset + 1] += element(2 * ia + 1, 2 * jb);
      values[col1 + offset] += element(2 * ia, 2 * jb + 1);
      values[col1 + offset + 1] += element(2 * ia + 1, 2 * jb + 1);
    }
  }
}

Eigen::SparseMatrix<double> NodalSparsity::matrix(const std::vector<double>& values) const {
  require(static_cast<Eigen::Index>(values.size()) == num_nonzeros(),
          "NodalSparsity::matrix: " + std::to_string(values.size()) + " values for " +
              std::to_string(num_nonzeros()) + " pattern entries");
  Eigen::SparseMatrix<double> A = zero_matrix();
  std::copy(values.begin(), values.end(), A.valuePtr());
  return A;
}

Eigen::SparseMatrix<double> NodalSparsity::zero_matrix() const {
  const int ndofs = num_dofs();
  Eigen::SparseMatrix<double> A(ndofs, ndofs);
  A.resizeNonZeros(num_nonzeros());
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < num_nodes_; ++j) {
    const int first = start_[static_cast<std::size_t>(j)];
    const int degree = start_[static_cast<std::size_t>(j) + 1] - first;
    for (int c = 0; c < 2; ++c) {
      int pos = 4 * first + 2 * degree * c;
      for (int p = 0; p < degree; ++p) {
        const int i = neighbours_[static_cast<std::size_t>(first + p)];
        inner[pos++] = 2 * i;
        inner[pos++] = 2 * i + 1;
      }
      outer[2 * j + c + 1] = pos;
    }
  }
  std::fill(A.valuePtr(), A.valuePtr() + num_nonzeros(), 0.0);
  return A;
}

void NodalSparsity::restricted_pattern(const std::vector<int>& kept, std::vector<int>& outer,
                                       std::vector<int>& inner) const {
  std::vector<int> position(static_cast<std::size_t>(num_dofs()), -1);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const int dof = kept[k];
    require(dof >= 0 && dof < num_dofs() && position[static_cast<std::size_t>(dof)] < 0,
            "NodalSparsity::restricted_pattern: DOF " + std::to_string(dof) + " out of range or repeated");
    position[static_cast<std::size_t>(dof)] = static_cast<int>(k);
  }
  // Column of DOF 2 j + c: rows 2 i, 2 i + 1 for the neighbours i of node j, ascending (zero_matrix).
  auto for_rows = [&](int dof, auto&& visit) {
    const std::size_t node = static_cast<std::size_t>(dof / 2);
    for (int q = start_[node]; q < start_[node + 1]; ++q) {
      const int i = neighbours_[static_cast<std::size_t>(q)];
      for (int c = 0; c < 2; ++c) {
        const int row = position[static_cast<std::size_t>(2 * i + c)];
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

std::vector<int> triangles_of_body(const mesh::Mesh& mesh, int body) {
  require(mesh.body.size() == mesh.triangles.size(),
          "triangles_of_body: " + std::to_string(mesh.body.size()) + " body ids for " +
              std::to_string(mesh.triangles.size()) + " triangles");
  std::vector<int> list;
  list.reserve(mesh.triangles.size());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    if (body < 0 || mesh.body[static_cast<std::size_t>(t)] == body) list.push_back(t);
  }
  return list;
}

}  // namespace contactrb::fem
