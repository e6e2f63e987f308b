#include "contactrb/mesh/mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "contactrb/common/error.hpp"

namespace contactrb::mesh {

template <int Dim>
int SimplexMesh<Dim>::num_bodies() const {
  int n = 0;
  for (int b : body) n = std::max(n, b + 1);
  return n;
}

template <int Dim>
const std::vector<typename SimplexMesh<Dim>::Facet>& SimplexMesh<Dim>::boundary(const std::string& name) const {
  auto it = boundaries.find(name);
  if (it == boundaries.end()) {
    std::ostringstream os;
    os << "mesh has no boundary group '" << name << "' (groups present:";
    for (const auto& [key, facets] : boundaries) os << " '" << key << "'";
    os << ")";
    throw Error(os.str());
  }
  return it->second;
}

template <int Dim>
double signed_volume(const SimplexMesh<Dim>& mesh, int c) {
  const auto& cell = mesh.cells()[static_cast<std::size_t>(c)];
  const auto& p0 = mesh.nodes[static_cast<std::size_t>(cell[0])];
  const auto& p1 = mesh.nodes[static_cast<std::size_t>(cell[1])];
  const auto& p2 = mesh.nodes[static_cast<std::size_t>(cell[2])];
  if constexpr (Dim == 2) {
    return 0.5 * ((p1.x() - p0.x()) * (p2.y() - p0.y()) - (p2.x() - p0.x()) * (p1.y() - p0.y()));
  } else {
    const auto& p3 = mesh.nodes[static_cast<std::size_t>(cell[3])];
    return (p1 - p0).dot((p2 - p0).cross(p3 - p0)) / 6.0;
  }
}

double signed_area(const Mesh& mesh, int t) { return signed_volume(mesh, t); }

template <int Dim>
Eigen::Matrix<double, Dim, 1> facet_area_normal(const SimplexMesh<Dim>& mesh,
                                                const typename SimplexMesh<Dim>::Facet& facet) {
  const auto v = facet.vertices();
  const auto& a = mesh.nodes[static_cast<std::size_t>(v[0])];
  const auto& b = mesh.nodes[static_cast<std::size_t>(v[1])];
  if constexpr (Dim == 2) {
    return {b.y() - a.y(), a.x() - b.x()};
  } else {
    const auto& c = mesh.nodes[static_cast<std::size_t>(v[2])];
    return 0.5 * (b - a).cross(c - a);
  }
}

template <int Dim>
std::vector<int> boundary_nodes(const SimplexMesh<Dim>& mesh, const std::string& name) {
  std::vector<int> nodes;
  for (const auto& facet : mesh.boundary(name)) {
    for (int v : facet.vertices()) nodes.push_back(v);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

std::vector<int> ordered_chain(const Mesh& mesh, const std::string& name) {
  const auto& edges = mesh.boundary(name);
  require(!edges.empty(), "boundary group '" + name + "' is empty");
  std::unordered_map<int, int> next;  // a -> b
  std::unordered_map<int, int> in_degree;
  for (const Edge& e : edges) {
    require(next.emplace(e.a, e.b).second,
            "boundary group '" + name + "' is not a single polyline (node " + std::to_string(e.a) +
                " starts two edges)");
    ++in_degree[e.b];
  }
  int start = edges.front().a;
  int starts = 0;
  for (const Edge& e : edges) {
    if (in_degree.count(e.a) == 0) {
      start = e.a;
      ++starts;
    }
  }
  require(starts <= 1, "boundary group '" + name + "' is not a single polyline (" +
                           std::to_string(starts) + " pieces)");
  std::vector<int> chain{start};
  int current = start;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    auto it = next.find(current);
    if (it == next.end()) break;
    current = it->second;
    if (current == start) break;  // closed loop
    chain.push_back(current);
  }
  require(chain.size() == edges.size() + (starts == 0 ? 0 : 1),
          "boundary group '" + name + "' is not a single polyline");
  return chain;
}

namespace {

template <std::size_t N>
std::string index_list(const std::array<int, N>& v) {
  std::string s = "(";
  for (std::size_t k = 0; k < N; ++k) s += (k == 0 ? "" : ", ") + std::to_string(v[k]);
  return s + ")";
}

// Longest squared edge of cell c, the scale of the degenerate-cell test.
template <int Dim>
double longest_edge2(const SimplexMesh<Dim>& mesh, int c) {
  const auto& cell = mesh.cells()[static_cast<std::size_t>(c)];
  double h2 = 0.0;
  for (int i = 0; i < Dim + 1; ++i) {
    for (int j = i + 1; j < Dim + 1; ++j) {
      h2 = std::max(h2, (mesh.nodes[static_cast<std::size_t>(cell[static_cast<std::size_t>(i)])] -
                         mesh.nodes[static_cast<std::size_t>(cell[static_cast<std::size_t>(j)])])
                            .squaredNorm());
    }
  }
  return h2;
}

// Checks cell c (node range, body id, orientation) and marks its nodes used.
template <int Dim>
void validate_cell(const SimplexMesh<Dim>& mesh, int c, std::vector<char>& used) {
  using Names = SimplexNames<Dim>;
  const int n = mesh.num_nodes();
  const std::string cell_name = std::string(Names::cell) + " ";
  for (int v : mesh.cells()[static_cast<std::size_t>(c)]) {
    if (!(v >= 0 && v < n)) {
      throw Error(cell_name + std::to_string(c) + " references node " + std::to_string(v) + " outside [0, " +
                  std::to_string(n) + ")");
    }
    used[static_cast<std::size_t>(v)] = 1;
  }
  const int b = mesh.body[static_cast<std::size_t>(c)];
  if (!(b == kSlaveBody || b == kMasterBody)) {
    throw Error(cell_name + std::to_string(c) + " has body id " + std::to_string(b) +
                " (expected 0 for the slave body or 1 for the master body)");
  }
  const double measure = signed_volume(mesh, c);
  // Relative test: the measure against the longest edge to the power Dim.
  const double h2 = longest_edge2(mesh, c);
  const double scale = Dim == 2 ? h2 : h2 * std::sqrt(h2);
  if (!(measure > 1e-12 * scale)) {
    const char* inverted = Dim == 2 ? " is inverted (clockwise)" : " is inverted (negative volume)";
    throw Error(cell_name + std::to_string(c) +
                (measure < 0 ? std::string(inverted) : std::string(" has zero ") + Names::measure));
  }
}

}  // namespace

template <int Dim>
void validate(const SimplexMesh<Dim>& mesh) {
  using Names = SimplexNames<Dim>;
  const int n = mesh.num_nodes();
  require(n > 0, "mesh has no nodes");
  require(mesh.num_cells() > 0, std::string("mesh has no ") + Names::cell + "s");
  require(mesh.body.size() == mesh.cells().size(),
          "mesh has " + std::to_string(mesh.cells().size()) + " " + Names::cell + "s but " +
              std::to_string(mesh.body.size()) + " body ids");
  // Messages are built only on failure (an eager require() formats ~4 strings per triangle:
  // 9% of a semi-smooth Newton solve on the 700-node hertz-a mesh, setup included).
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  std::vector<std::array<int, Dim>> cell_facets;  // oriented keys, sorted below
  cell_facets.reserve(static_cast<std::size_t>(Dim + 1) * mesh.cells().size());
  for (int c = 0; c < mesh.num_cells(); ++c) {
    validate_cell(mesh, c, used);
    const auto& cell = mesh.cells()[static_cast<std::size_t>(c)];
    for (const auto& local : kCellFacets<Dim>) {
      std::array<int, Dim> f{};
      for (int k = 0; k < Dim; ++k) f[static_cast<std::size_t>(k)] = cell[static_cast<std::size_t>(local[static_cast<std::size_t>(k)])];
      cell_facets.push_back(oriented_key<Dim>(f));
    }
  }
  std::sort(cell_facets.begin(), cell_facets.end());
  for (int v = 0; v < n; ++v) {
    if (used[static_cast<std::size_t>(v)] == 0) {
      throw Error("node " + std::to_string(v) + " is not referenced by any " + Names::cell);
    }
  }
  for (const auto& [name, facets] : mesh.boundaries) {
    for (const auto& facet : facets) {
      if (!std::binary_search(cell_facets.begin(), cell_facets.end(), oriented_key<Dim>(facet.vertices()))) {
        throw Error("boundary group '" + name + "' " + Names::facet + " " + index_list(facet.vertices()) +
                    (Dim == 2 ? " is not a counter-clockwise edge of a triangle"
                              : " is not an outward-oriented face of a tetrahedron"));
      }
    }
  }
}

template <int Dim>
void map_body(SimplexMesh<Dim>& mesh, int body, const std::type_identity_t<Eigen::Matrix<double, Dim, Dim>>& M,
              const std::type_identity_t<Eigen::Matrix<double, Dim, 1>>& b) {
  std::vector<int> owner(mesh.nodes.size(), -1);
  for (int c = 0; c < mesh.num_cells(); ++c) {
    for (int v : mesh.cells()[static_cast<std::size_t>(c)]) {
      int& o = owner[static_cast<std::size_t>(v)];
      const int bc = mesh.body[static_cast<std::size_t>(c)];
      require(o == -1 || o == bc, "node " + std::to_string(v) + " belongs to both bodies");
      o = bc;
    }
  }
  for (std::size_t v = 0; v < mesh.nodes.size(); ++v) {
    if (owner[v] == body) mesh.nodes[v] = M * mesh.nodes[v] + b;
  }
}

#define CONTACTRB_MESH_INSTANTIATE(D)                                                                             \
  template struct SimplexMesh<D>;                                                                                 \
  template double signed_volume<D>(const SimplexMesh<D>&, int);                                                   \
  template Eigen::Matrix<double, D, 1> facet_area_normal<D>(const SimplexMesh<D>&,                                \
                                                            const typename SimplexMesh<D>::Facet&);               \
  template std::vector<int> boundary_nodes<D>(const SimplexMesh<D>&, const std::string&);                         \
  template void validate<D>(const SimplexMesh<D>&);                                                               \
  template void map_body<D>(SimplexMesh<D>&, int, const std::type_identity_t<Eigen::Matrix<double, D, D>>&,        \
                            const std::type_identity_t<Eigen::Matrix<double, D, 1>>&);
CONTACTRB_MESH_INSTANTIATE(2)
CONTACTRB_MESH_INSTANTIATE(3)
#undef CONTACTRB_MESH_INSTANTIATE

}  // namespace contactrb::mesh
