#pragma once
// The group /mesh of the snapshot and reduced-model files: the reference mesh the HF
// solutions live on (nodes, cells, body of each cell, named boundary facet groups; triangles
// and edges in 2D, tetrahedra and triangles in 3D), so
// that a file needs no .msh path to be used (docs/file-formats.md). Visited by FieldWriter and
// FieldReader (hdf5_visitor.hpp); the reader's caller runs mesh::validate on the result.
// Internal to io/: include only from io/*.cpp.
#include <cstdio>
#include <map>
#include <type_traits>
#include <string>
#include <vector>

#include "contactrb/io/hdf5_visitor.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::io::hdf5 {

// "000000", "000001", ...: the subgroup names of numbered lists (sort as their index).
inline std::string list_entry_name(std::size_t i) {
  char buffer[24];
  std::snprintf(buffer, sizeof buffer, "%06zu", i);
  return buffer;
}

// What /mesh says of its datasets in each dimension (the 2D texts are those of every 2D file).
template <int Dim>
struct MeshGroupText;
template <>
struct MeshGroupText<2> {
  static constexpr const char* group =
      "the reference mesh (reference configuration, the file's refinement level): P1 triangles of "
      "two bodies; DOF 2 i + c is component c (0: x, 1: y) of node i";
  static constexpr const char* nodes = "num_nodes x 2: row i is (x, y) of node i";
  static constexpr const char* cells_name = "triangles";
  static constexpr const char* cells = "num_triangles x 3: row t is the node indices of triangle t, counter-clockwise";
  static constexpr const char* body = "num_triangles: body of triangle t, 0 slave body, 1 master body";
  static constexpr const char* boundaries =
      "named boundary edge groups, one subgroup each (000000, ...): attribute name, dataset edges";
  static constexpr const char* facets_name = "edges";
  static constexpr const char* facets =
      "num_edges x 2: row k is the nodes (a, b) of edge k, oriented with its body on the left";
  static constexpr const char* columns = "2 (x, y)";
};
template <>
struct MeshGroupText<3> {
  static constexpr const char* group =
      "the reference mesh (reference configuration, the file's refinement level): P1 tetrahedra of "
      "two bodies; DOF 3 i + c is component c (0: x, 1: y, 2: z) of node i";
  static constexpr const char* nodes = "num_nodes x 3: row i is (x, y, z) of node i";
  static constexpr const char* cells_name = "tetrahedra";
  static constexpr const char* cells =
      "num_tetrahedra x 4: row t is the node indices (p0, p1, p2, p3) of tetrahedron t, "
      "det(p1 - p0, p2 - p0, p3 - p0) > 0";
  static constexpr const char* body = "num_tetrahedra: body of tetrahedron t, 0 slave body, 1 master body";
  static constexpr const char* boundaries =
      "named boundary triangle groups, one subgroup each (000000, ...): attribute name, dataset faces";
  static constexpr const char* facets_name = "faces";
  static constexpr const char* facets =
      "num_faces x 3: row k is the nodes (a, b, c) of boundary triangle k, counter-clockwise seen from "
      "outside its body";
  static constexpr const char* columns = "3 (x, y, z)";
};

// M: mesh::Mesh or mesh::Mesh3, const for the writer. The dimension of the file is recorded
// by its owner (snapshot files: the root attribute `dimension`).
template <typename V, typename M>
void visit_mesh(V& v, const Loc& root, M& m) {
  using MeshType = std::remove_const_t<M>;
  constexpr int Dim = MeshType::dim;
  using Text = MeshGroupText<Dim>;
  Handle g = v.group(root, "mesh", Text::group);
  const Loc loc{g.get(), root.field("mesh")};
  Eigen::MatrixXd nodes(static_cast<Eigen::Index>(m.nodes.size()), Dim);
  for (std::size_t i = 0; i < m.nodes.size(); ++i) nodes.row(static_cast<Eigen::Index>(i)) = m.nodes[i].transpose();
  v.mat(loc, "nodes", nodes, {Text::nodes, "length (the case's unit)"});
  std::vector<int> cells;
  cells.reserve((Dim + 1) * m.cells().size());
  for (const auto& t : m.cells()) cells.insert(cells.end(), t.begin(), t.end());
  v.ints(loc, Text::cells_name, cells, {Text::cells, "index (0-based)"}, Dim + 1);
  v.ints(loc, "body", m.body, {Text::body, "index (0-based)"});
  if constexpr (!V::kWriting) {
    if (nodes.cols() != Dim) {
      throw Failure{"dataset '" + loc.field("nodes") + "' has " + std::to_string(nodes.cols()) + " columns, expected " +
                    Text::columns};
    }
    m.nodes.resize(static_cast<std::size_t>(nodes.rows()));
    for (std::size_t i = 0; i < m.nodes.size(); ++i) m.nodes[i] = nodes.row(static_cast<Eigen::Index>(i)).transpose();
    m.cells().resize(cells.size() / (Dim + 1));
    for (std::size_t t = 0; t < m.cells().size(); ++t) {
      for (std::size_t k = 0; k <= Dim; ++k) m.cells()[t][k] = cells[(Dim + 1) * t + k];
    }
  }

  Handle bg = v.group(loc, "boundaries", Text::boundaries);
  const Loc b{bg.get(), loc.field("boundaries")};
  int count = static_cast<int>(m.boundaries.size());
  v.integer(b, "count", count);
  if (count < 0 || count > 100000) throw Failure{"'" + b.field("count") + "' is " + std::to_string(count)};
  auto it = m.boundaries.begin();
  std::map<std::string, std::vector<typename MeshType::Facet>> read;
  for (int k = 0; k < count; ++k) {
    const std::string entry = list_entry_name(static_cast<std::size_t>(k));
    Handle eg = v.group(b, entry, Dim == 2 ? "one boundary group: its name and its edges"
                                           : "one boundary group: its name and its triangles");
    const Loc e{eg.get(), b.field(entry)};
    std::string name;
    std::vector<int> facets;
    if constexpr (V::kWriting) {
      name = it->first;
      for (const auto& x : it->second) {
        const auto vertices = x.vertices();
        facets.insert(facets.end(), vertices.begin(), vertices.end());
      }
      ++it;
    }
    v.str(e, "name", name);
    v.ints(e, Text::facets_name, facets, {Text::facets, "index (0-based)"}, Dim);
    if constexpr (!V::kWriting) {
      if (read.count(name) != 0) throw Failure{"'" + e.field("name") + "': boundary group '" + name + "' appears twice"};
      auto& list = read[name];
      for (std::size_t i = 0; i + Dim - 1 < facets.size(); i += Dim) {
        if constexpr (Dim == 2) {
          list.push_back({facets[i], facets[i + 1]});
        } else {
          list.push_back({facets[i], facets[i + 1], facets[i + 2]});
        }
      }
    }
  }
  if constexpr (!V::kWriting) m.boundaries = std::move(read);
}

}  // namespace contactrb::io::hdf5
