#include "contactrb/hf/level_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/facet_tree.hpp"
#include "contactrb/contact/segment_hit.hpp"
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

// A cell counts as containing x when its barycentric coordinates are all above -kInsideRoundOff
// (a fine node on a coarse facet, to round-off).
constexpr double kInsideRoundOff = 1e-12;

// Barycentric coordinates of x in cell `cell` (extrapolated outside it).
template <int Dim>
Eigen::Matrix<double, Dim + 1, 1> cell_barycentric(const mesh::SimplexMesh<Dim>& mesh, int cell,
                                                   const Eigen::Matrix<double, Dim, 1>& x) {
  const auto& v = mesh.cells()[static_cast<std::size_t>(cell)];
  const auto node = [&](int k) -> const Eigen::Matrix<double, Dim, 1>& {
    return mesh.nodes[static_cast<std::size_t>(v[static_cast<std::size_t>(k)])];
  };
  if constexpr (Dim == 2) {
    return barycentric(node(0), node(1), node(2), x);
  } else {
    return barycentric(node(0), node(1), node(2), node(3), x);
  }
}

// The closest point of x on a boundary facet: an edge in 2D, a triangle in 3D.
contact::SegmentHit closest_on_facet(const std::array<Eigen::Vector2d, 2>& f, int k, const Eigen::Vector2d& x) {
  return contact::closest_on_segment(f[0], f[1], k, x);
}
contact::TriangleHit closest_on_facet(const std::array<Eigen::Vector3d, 3>& f, int k, const Eigen::Vector3d& x) {
  return contact::closest_on_triangle(f[0], f[1], f[2], k, x);
}
int facet_index(const contact::SegmentHit& h) { return h.segment; }
int facet_index(const contact::TriangleHit& h) { return h.facet; }

// The boundary facets of the cells `cells` (the facets of exactly one of them) as (cell, local
// facet of mesh::kCellFacets), ordered by cell then local facet: among equally near facets the
// locator takes the lowest-numbered cell.
template <int Dim>
std::vector<std::pair<int, int>> boundary_facets(const mesh::SimplexMesh<Dim>& mesh, const std::vector<int>& cells) {
  struct Entry {
    std::array<int, Dim> key;  // sorted vertices
    int cell, local;
  };
  std::vector<Entry> entries;
  entries.reserve(cells.size() * (Dim + 1));
  for (int t : cells) {
    const auto& cell = mesh.cells()[static_cast<std::size_t>(t)];
    for (int k = 0; k <= Dim; ++k) {
      Entry e{{}, t, k};
      for (std::size_t j = 0; j < static_cast<std::size_t>(Dim); ++j) {
        e.key[j] = cell[static_cast<std::size_t>(mesh::kCellFacets<Dim>[static_cast<std::size_t>(k)][j])];
      }
      std::sort(e.key.begin(), e.key.end());
      entries.push_back(e);
    }
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.key < b.key; });
  std::vector<std::pair<int, int>> facets;
  for (std::size_t i = 0; i < entries.size();) {
    std::size_t j = i + 1;
    while (j < entries.size() && entries[j].key == entries[i].key) ++j;
    if (j == i + 1) facets.emplace_back(entries[i].cell, entries[i].local);
    i = j;
  }
  std::sort(facets.begin(), facets.end());
  return facets;
}

}  // namespace

template <int Dim>
struct SimplexLocator<Dim>::Search {
  using CellTree = contact::FacetTree<Dim, Dim + 1>;
  using BoundaryTree = contact::FacetTree<Dim>;
  std::vector<int> cells;  // the body's cells, ascending: entry k of cell_tree is cells[k]
  CellTree cell_tree;
  std::vector<int> facet_cell;  // the cell of entry k of boundary_tree
  BoundaryTree boundary_tree;

  // boundary: boundary_facets(mesh, own).
  Search(const mesh::SimplexMesh<Dim>& mesh, std::vector<int> own, const std::vector<std::pair<int, int>>& boundary)
      : cells(std::move(own)),
        cell_tree(cell_simplices(mesh, cells)),
        facet_cell(boundary.size()),
        boundary_tree(facet_simplices(mesh, boundary)) {
    for (std::size_t k = 0; k < boundary.size(); ++k) facet_cell[k] = boundary[k].first;
  }

  static std::vector<typename CellTree::Facet> cell_simplices(const mesh::SimplexMesh<Dim>& mesh,
                                                              const std::vector<int>& cells) {
    std::vector<typename CellTree::Facet> simplices;
    simplices.reserve(cells.size());
    for (int t : cells) {
      const auto& cell = mesh.cells()[static_cast<std::size_t>(t)];
      typename CellTree::Facet s;
      for (std::size_t j = 0; j <= static_cast<std::size_t>(Dim); ++j) s[j] = mesh.nodes[static_cast<std::size_t>(cell[j])];
      simplices.push_back(s);
    }
    return simplices;
  }

  static std::vector<typename BoundaryTree::Facet> facet_simplices(const mesh::SimplexMesh<Dim>& mesh,
                                                                   const std::vector<std::pair<int, int>>& boundary) {
    std::vector<typename BoundaryTree::Facet> facets;
    facets.reserve(boundary.size());
    for (const auto& [t, k] : boundary) {
      const auto& cell = mesh.cells()[static_cast<std::size_t>(t)];
      const auto& local = mesh::kCellFacets<Dim>[static_cast<std::size_t>(k)];
      typename BoundaryTree::Facet f;
      for (std::size_t j = 0; j < static_cast<std::size_t>(Dim); ++j) {
        f[j] = mesh.nodes[static_cast<std::size_t>(cell[static_cast<std::size_t>(local[j])])];
      }
      facets.push_back(f);
    }
    return facets;
  }
};

template <int Dim>
SimplexLocator<Dim>::SimplexLocator(const mesh::SimplexMesh<Dim>& mesh, int body) : mesh_(&mesh) {
  std::vector<int> own;
  for (int t = 0; t < mesh.num_cells(); ++t) {
    if (mesh.body[static_cast<std::size_t>(t)] == body) own.push_back(t);
  }
  require(!own.empty(), "level transfer: body " + std::to_string(body) + " has no " +
                            mesh::SimplexNames<Dim>::cell + " in the coarse mesh");
  const std::vector<std::pair<int, int>> boundary = boundary_facets(mesh, own);
  search_ = std::make_unique<const Search>(mesh, std::move(own), boundary);
}

template <int Dim>
SimplexLocator<Dim>::~SimplexLocator() = default;
template <int Dim>
SimplexLocator<Dim>::SimplexLocator(SimplexLocator&&) noexcept = default;
template <int Dim>
SimplexLocator<Dim>& SimplexLocator<Dim>::operator=(SimplexLocator&&) noexcept = default;

template <int Dim>
typename SimplexLocator<Dim>::Location SimplexLocator<Dim>::locate(const Point& x) const {
  require(x.allFinite(), "level transfer: a node position is not finite");
  const Search& s = *search_;
  // Inside: the cells whose box holds x, the lowest-numbered containing one.
  std::vector<int> candidates, stack;
  s.cell_tree.overlapping(x, x, candidates, stack);
  std::sort(candidates.begin(), candidates.end());
  for (int k : candidates) {
    const int cell = s.cells[static_cast<std::size_t>(k)];
    const Barycentric l = cell_barycentric(*mesh_, cell, x);
    if (l.minCoeff() >= -kInsideRoundOff) return {cell, l, 0.0};
  }
  // Outside: the nearest point of the body is on its boundary, so a nearest cell is the cell of
  // the nearest boundary facet.
  using Hit = decltype(closest_on_facet(s.boundary_tree.facet(0), 0, x));
  std::vector<std::pair<int, double>> queue;
  const Hit hit = s.boundary_tree.template nearest<Hit>(
      x, [&s](int k, const Point& p) { return closest_on_facet(s.boundary_tree.facet(k), k, p); },
      [](const Hit& h) { return facet_index(h); }, queue);
  const int cell = s.facet_cell[static_cast<std::size_t>(facet_index(hit))];
  return {cell, cell_barycentric(*mesh_, cell, x), std::sqrt(hit.d2)};
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
