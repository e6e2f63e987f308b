#include "contactrb/hf/level_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <string>

#include "contactrb/common/error.hpp"

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

double segment_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& x) {
  const Eigen::Vector2d e = b - a;
  const double t = std::clamp((x - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
  return (a + t * e - x).norm();
}

}  // namespace

TriangleLocator::TriangleLocator(const mesh::Mesh& mesh, int body) : mesh_(&mesh) {
  std::vector<int> own;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  double area = 0.0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    if (mesh.body[static_cast<std::size_t>(t)] != body) continue;
    own.push_back(t);
    for (int v : mesh.triangles[static_cast<std::size_t>(t)]) {
      lo = lo.cwiseMin(mesh.nodes[static_cast<std::size_t>(v)]);
      hi = hi.cwiseMax(mesh.nodes[static_cast<std::size_t>(v)]);
    }
    area += std::abs(mesh::signed_area(mesh, t));
  }
  require(!own.empty(), "level transfer: body " + std::to_string(body) + " has no triangle in the coarse mesh");
  // About one triangle per cell: the cell side is the mean triangle's diameter.
  cell_ = std::max(std::sqrt(2.0 * area / static_cast<double>(own.size())), 1e-300);
  origin_ = lo;
  nx_ = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / cell_)));
  // Counting pass then filling pass (CSR).
  start_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
  auto for_cells = [&](int t, auto&& visit) {
    Eigen::Vector2d tlo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector2d thi = -tlo;
    for (int v : mesh.triangles[static_cast<std::size_t>(t)]) {
      tlo = tlo.cwiseMin(mesh.nodes[static_cast<std::size_t>(v)]);
      thi = thi.cwiseMax(mesh.nodes[static_cast<std::size_t>(v)]);
    }
    int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
    cell_of(tlo, i0, j0);
    cell_of(thi, i1, j1);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) visit(static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i));
    }
  };
  for (int t : own) for_cells(t, [&](std::size_t c) { ++start_[c + 1]; });
  std::partial_sum(start_.begin(), start_.end(), start_.begin());
  triangles_.resize(static_cast<std::size_t>(start_.back()));
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int t : own) for_cells(t, [&](std::size_t c) { triangles_[static_cast<std::size_t>(fill[c]++)] = t; });
}

void TriangleLocator::cell_of(const Eigen::Vector2d& x, int& i, int& j) const {
  auto index = [&](double v, double o, int n) {
    const double k = std::floor((v - o) / cell_);
    return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(n - 1)));
  };
  i = index(x.x(), origin_.x(), nx_);
  j = index(x.y(), origin_.y(), ny_);
}

TriangleLocator::Location TriangleLocator::locate(const Eigen::Vector2d& x) const {
  require(x.allFinite(), "level transfer: a node position is not finite");
  int ci = 0, cj = 0;
  cell_of(x, ci, cj);
  Location best;
  best.distance = std::numeric_limits<double>::infinity();
  auto visit_cell = [&](int i, int j) {
    const std::size_t c = static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
    for (int k = start_[c]; k < start_[c + 1]; ++k) {
      const int t = triangles_[static_cast<std::size_t>(k)];
      const auto& tri = mesh_->triangles[static_cast<std::size_t>(t)];
      const Eigen::Vector2d& a = mesh_->nodes[static_cast<std::size_t>(tri[0])];
      const Eigen::Vector2d& b = mesh_->nodes[static_cast<std::size_t>(tri[1])];
      const Eigen::Vector2d& cc = mesh_->nodes[static_cast<std::size_t>(tri[2])];
      const Eigen::Vector3d l = barycentric(a, b, cc, x);
      double d = 0.0;
      if (l.minCoeff() < -1e-12) d = std::min({segment_distance(a, b, x), segment_distance(b, cc, x), segment_distance(cc, a, x)});
      if (d < best.distance) {
        best.triangle = t;
        best.barycentric = l;
        best.distance = d;
      }
    }
  };
  // Rings of cells around x's (clamped) cell: a triangle first met in ring r + 1 is at least
  // r cells from x, so the search stops once the best distance is within that.
  const int max_ring = std::max(nx_, ny_);
  for (int r = 0; r <= max_ring; ++r) {
    for (int j = cj - r; j <= cj + r; ++j) {
      if (j < 0 || j >= ny_) continue;
      for (int i = ci - r; i <= ci + r; ++i) {
        if (i < 0 || i >= nx_) continue;
        if (std::max(std::abs(i - ci), std::abs(j - cj)) != r) continue;
        visit_cell(i, j);
      }
    }
    if (best.distance == 0.0 || best.distance <= static_cast<double>(r) * cell_) break;
  }
  return best;
}

Eigen::VectorXd transfer_displacement(const mesh::Mesh& coarse, const Eigen::VectorXd& u_coarse,
                                      const mesh::Mesh& fine) {
  require(u_coarse.size() == coarse.num_dofs(), "level transfer: the coarse displacement has " +
                                                    std::to_string(u_coarse.size()) + " entries for " +
                                                    std::to_string(coarse.num_dofs()) + " DOFs");
  std::vector<int> node_body(static_cast<std::size_t>(fine.num_nodes()), -1);
  for (int t = 0; t < fine.num_triangles(); ++t) {
    for (int v : fine.triangles[static_cast<std::size_t>(t)]) node_body[static_cast<std::size_t>(v)] = fine.body[static_cast<std::size_t>(t)];
  }
  const int bodies = fine.num_bodies();
  std::vector<TriangleLocator> locators;
  for (int b = 0; b < bodies; ++b) locators.emplace_back(coarse, b);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(fine.num_dofs());
  for (int v = 0; v < fine.num_nodes(); ++v) {
    const int b = node_body[static_cast<std::size_t>(v)];
    require(b >= 0 && b < bodies, "level transfer: fine node " + std::to_string(v) + " belongs to no triangle");
    const TriangleLocator::Location loc = locators[static_cast<std::size_t>(b)].locate(fine.nodes[static_cast<std::size_t>(v)]);
    const auto& tri = coarse.triangles[static_cast<std::size_t>(loc.triangle)];
    for (int c = 0; c < 2; ++c) {
      double value = 0.0;
      for (int k = 0; k < 3; ++k) value += loc.barycentric(k) * u_coarse(2 * tri[static_cast<std::size_t>(k)] + c);
      u(2 * v + c) = value;
    }
  }
  return u;
}

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

}  // namespace contactrb::hf
