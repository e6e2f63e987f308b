#include "contactrb/fem/traction.hpp"

#include <map>
#include <utility>

#include "contactrb/common/error.hpp"

namespace contactrb::fem {

Eigen::VectorXd traction_load(const mesh::Mesh& mesh, const TractionLoad& load) {
  require(load.group != mesh::kSlaveBoundary && load.group != mesh::kMasterBoundary,
          "a traction load on the contact group '" + load.group + "' is not allowed");
  const std::vector<mesh::Edge>& edges = mesh.boundary(load.group);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (const mesh::Edge& e : edges) {
    require(e.a >= 0 && e.a < mesh.num_nodes() && e.b >= 0 && e.b < mesh.num_nodes(),
            "traction_load: an edge of group '" + load.group + "' has a node index out of range");
    const Eigen::Vector2d d = mesh.nodes[static_cast<std::size_t>(e.b)] - mesh.nodes[static_cast<std::size_t>(e.a)];
    // Edges run with their body on the left (mesh.hpp): the outward normal is (dy, -dx) / |e|,
    // so -p n |e| = -p (dy, -dx).
    const Eigen::Vector2d t_len = load.is_pressure ? Eigen::Vector2d(-load.pressure * d.y(), load.pressure * d.x())
                                                   : Eigen::Vector2d(load.vector * d.norm());
    for (int node : {e.a, e.b}) f.segment<2>(2 * node) += 0.5 * t_len;
  }
  return f;
}

int traction_body(const mesh::Mesh& mesh, const std::string& group) {
  const std::vector<mesh::Edge>& edges = mesh.boundary(group);
  require(!edges.empty(), "boundary group '" + group + "' has no edge");
  // The body of each node, from the triangles (bodies are disjoint: mesh.hpp).
  std::vector<int> body(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int n : mesh.triangles[static_cast<std::size_t>(t)]) body[static_cast<std::size_t>(n)] = mesh.body[static_cast<std::size_t>(t)];
  }
  int found = -1;
  for (const mesh::Edge& e : edges) {
    for (int n : {e.a, e.b}) {
      require(n >= 0 && n < mesh.num_nodes(), "boundary group '" + group + "' has a node index out of range");
      const int b = body[static_cast<std::size_t>(n)];
      require(found == -1 || b == found, "boundary group '" + group + "' touches both bodies");
      found = b;
    }
  }
  return found;
}

}  // namespace contactrb::fem
