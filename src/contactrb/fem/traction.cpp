#include "contactrb/fem/traction.hpp"

#include <utility>

#include "contactrb/common/error.hpp"

namespace contactrb::fem {

template <int Dim>
Eigen::VectorXd traction_load(const mesh::SimplexMesh<Dim>& mesh, const SurfaceLoad<Dim>& load) {
  using Vector = Eigen::Matrix<double, Dim, 1>;
  require(load.group != mesh::kSlaveBoundary && load.group != mesh::kMasterBoundary,
          "a traction load on the contact group '" + load.group + "' is not allowed");
  const auto& facets = mesh.boundary(load.group);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (const auto& facet : facets) {
    for (int v : facet.vertices()) {
      require(v >= 0 && v < mesh.num_nodes(), "traction_load: " + std::string(mesh::SimplexNames<Dim>::facet) +
                                                  " of group '" + load.group + "' has a node index out of range");
    }
    // Facets are oriented with the outward normal (mesh.hpp): -p n |F| = -p (area normal).
    Vector t_measure;
    if (load.is_pressure) {
      t_measure = -load.pressure * mesh::facet_area_normal(mesh, facet);
    } else if constexpr (Dim == 2) {
      t_measure = load.vector * (mesh.nodes[static_cast<std::size_t>(facet.b)] -
                                 mesh.nodes[static_cast<std::size_t>(facet.a)]).norm();
    } else {
      t_measure = load.vector * mesh::facet_area_normal(mesh, facet).norm();
    }
    for (int node : facet.vertices()) f.template segment<Dim>(Dim * node) += (1.0 / Dim) * t_measure;
  }
  return f;
}

template <int Dim>
int traction_body(const mesh::SimplexMesh<Dim>& mesh, const std::string& group) {
  const auto& facets = mesh.boundary(group);
  require(!facets.empty(), "boundary group '" + group + "' has no " + mesh::SimplexNames<Dim>::facet);
  // The body of each node, from the cells (bodies are disjoint: mesh.hpp).
  std::vector<int> body(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (int t = 0; t < mesh.num_cells(); ++t) {
    for (int n : mesh.cells()[static_cast<std::size_t>(t)]) {
      body[static_cast<std::size_t>(n)] = mesh.body[static_cast<std::size_t>(t)];
    }
  }
  int found = -1;
  for (const auto& facet : facets) {
    for (int n : facet.vertices()) {
      require(n >= 0 && n < mesh.num_nodes(), "boundary group '" + group + "' has a node index out of range");
      const int b = body[static_cast<std::size_t>(n)];
      require(found == -1 || b == found, "boundary group '" + group + "' touches both bodies");
      found = b;
    }
  }
  return found;
}

template Eigen::VectorXd traction_load<2>(const mesh::Mesh&, const SurfaceLoad<2>&);
template Eigen::VectorXd traction_load<3>(const mesh::Mesh3&, const SurfaceLoad<3>&);
template int traction_body<2>(const mesh::Mesh&, const std::string&);
template int traction_body<3>(const mesh::Mesh3&, const std::string&);

}  // namespace contactrb::fem
