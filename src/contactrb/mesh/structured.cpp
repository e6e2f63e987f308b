#include "contactrb/mesh/structured.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "contactrb/common/error.hpp"

namespace contactrb::mesh {

Mesh rectangle(double x0, double y0, double x1, double y1, int nx, int ny, int body) {
  require(nx >= 1 && ny >= 1, "rectangle: nx and ny must be >= 1");
  require(x1 > x0 && y1 > y0, "rectangle: empty extent");
  Mesh m;
  auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      m.nodes.emplace_back(x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny);
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, c, d});
      }
      m.body.push_back(body);
      m.body.push_back(body);
    }
  }
  auto& bottom = m.boundaries["bottom"];
  auto& top = m.boundaries["top"];
  for (int i = 0; i < nx; ++i) {
    bottom.push_back({id(i, 0), id(i + 1, 0)});
    top.push_back({id(nx - i, ny), id(nx - i - 1, ny)});
  }
  auto& right = m.boundaries["right"];
  auto& left = m.boundaries["left"];
  for (int j = 0; j < ny; ++j) {
    right.push_back({id(nx, j), id(nx, j + 1)});
    left.push_back({id(0, ny - j), id(0, ny - j - 1)});
  }
  return m;
}

namespace {

// Facets of exactly one cell, outward-oriented, in the order of their sorted vertex sets.
template <int Dim>
std::vector<std::array<int, Dim>> boundary_facets(const SimplexMesh<Dim>& mesh) {
  std::map<std::array<int, Dim>, std::pair<int, std::array<int, Dim>>> seen;  // sorted -> (count, oriented)
  for (const auto& cell : mesh.cells()) {
    for (const auto& local : kCellFacets<Dim>) {
      std::array<int, Dim> f{};
      for (std::size_t k = 0; k < static_cast<std::size_t>(Dim); ++k) f[k] = cell[static_cast<std::size_t>(local[k])];
      std::array<int, Dim> key = f;
      std::sort(key.begin(), key.end());
      auto& entry = seen[key];
      ++entry.first;
      entry.second = f;
    }
  }
  std::vector<std::array<int, Dim>> facets;
  for (const auto& [key, entry] : seen) {
    if (entry.first == 1) facets.push_back(entry.second);
  }
  return facets;
}

// The six faces of the box [lo, hi]: the group of a boundary triangle with all its nodes on
// one face.
const char* box_face(const Mesh3& mesh, const std::array<int, 3>& f, const Eigen::Vector3d& lo,
                     const Eigen::Vector3d& hi) {
  static const char* names[3][2] = {{"left", "right"}, {"front", "back"}, {"bottom", "top"}};
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const double plane = side == 0 ? lo[axis] : hi[axis];
      bool on = true;
      for (int v : f) on = on && mesh.nodes[static_cast<std::size_t>(v)][axis] == plane;
      if (on) return names[axis][side];
    }
  }
  throw Error("box: a boundary triangle lies on no face of the box");
}

}  // namespace

Mesh3 box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny, int nz, int body) {
  require(nx >= 1 && ny >= 1 && nz >= 1, "box: nx, ny and nz must be >= 1");
  require((hi - lo).minCoeff() > 0.0, "box: empty extent");
  Mesh3 m;
  const std::array<int, 3> n{nx, ny, nz};
  auto id = [nx, ny](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  for (int k = 0; k <= nz; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) {
        const std::array<int, 3> ijk{i, j, k};
        Eigen::Vector3d x;
        for (int a = 0; a < 3; ++a) x[a] = ijk[a] == n[a] ? hi[a] : lo[a] + (hi[a] - lo[a]) * ijk[a] / n[a];
        m.nodes.push_back(x);
      }
    }
  }
  // Kuhn's subdivision: one tetrahedron per order of the three axes, walking from the cube's
  // lowest corner to its highest one; odd orders are reflected, hence two nodes swapped.
  static const int orders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        for (int p = 0; p < 6; ++p) {
          std::array<int, 3> at{i, j, k};
          std::array<int, 4> tet{id(i, j, k), 0, 0, 0};
          for (int s = 0; s < 3; ++s) {
            ++at[static_cast<std::size_t>(orders[p][s])];
            tet[static_cast<std::size_t>(s) + 1] = id(at[0], at[1], at[2]);
          }
          if (p >= 3) std::swap(tet[1], tet[2]);
          m.tetrahedra.push_back(tet);
          m.body.push_back(body);
        }
      }
    }
  }
  for (const char* name : {"bottom", "top", "left", "right", "front", "back"}) m.boundaries[name];
  for (const auto& f : boundary_facets(m)) m.boundaries[box_face(m, f, lo, hi)].push_back({f[0], f[1], f[2]});
  return m;
}

namespace {

// The union of groups `from` under the name `to`.
void join_groups(Mesh3& mesh, const std::vector<std::string>& from, const std::string& to) {
  std::vector<Face> joined;
  for (const std::string& name : from) {
    const auto& faces = mesh.boundary(name);
    joined.insert(joined.end(), faces.begin(), faces.end());
    mesh.boundaries.erase(name);
  }
  mesh.boundaries[to] = std::move(joined);
}

// The groups of one block of stacked_blocks(): `contact` for the face towards the other block,
// `outer` for the opposite face, `sides` for the four vertical faces.
Mesh3 block(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n, int nz, int body, const char* contact_face,
            const char* contact, const char* outer_face, const char* outer, const std::string& sides) {
  Mesh3 m = box(lo, hi, n, n, nz, body);
  rename_boundary(m, contact_face, contact);
  if (std::string(outer_face) != outer) rename_boundary(m, outer_face, outer);
  join_groups(m, {"left", "right", "front", "back"}, sides);
  return m;
}

}  // namespace

Mesh3 stacked_blocks(int level, double gap) {
  require(level >= 0 && level <= 4, "stacked_blocks: level " + std::to_string(level) + " outside [0, 4]");
  require(std::isfinite(gap) && gap >= 0.0, "stacked_blocks: the gap must be finite and >= 0");
  constexpr double h = 0.5;
  const int n_master = 4 << level;
  const int n_slave = 3 * n_master / 2 + 1;  // odd: its node rows miss the master's inside the face
  const Mesh3 slave = block({0.0, 0.0, gap}, {1.0, 1.0, gap + h}, n_slave, (n_slave + 1) / 2, kSlaveBody, "bottom",
                            kSlaveBoundary, "top", "top", "slave_sides");
  const Mesh3 master = block({0.0, 0.0, -h}, {1.0, 1.0, 0.0}, n_master, n_master / 2, kMasterBody, "top",
                             kMasterBoundary, "bottom", "bottom", "master_sides");
  Mesh3 m = merge(slave, master);
  validate(m);
  return m;
}

template <int Dim>
SimplexMesh<Dim> merge(const SimplexMesh<Dim>& a, const SimplexMesh<Dim>& b) {
  SimplexMesh<Dim> m = a;
  const int shift = a.num_nodes();
  m.nodes.insert(m.nodes.end(), b.nodes.begin(), b.nodes.end());
  for (auto cell : b.cells()) {
    for (int& v : cell) v += shift;
    m.cells().push_back(cell);
  }
  m.body.insert(m.body.end(), b.body.begin(), b.body.end());
  for (const auto& [name, facets] : b.boundaries) {
    require(!m.has_boundary(name), "merge: both meshes have boundary group '" + name + "'");
    auto& dst = m.boundaries[name];
    for (auto facet : facets) {
      if constexpr (Dim == 2) {
        dst.push_back({facet.a + shift, facet.b + shift});
      } else {
        dst.push_back({facet.a + shift, facet.b + shift, facet.c + shift});
      }
    }
  }
  return m;
}

template <int Dim>
void rename_boundary(SimplexMesh<Dim>& mesh, const std::string& from, const std::string& to) {
  auto facets = mesh.boundary(from);
  require(!mesh.has_boundary(to), "rename_boundary: group '" + to + "' already exists");
  mesh.boundaries.erase(from);
  mesh.boundaries[to] = std::move(facets);
}

template <int Dim>
SimplexMesh<Dim> mirror(const SimplexMesh<Dim>& mesh, int axis, const std::string& plane_group) {
  require(axis >= 0 && axis < Dim, "mirror: axis " + std::to_string(axis) + " out of range");
  double extent = 0.0;
  for (const auto& x : mesh.nodes) extent = std::max(extent, x.cwiseAbs().maxCoeff());
  const double tol = 1e-12 * std::max(extent, 1.0);
  require(mesh.has_boundary(plane_group), "mirror: no boundary group '" + plane_group + "'");
  for (const auto& facet : mesh.boundary(plane_group)) {
    for (int v : facet.vertices()) {
      require(std::abs(mesh.nodes[static_cast<std::size_t>(v)](axis)) <= tol, 
              "mirror: a facet of '" + plane_group + "' is off the plane");
    }
  }
  SimplexMesh<Dim> m = mesh;
  std::vector<int> image(mesh.nodes.size());
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    if (std::abs(mesh.nodes[i](axis)) <= tol) {
      image[i] = static_cast<int>(i);
      continue;
    }
    image[i] = m.num_nodes();
    auto x = mesh.nodes[i];
    x(axis) = -x(axis);
    m.nodes.push_back(x);
  }
  auto on_image = [&](int v) { return image[static_cast<std::size_t>(v)]; };
  for (auto cell : mesh.cells()) {
    for (int& v : cell) v = on_image(v);
    std::swap(cell[0], cell[1]);  // a reflection reverses the orientation
    m.cells().push_back(cell);
  }
  m.body.insert(m.body.end(), mesh.body.begin(), mesh.body.end());
  m.boundaries.erase(plane_group);
  for (auto& [name, facets] : m.boundaries) {
    const std::size_t n = facets.size();
    for (std::size_t k = 0; k < n; ++k) {
      auto f = facets[k];
      if constexpr (Dim == 2) {
        facets.push_back({on_image(f.b), on_image(f.a)});
      } else {
        facets.push_back({on_image(f.b), on_image(f.a), on_image(f.c)});
      }
    }
  }
  return m;
}

template <int Dim>
void perturb_interior(SimplexMesh<Dim>& mesh, double fraction, unsigned seed) {
  // Boundary nodes: nodes of facets that belong to exactly one cell.
  std::map<std::array<int, Dim>, int> count;
  std::set<std::pair<int, int>> edges;
  for (const auto& cell : mesh.cells()) {
    for (const auto& local : kCellFacets<Dim>) {
      std::array<int, Dim> key{};
      for (std::size_t k = 0; k < static_cast<std::size_t>(Dim); ++k) key[k] = cell[static_cast<std::size_t>(local[k])];
      std::sort(key.begin(), key.end());
      ++count[key];
    }
    for (std::size_t i = 0; i < cell.size(); ++i) {
      for (std::size_t j = i + 1; j < cell.size(); ++j) edges.insert({std::min(cell[i], cell[j]), std::max(cell[i], cell[j])});
    }
  }
  std::vector<double> hmin(mesh.nodes.size(), INFINITY);
  for (const auto& [u, v] : edges) {
    const double len = (mesh.nodes[static_cast<std::size_t>(u)] - mesh.nodes[static_cast<std::size_t>(v)]).norm();
    hmin[static_cast<std::size_t>(u)] = std::min(hmin[static_cast<std::size_t>(u)], len);
    hmin[static_cast<std::size_t>(v)] = std::min(hmin[static_cast<std::size_t>(v)], len);
  }
  std::set<int> boundary;
  for (const auto& [key, c] : count) {
    if (c == 1) boundary.insert(key.begin(), key.end());
  }
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> unif(-1.0, 1.0);
  for (std::size_t v = 0; v < mesh.nodes.size(); ++v) {
    Eigen::Matrix<double, Dim, 1> offset;
    for (int d = 0; d < Dim; ++d) offset[d] = unif(gen);
    if (boundary.count(static_cast<int>(v)) || !std::isfinite(hmin[v])) continue;
    mesh.nodes[v] += fraction * hmin[v] * offset / std::sqrt(static_cast<double>(Dim));
  }
}

template Mesh merge<2>(const Mesh&, const Mesh&);
template Mesh3 merge<3>(const Mesh3&, const Mesh3&);
template void rename_boundary<2>(Mesh&, const std::string&, const std::string&);
template void rename_boundary<3>(Mesh3&, const std::string&, const std::string&);
template Mesh mirror<2>(const Mesh&, int, const std::string&);
template Mesh3 mirror<3>(const Mesh3&, int, const std::string&);
template void perturb_interior<2>(Mesh&, double, unsigned);
template void perturb_interior<3>(Mesh3&, double, unsigned);

}  // namespace contactrb::mesh
