#include "contactrb/hf/level_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/facet_tree.hpp"
#include "contactrb/contact/triangle_hit.hpp"

namespace contactrb::hf {

namespace {

// Barycentric coordinates of x in triangle (a, b, c) (non-degenerate: mesh::validate).
Eigen::Vector3d barycentric(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                            const Eigen::Vector2d& x) {
  const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
  const double l1 = ((b.x() - x.x()) * (c.y() - x.y()) - (c.x() - x.x()) * (b.y() - x.y())) / det;
  const double l2 = ((c.x() - x.x()) * (a.y() - x.y()) - (a.x() - x.x()) * (c.y() - x.y())) / det;
  return {l1, l2, 1.0 - l1 - l2};
}

// Barycentric coordinates of x in tetrahedron (a, b, c, d) (positive volume: mesh::validate).
Eigen::Vector4d barycentric(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                            const Eigen::Vector3d& d, const Eigen::Vector3d& x) {
  Eigen::Matrix3d J;
  J << b - a, c - a, d - a;
  const Eigen::Vector3d l = J.partialPivLu().solve(x - a);
  return {1.0 - l.sum(), l(0), l(1), l(2)};
}

double segment_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& x) {
  const Eigen::Vector2d e = b - a;
  const double t = std::clamp((x - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
  return (a + t * e - x).norm();
}

// Barycentric coordinates of x in cell `cell` and its distance to the cell (0 inside, to
// round-off: a coordinate above -1e-12 counts as inside): the boundary edges (2D) or faces (3D).
template <int Dim>
std::pair<Eigen::Matrix<double, Dim + 1, 1>, double> cell_hit(const mesh::SimplexMesh<Dim>& mesh, int cell,
                                                               const Eigen::Matrix<double, Dim, 1>& x) {
  const auto& v = mesh.cells()[static_cast<std::size_t>(cell)];
  const auto node = [&](int k) -> const Eigen::Matrix<double, Dim, 1>& {
    return mesh.nodes[static_cast<std::size_t>(v[static_cast<std::size_t>(k)])];
  };
  if constexpr (Dim == 2) {
    const Eigen::Vector3d l = barycentric(node(0), node(1), node(2), x);
    double d = 0.0;
    if (l.minCoeff() < -1e-12) {
      d = std::min({segment_distance(node(0), node(1), x), segment_distance(node(1), node(2), x),
                    segment_distance(node(2), node(0), x)});
    }
    return {l, d};
  } else {
    const Eigen::Vector4d l = barycentric(node(0), node(1), node(2), node(3), x);
    double d = 0.0;
    if (l.minCoeff() < -1e-12) {
      double d2 = std::numeric_limits<double>::infinity();
      for (const auto& f : mesh::kCellFacets<3>) d2 = std::min(d2, contact::closest_on_triangle(node(f[0]), node(f[1]), node(f[2]), 0, x).d2);
      d = std::sqrt(d2);
    }
    return {l, d};
  }
}

// The grid side giving about one cell per grid cell: the side of a cube (square) of the mean
// cell's measure times Dim! (a simplex of diameter h has measure about h^Dim / Dim!).
template <int Dim>
double grid_side(double measure, std::size_t cells) {
  if constexpr (Dim == 2) {
    return std::max(std::sqrt(2.0 * measure / static_cast<double>(cells)), 1e-300);
  } else {
    return std::max(std::cbrt(6.0 * measure / static_cast<double>(cells)), 1e-300);
  }
}

}  // namespace

template <int Dim>
SimplexLocator<Dim>::SimplexLocator(const mesh::SimplexMesh<Dim>& mesh, int body) : mesh_(&mesh) {
  std::vector<int> own;
  Point lo = Point::Constant(std::numeric_limits<double>::infinity());
  Point hi = -lo;
  double measure = 0.0;
  for (int t = 0; t < mesh.num_cells(); ++t) {
    if (mesh.body[static_cast<std::size_t>(t)] != body) continue;
    own.push_back(t);
    for (int v : mesh.cells()[static_cast<std::size_t>(t)]) {
      lo = lo.cwiseMin(mesh.nodes[static_cast<std::size_t>(v)]);
      hi = hi.cwiseMax(mesh.nodes[static_cast<std::size_t>(v)]);
    }
    measure += std::abs(mesh::signed_volume(mesh, t));
  }
  require(!own.empty(), "level transfer: body " + std::to_string(body) + " has no " +
                            mesh::SimplexNames<Dim>::cell + " in the coarse mesh");
  cell_ = grid_side<Dim>(measure, own.size());
  origin_ = lo;
  std::size_t total = 1;
  for (int a = 0; a < Dim; ++a) {
    n_[static_cast<std::size_t>(a)] = std::max(1, static_cast<int>(std::ceil((hi(a) - lo(a)) / cell_)));
    total *= static_cast<std::size_t>(n_[static_cast<std::size_t>(a)]);
  }
  // Counting pass then filling pass (CSR).
  start_.assign(total + 1, 0);
  auto for_cells = [&](int t, auto&& visit) {
    Point tlo = Point::Constant(std::numeric_limits<double>::infinity());
    Point thi = -tlo;
    for (int v : mesh.cells()[static_cast<std::size_t>(t)]) {
      tlo = tlo.cwiseMin(mesh.nodes[static_cast<std::size_t>(v)]);
      thi = thi.cwiseMax(mesh.nodes[static_cast<std::size_t>(v)]);
    }
    const std::array<int, Dim> g0 = grid_cell_of(tlo), g1 = grid_cell_of(thi);
    std::array<int, Dim> g = g0;
    if constexpr (Dim == 2) {
      for (g[1] = g0[1]; g[1] <= g1[1]; ++g[1]) {
        for (g[0] = g0[0]; g[0] <= g1[0]; ++g[0]) visit(grid_index(g));
      }
    } else {
      for (g[2] = g0[2]; g[2] <= g1[2]; ++g[2]) {
        for (g[1] = g0[1]; g[1] <= g1[1]; ++g[1]) {
          for (g[0] = g0[0]; g[0] <= g1[0]; ++g[0]) visit(grid_index(g));
        }
      }
    }
  };
  for (int t : own) for_cells(t, [&](std::size_t c) { ++start_[c + 1]; });
  std::partial_sum(start_.begin(), start_.end(), start_.begin());
  cells_.resize(static_cast<std::size_t>(start_.back()));
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int t : own) for_cells(t, [&](std::size_t c) { cells_[static_cast<std::size_t>(fill[c]++)] = t; });
}

template <int Dim>
std::array<int, Dim> SimplexLocator<Dim>::grid_cell_of(const Point& x) const {
  std::array<int, Dim> g{};
  for (int a = 0; a < Dim; ++a) {
    const int n = n_[static_cast<std::size_t>(a)];
    const double k = std::floor((x(a) - origin_(a)) / cell_);
    g[static_cast<std::size_t>(a)] = static_cast<int>(std::clamp(k, 0.0, static_cast<double>(n - 1)));
  }
  return g;
}

template <int Dim>
std::size_t SimplexLocator<Dim>::grid_index(const std::array<int, Dim>& g) const {
  std::size_t index = 0;
  for (int a = Dim - 1; a >= 0; --a) {
    index = index * static_cast<std::size_t>(n_[static_cast<std::size_t>(a)]) + static_cast<std::size_t>(g[static_cast<std::size_t>(a)]);
  }
  return index;
}

template <int Dim>
typename SimplexLocator<Dim>::Location SimplexLocator<Dim>::locate(const Point& x) const {
  require(x.allFinite(), "level transfer: a node position is not finite");
  const std::array<int, Dim> home = grid_cell_of(x);
  Location best;
  best.distance = std::numeric_limits<double>::infinity();
  auto visit_cell = [&](const std::array<int, Dim>& g) {
    const std::size_t c = grid_index(g);
    for (int k = start_[c]; k < start_[c + 1]; ++k) {
      const int t = cells_[static_cast<std::size_t>(k)];
      const auto [l, d] = cell_hit(*mesh_, t, x);
      if (d < best.distance) {
        best.cell = t;
        best.barycentric = l;
        best.distance = d;
      }
    }
  };
  // The grid cells at Chebyshev distance exactly r from `home`, inside the grid.
  auto visit_ring = [&](int r) {
    std::array<int, Dim> g{};
    const auto inside = [&](int a, int v) { return v >= 0 && v < n_[static_cast<std::size_t>(a)]; };
    const auto on_ring = [&] {
      int m = 0;
      for (int a = 0; a < Dim; ++a) m = std::max(m, std::abs(g[static_cast<std::size_t>(a)] - home[static_cast<std::size_t>(a)]));
      return m == r;
    };
    const int z0 = Dim == 3 ? home[Dim - 1] - r : 0, z1 = Dim == 3 ? home[Dim - 1] + r : 0;
    for (int z = z0; z <= z1; ++z) {
      if (Dim == 3 && !inside(Dim - 1, z)) continue;
      if constexpr (Dim == 3) g[2] = z;
      for (g[1] = home[1] - r; g[1] <= home[1] + r; ++g[1]) {
        if (!inside(1, g[1])) continue;
        for (g[0] = home[0] - r; g[0] <= home[0] + r; ++g[0]) {
          if (!inside(0, g[0]) || !on_ring()) continue;
          visit_cell(g);
        }
      }
    }
  };
  // A cell first met in ring r + 1 is at least r grid cells from x, so the search stops once the
  // best distance is within that.
  const int max_ring = *std::max_element(n_.begin(), n_.end());
  for (int r = 0; r <= max_ring; ++r) {
    visit_ring(r);
    if (best.distance == 0.0 || best.distance <= static_cast<double>(r) * cell_) break;
  }
  return best;
}

template class SimplexLocator<2>;
template class SimplexLocator<3>;

template <int Dim>
Eigen::VectorXd transfer_displacement(const mesh::SimplexMesh<Dim>& coarse, const Eigen::VectorXd& u_coarse,
                                      const mesh::SimplexMesh<Dim>& fine) {
  require(u_coarse.size() == coarse.num_dofs(), "level transfer: the coarse displacement has " +
                                                    std::to_string(u_coarse.size()) + " entries for " +
                                                    std::to_string(coarse.num_dofs()) + " DOFs");
  std::vector<int> node_body(static_cast<std::size_t>(fine.num_nodes()), -1);
  for (int t = 0; t < fine.num_cells(); ++t) {
    for (int v : fine.cells()[static_cast<std::size_t>(t)]) node_body[static_cast<std::size_t>(v)] = fine.body[static_cast<std::size_t>(t)];
  }
  const int bodies = fine.num_bodies();
  std::vector<SimplexLocator<Dim>> locators;
  for (int b = 0; b < bodies; ++b) locators.emplace_back(coarse, b);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(fine.num_dofs());
  for (int v = 0; v < fine.num_nodes(); ++v) {
    const int b = node_body[static_cast<std::size_t>(v)];
    require(b >= 0 && b < bodies, "level transfer: fine node " + std::to_string(v) + " belongs to no " +
                                      mesh::SimplexNames<Dim>::cell);
    const auto loc = locators[static_cast<std::size_t>(b)].locate(fine.nodes[static_cast<std::size_t>(v)]);
    const auto& cell = coarse.cells()[static_cast<std::size_t>(loc.cell)];
    for (int c = 0; c < Dim; ++c) {
      double value = 0.0;
      for (int k = 0; k <= Dim; ++k) value += loc.barycentric(k) * u_coarse(Dim * cell[static_cast<std::size_t>(k)] + c);
      u(Dim * v + c) = value;
    }
  }
  return u;
}

template Eigen::VectorXd transfer_displacement(const mesh::Mesh&, const Eigen::VectorXd&, const mesh::Mesh&);
template Eigen::VectorXd transfer_displacement(const mesh::Mesh3&, const Eigen::VectorXd&, const mesh::Mesh3&);

std::vector<double> row_arc_positions(const mesh::Mesh& mesh, const contact::ContactPair& pair,
                                      const contact::ContactQuadrature& quadrature) {
  const std::size_t S = pair.slave.size();
  require(S >= 2 && quadrature.W.cols() == static_cast<Eigen::Index>(S),
          "level transfer: the quadrature does not match the slave chain");
  std::vector<double> s(S, 0.0);
  for (std::size_t k = 1; k < S; ++k) {
    s[k] = s[k - 1] + (mesh.nodes[static_cast<std::size_t>(pair.slave[k])] - mesh.nodes[static_cast<std::size_t>(pair.slave[k - 1])]).norm();
  }
  const double length = s.back();
  require(length > 0.0, "level transfer: the slave chain has zero length");
  std::vector<double> rows(static_cast<std::size_t>(quadrature.W.rows()), 0.0);
  for (int r = 0; r < quadrature.W.outerSize(); ++r) {
    double sum = 0.0, weighted = 0.0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(quadrature.W, r); it; ++it) {
      sum += it.value();
      weighted += it.value() * s[static_cast<std::size_t>(it.col())];
    }
    require(sum > 0.0, "level transfer: constraint row " + std::to_string(r) + " has no quadrature weight");
    rows[static_cast<std::size_t>(r)] = weighted / sum / length;
  }
  return rows;
}

Eigen::VectorXd transfer_pressure(const mesh::Mesh& coarse, const contact::ContactPair& coarse_pair,
                                  const contact::ContactQuadrature& coarse_quadrature,
                                  const Eigen::VectorXd& lambda_coarse, const mesh::Mesh& fine,
                                  const contact::ContactPair& fine_pair,
                                  const contact::ContactQuadrature& fine_quadrature) {
  const std::vector<double> sc = row_arc_positions(coarse, coarse_pair, coarse_quadrature);
  require(lambda_coarse.size() == static_cast<Eigen::Index>(sc.size()),
          "level transfer: the coarse pressure has " + std::to_string(lambda_coarse.size()) + " entries for " +
              std::to_string(sc.size()) + " constraint rows");
  require(std::is_sorted(sc.begin(), sc.end()), "level transfer: the coarse rows are not ordered along the slave chain");
  const std::vector<double> sf = row_arc_positions(fine, fine_pair, fine_quadrature);
  Eigen::VectorXd lambda(static_cast<Eigen::Index>(sf.size()));
  for (std::size_t r = 0; r < sf.size(); ++r) {
    const double s = sf[r];
    const auto hi = std::upper_bound(sc.begin(), sc.end(), s);
    if (hi == sc.begin()) {
      lambda(static_cast<Eigen::Index>(r)) = lambda_coarse(0);
    } else if (hi == sc.end()) {
      lambda(static_cast<Eigen::Index>(r)) = lambda_coarse(lambda_coarse.size() - 1);
    } else {
      const auto k = static_cast<Eigen::Index>(hi - sc.begin());
      const double t = (s - sc[static_cast<std::size_t>(k - 1)]) / (sc[static_cast<std::size_t>(k)] - sc[static_cast<std::size_t>(k - 1)]);
      lambda(static_cast<Eigen::Index>(r)) = (1.0 - t) * lambda_coarse(k - 1) + t * lambda_coarse(k);
    }
  }
  return lambda;
}

Eigen::VectorXd transfer_pressure(const mesh::Mesh3& coarse, const contact::ContactPair3& coarse_pair,
                                  const contact::ContactQuadrature& coarse_quadrature,
                                  const Eigen::VectorXd& lambda_coarse, const mesh::Mesh3& fine,
                                  const contact::ContactPair3& /*fine_pair: its rows are fine_quadrature's*/,
                                  const contact::ContactQuadrature& fine_quadrature) {
  const std::vector<int>& rows_c = coarse_quadrature.center_node;
  require(lambda_coarse.size() == static_cast<Eigen::Index>(rows_c.size()),
          "level transfer: the coarse pressure has " + std::to_string(lambda_coarse.size()) + " entries for " +
              std::to_string(rows_c.size()) + " constraint rows");
  // The coarse row of each coarse slave node (one row per slave node in 3D).
  std::vector<int> row_of(static_cast<std::size_t>(coarse.num_nodes()), -1);
  for (std::size_t r = 0; r < rows_c.size(); ++r) row_of[static_cast<std::size_t>(rows_c[r])] = static_cast<int>(r);
  std::vector<contact::FacetTree<3>::Facet> faces;
  faces.reserve(coarse_pair.slave_faces.size());
  for (const mesh::Face& f : coarse_pair.slave_faces) {
    for (int v : f.vertices()) {
      require(row_of[static_cast<std::size_t>(v)] >= 0,
              "level transfer: coarse slave node " + std::to_string(v) + " carries no constraint row");
    }
    faces.push_back({coarse.nodes[static_cast<std::size_t>(f.a)], coarse.nodes[static_cast<std::size_t>(f.b)],
                     coarse.nodes[static_cast<std::size_t>(f.c)]});
  }
  require(!faces.empty(), "level transfer: the coarse slave surface has no triangle");
  const contact::FacetTree<3> tree(faces);
  std::vector<std::pair<int, double>> stack;
  const std::vector<int>& rows_f = fine_quadrature.center_node;
  Eigen::VectorXd lambda(static_cast<Eigen::Index>(rows_f.size()));
  for (std::size_t r = 0; r < rows_f.size(); ++r) {
    const Eigen::Vector3d& x = fine.nodes[static_cast<std::size_t>(rows_f[r])];
    const contact::TriangleHit hit = tree.nearest<contact::TriangleHit>(
        x,
        [&](int k, const Eigen::Vector3d& p) {
          const auto& f = faces[static_cast<std::size_t>(k)];
          return contact::closest_on_triangle(f[0], f[1], f[2], k, p);
        },
        [](const contact::TriangleHit& h) { return h.facet; }, stack);
    const std::array<int, 3> v = coarse_pair.slave_faces[static_cast<std::size_t>(hit.facet)].vertices();
    double value = 0.0;
    for (std::size_t k = 0; k < 3; ++k) value += hit.phi(static_cast<Eigen::Index>(k)) * lambda_coarse(row_of[static_cast<std::size_t>(v[k])]);
    lambda(static_cast<Eigen::Index>(r)) = value;
  }
  return lambda;
}

}  // namespace contactrb::hf
