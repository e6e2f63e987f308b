#pragma once
// The group /mesh of the snapshot and reduced-model files: the reference mesh the HF
// solutions live on (nodes, triangles, body of each triangle, named boundary edge groups), so
// that a file needs no .msh path to be used (docs/file-formats.md). Visited by FieldWriter and
// FieldReader (hdf5_visitor.hpp); the reader's caller runs mesh::validate on the result.
// Internal to io/: include only from io/*.cpp.
#include <cstdio>
#include <map>
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

// M: mesh::Mesh, or const mesh::Mesh for the writer.
template <typename V, typename M>
void visit_mesh(V& v, const Loc& root, M& m) {
  Handle g = v.group(root, "mesh",
                     "the reference mesh (reference configuration, the file's refinement level): P1 triangles of "
                     "two bodies; DOF 2 i + c is component c (0: x, 1: y) of node i");
  const Loc loc{g.get(), root.field("mesh")};
  Eigen::MatrixXd nodes(static_cast<Eigen::Index>(m.nodes.size()), 2);
  for (std::size_t i = 0; i < m.nodes.size(); ++i) nodes.row(static_cast<Eigen::Index>(i)) = m.nodes[i].transpose();
  v.mat(loc, "nodes", nodes, {"num_nodes x 2: row i is (x, y) of node i", "length (the case's unit)"});
  std::vector<int> triangles;
  triangles.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles) triangles.insert(triangles.end(), t.begin(), t.end());
  v.ints(loc, "triangles", triangles,
         {"num_triangles x 3: row t is the node indices of triangle t, counter-clockwise", "index (0-based)"}, 3);
  v.ints(loc, "body", m.body, {"num_triangles: body of triangle t, 0 slave body, 1 master body", "index (0-based)"});
  if constexpr (!V::kWriting) {
    if (nodes.cols() != 2) {
      throw Failure{"dataset '" + loc.field("nodes") + "' has " + std::to_string(nodes.cols()) +
                    " columns, expected 2 (x, y)"};
    }
    m.nodes.resize(static_cast<std::size_t>(nodes.rows()));
    for (std::size_t i = 0; i < m.nodes.size(); ++i) m.nodes[i] = nodes.row(static_cast<Eigen::Index>(i)).transpose();
    m.triangles.resize(triangles.size() / 3);
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      m.triangles[t] = {triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]};
    }
  }

  Handle bg = v.group(loc, "boundaries",
                      "named boundary edge groups, one subgroup each (000000, ...): attribute name, dataset edges");
  const Loc b{bg.get(), loc.field("boundaries")};
  int count = static_cast<int>(m.boundaries.size());
  v.integer(b, "count", count);
  if (count < 0 || count > 100000) throw Failure{"'" + b.field("count") + "' is " + std::to_string(count)};
  auto it = m.boundaries.begin();
  std::map<std::string, std::vector<mesh::Edge>> read;
  for (int k = 0; k < count; ++k) {
    const std::string entry = list_entry_name(static_cast<std::size_t>(k));
    Handle eg = v.group(b, entry, "one boundary group: its name and its edges");
    const Loc e{eg.get(), b.field(entry)};
    std::string name;
    std::vector<int> edges;
    if constexpr (V::kWriting) {
      name = it->first;
      for (const mesh::Edge& x : it->second) edges.insert(edges.end(), {x.a, x.b});
      ++it;
    }
    v.str(e, "name", name);
    v.ints(e, "edges", edges,
           {"num_edges x 2: row k is the nodes (a, b) of edge k, oriented with its body on the left",
            "index (0-based)"},
           2);
    if constexpr (!V::kWriting) {
      if (read.count(name) != 0) throw Failure{"'" + e.field("name") + "': boundary group '" + name + "' appears twice"};
      std::vector<mesh::Edge>& list = read[name];
      for (std::size_t i = 0; i + 1 < edges.size(); i += 2) list.push_back({edges[i], edges[i + 1]});
    }
  }
  if constexpr (!V::kWriting) m.boundaries = std::move(read);
}

}  // namespace contactrb::io::hdf5
