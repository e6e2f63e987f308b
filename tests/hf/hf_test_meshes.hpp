#pragma once
// Meshes for the HF solver tests, built from structured rectangles.
#include "contactrb/mesh/structured.hpp"

namespace contactrb::test_meshes {

// Upper block [0, width] x [0, h1] (slave body, bottom edge "slave") over a lower block
// [0, width] x [-h2, 0] (master body, top edge "master"), with nx1 and nx2 cells along the
// interface (non-matching when they differ). Other groups: "top", "bottom", "left1",
// "left2", "right1", "right2".
inline mesh::Mesh two_blocks(double width, double h1, double h2, int nx1, int ny1, int nx2, int ny2) {
  mesh::Mesh upper = mesh::rectangle(0.0, 0.0, width, h1, nx1, ny1, mesh::kSlaveBody);
  mesh::Mesh lower = mesh::rectangle(0.0, -h2, width, 0.0, nx2, ny2, mesh::kMasterBody);
  mesh::rename_boundary(upper, "bottom", mesh::kSlaveBoundary);
  mesh::rename_boundary(upper, "left", "left1");
  mesh::rename_boundary(upper, "right", "right1");
  mesh::rename_boundary(lower, "top", mesh::kMasterBoundary);
  mesh::rename_boundary(lower, "left", "left2");
  mesh::rename_boundary(lower, "right", "right2");
  return mesh::merge(upper, lower);
}

}  // namespace contactrb::test_meshes

#include <vector>

namespace contactrb::test_meshes {

// The triangles of one body with their nodes renumbered, and the boundary groups whose
// edges lie on that body; the body id is set to `new_body`.
inline mesh::Mesh extract_body(const mesh::Mesh& m, int body, int new_body) {
  mesh::Mesh out;
  std::vector<int> index(m.nodes.size(), -1);
  for (int t = 0; t < m.num_triangles(); ++t) {
    if (m.body[static_cast<std::size_t>(t)] != body) continue;
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      const int v = m.triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)];
      int& id = index[static_cast<std::size_t>(v)];
      if (id < 0) {
        id = out.num_nodes();
        out.nodes.push_back(m.nodes[static_cast<std::size_t>(v)]);
      }
      tri[static_cast<std::size_t>(k)] = id;
    }
    out.triangles.push_back(tri);
    out.body.push_back(new_body);
  }
  for (const auto& [name, edges] : m.boundaries) {
    std::vector<mesh::Edge> kept;
    for (const mesh::Edge& e : edges) {
      const int a = index[static_cast<std::size_t>(e.a)], b = index[static_cast<std::size_t>(e.b)];
      if (a >= 0 && b >= 0) kept.push_back({a, b});
    }
    if (!kept.empty()) out.boundaries[name] = kept;
  }
  return out;
}

}  // namespace contactrb::test_meshes
