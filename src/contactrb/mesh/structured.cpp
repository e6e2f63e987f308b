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

Mesh merge(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  const int shift = a.num_nodes();
  m.nodes.insert(m.nodes.end(), b.nodes.begin(), b.nodes.end());
  for (const auto& tri : b.triangles) m.triangles.push_back({tri[0] + shift, tri[1] + shift, tri[2] + shift});
  m.body.insert(m.body.end(), b.body.begin(), b.body.end());
  for (const auto& [name, edges] : b.boundaries) {
    require(!m.has_boundary(name), "merge: both meshes have boundary group '" + name + "'");
    auto& dst = m.boundaries[name];
    for (const Edge& e : edges) dst.push_back({e.a + shift, e.b + shift});
  }
  return m;
}

void rename_boundary(Mesh& mesh, const std::string& from, const std::string& to) {
  auto edges = mesh.boundary(from);
  require(!mesh.has_boundary(to), "rename_boundary: group '" + to + "' already exists");
  mesh.boundaries.erase(from);
  mesh.boundaries[to] = std::move(edges);
}

void perturb_interior(Mesh& mesh, double fraction, unsigned seed) {
  // Boundary nodes: endpoints of edges that belong to exactly one triangle.
  std::map<std::pair<int, int>, int> count;
  for (const auto& tri : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      int u = tri[static_cast<std::size_t>(k)], v = tri[static_cast<std::size_t>((k + 1) % 3)];
      ++count[{std::min(u, v), std::max(u, v)}];
    }
  }
  std::vector<double> hmin(mesh.nodes.size(), INFINITY);
  std::set<int> boundary;
  for (const auto& [e, c] : count) {
    const double len = (mesh.nodes[static_cast<std::size_t>(e.first)] - mesh.nodes[static_cast<std::size_t>(e.second)]).norm();
    hmin[static_cast<std::size_t>(e.first)] = std::min(hmin[static_cast<std::size_t>(e.first)], len);
    hmin[static_cast<std::size_t>(e.second)] = std::min(hmin[static_cast<std::size_t>(e.second)], len);
    if (c == 1) {
      boundary.insert(e.first);
      boundary.insert(e.second);
    }
  }
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> unif(-1.0, 1.0);
  for (std::size_t v = 0; v < mesh.nodes.size(); ++v) {
    const double dx = unif(gen), dy = unif(gen);
    if (boundary.count(static_cast<int>(v)) || !std::isfinite(hmin[v])) continue;
    mesh.nodes[v] += fraction * hmin[v] * Eigen::Vector2d(dx, dy) / std::sqrt(2.0);
  }
}

}  // namespace contactrb::mesh
