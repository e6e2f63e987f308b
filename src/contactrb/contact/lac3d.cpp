#include "contactrb/contact/lac3d.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/facet_tree.hpp"
#include "contactrb/contact/master_surface.hpp"
#include "contactrb/contact/polygon_clip.hpp"
#include "contactrb/contact/triangle_hit.hpp"

namespace contactrb::contact {

namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

std::size_t sz(int i) { return static_cast<std::size_t>(i); }

// A triangle (slave or master) whose projection along d covers less than this fraction of its
// area is edge-on: it has no pieces (docs/contact.md, "LAC in three dimensions").
constexpr double kEdgeOn = 1e-6;
// The candidate box around the feet of a slave triangle is widened by this fraction of its
// longest edge: the projection along d_T and the closest-point feet differ by (distance) x
// (angle between d_T and the local master normal), a small part of an edge for any gap below
// the master's radius of curvature.
constexpr double kSearchMargin = 0.5;
// An uncovered part of a cell below this fraction of the cell's area is round-off of the
// clipping (a slave and a master edge on the same line), not a part beyond the rim.
constexpr double kUncoveredTolerance = 1e-12;
// Barycentric coordinates (vertex, other, other) of the centroid of a median dual cell.
constexpr double kCellCentroidVertex = 11.0 / 18.0, kCellCentroidOther = 7.0 / 36.0;

// The slave triangles as positions in pair.slave and, per position, the triangles around it.
struct SlaveStar {
  std::vector<std::array<int, 3>> tri;
  std::vector<int> start, adj;  // CSR: triangles at slave position s
};

SlaveStar slave_star(const mesh::Mesh3& mesh, const ContactPair3& pair) {
  const int S = static_cast<int>(pair.slave.size());
  const auto position = [&pair](int v) {
    const auto it = std::lower_bound(pair.slave.begin(), pair.slave.end(), v);
    require(it != pair.slave.end() && *it == v,
            "integrate_lac_rows: slave triangle node " + std::to_string(v) + " is not a slave node");
    return static_cast<int>(it - pair.slave.begin());
  };
  SlaveStar star;
  star.tri.reserve(pair.slave_faces.size());
  star.start.assign(sz(S + 1), 0);
  for (const mesh::Face& f : pair.slave_faces) {
    std::array<int, 3> t{};
    for (std::size_t i = 0; i < 3; ++i) {
      const int v = f.vertices()[i];
      require(v >= 0 && v < mesh.num_nodes(), "integrate_lac_rows: slave node " + std::to_string(v) +
                                                  " outside [0, " + std::to_string(mesh.num_nodes()) + ")");
      t[i] = position(v);
      ++star.start[sz(t[i] + 1)];
    }
    star.tri.push_back(t);
  }
  for (int s = 0; s < S; ++s) star.start[sz(s + 1)] += star.start[sz(s)];
  star.adj.resize(sz(star.start.back()));
  std::vector<int> next(star.start.begin(), star.start.end() - 1);
  for (std::size_t t = 0; t < star.tri.size(); ++t) {
    for (int s : star.tri[t]) star.adj[sz(next[sz(s)]++)] = static_cast<int>(t);
  }
  return star;
}

// A slave triangle seen along its direction d: a frame (e1, e2) of the plane normal to d, the
// projected deformed vertices and the slave barycentric coordinates as functions on the plane.
struct TriangleView {
  Vec3 d, e1, e2, origin;
  std::array<Vec2, 3> p;
  std::array<Affine2, 3> lambda;
  double area_ratio = 0.0;  // reference area / projected area
  bool edge_on = true;
  Vec2 project(const Vec3& x) const { return {(x - origin).dot(e1), (x - origin).dot(e2)}; }
};

// Which master triangles each slave triangle meets along its direction, and the pieces of its
// cells: the segmentation of the slave surface by the master surface.
class Segmentation {
 public:
  Segmentation(const mesh::Mesh3& mesh, const ContactPair3& pair, const PointwiseContact3& pointwise,
               const Eigen::VectorXd& w, SlaveStar star, const std::vector<char>& needed)
      : mesh_(mesh), pair_(pair), pointwise_(pointwise), w_(w), star_(std::move(star)),
        master_(deformed_master(mesh, pair, w)), tree_(master_facets(master_)) {
    direction_.assign(star_.tri.size(), Vec3::Zero());
    candidate_start_.assign(star_.tri.size() + 1, 0);
    for (std::size_t t = 0; t < star_.tri.size(); ++t) {
      if (needed[t] != 0) find_candidates(static_cast<int>(t));
      candidate_start_[t + 1] = static_cast<int>(candidate_.size());
    }
  }

  const SlaveStar& star() const { return star_; }
  const MasterSurface& master() const { return master_; }

  Vec3 reference(int slave_position) const { return mesh_.nodes[sz(pair_.slave[sz(slave_position)])]; }
  Vec3 deformed(int slave_position) const {
    const int v = pair_.slave[sz(slave_position)];
    return mesh_.nodes[sz(v)] + w_.segment<3>(3 * v);
  }
  double reference_area(int t) const {
    const auto& s = star_.tri[sz(t)];
    return 0.5 * (reference(s[1]) - reference(s[0])).cross(reference(s[2]) - reference(s[0])).norm();
  }

  TriangleView view(int t) const {
    const auto& s = star_.tri[sz(t)];
    TriangleView v;
    v.d = direction_[sz(t)];
    const std::array<Vec3, 3> x{deformed(s[0]), deformed(s[1]), deformed(s[2])};
    int axis = 0;
    v.d.cwiseAbs().minCoeff(&axis);
    v.e1 = Vec3::Unit(axis).cross(v.d).normalized();
    v.e2 = v.d.cross(v.e1);
    v.origin = (x[0] + x[1] + x[2]) / 3.0;
    for (std::size_t i = 0; i < 3; ++i) v.p[i] = v.project(x[i]);
    const double projected = 0.5 * std::abs(cross2(v.p[1] - v.p[0], v.p[2] - v.p[0]));
    const double deformed_area = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
    v.edge_on = !(projected > kEdgeOn * deformed_area);
    if (v.edge_on) return v;
    v.lambda = barycentric_functions(v.p);
    v.area_ratio = reference_area(t) / projected;
    return v;
  }

  // The median dual cell of vertex a: the vertex, the midpoint of an edge, the centroid, the
  // midpoint of the other edge.
  static Polygon2 cell(const TriangleView& v, int a) {
    const Vec2& pa = v.p[sz(a)];
    const Vec2& pb = v.p[sz((a + 1) % 3)];
    const Vec2& pc = v.p[sz((a + 2) % 3)];
    Polygon2 c;
    c.push(pa);
    c.push(0.5 * (pa + pb));
    c.push((pa + pb + pc) / 3.0);
    c.push(0.5 * (pa + pc));
    return c;
  }

  // visit(piece, master triangle f, its barycentric functions mu) for every non-empty piece of
  // `cell` of slave triangle t.
  template <class Visit>
  void for_each_piece(int t, const TriangleView& v, const Polygon2& cell, Visit&& visit) const {
    Vec2 lo = cell[0], hi = cell[0];
    for (int i = 1; i < cell.n; ++i) {
      lo = lo.cwiseMin(cell[i]);
      hi = hi.cwiseMax(cell[i]);
    }
    for (int k = candidate_start_[sz(t)]; k < candidate_start_[sz(t + 1)]; ++k) {
      const int f = candidate_[sz(k)];
      const auto& face = master_.face[sz(f)];
      const std::array<Vec2, 3> q{v.project(y(face[0])), v.project(y(face[1])), v.project(y(face[2]))};
      // Disjoint boxes: no piece (most candidates of a cell; the clipping below is the cost).
      const Vec2 qlo = q[0].cwiseMin(q[1]).cwiseMin(q[2]), qhi = q[0].cwiseMax(q[1]).cwiseMax(q[2]);
      if ((qlo.array() > hi.array()).any() || (lo.array() > qhi.array()).any()) continue;
      const std::array<Affine2, 3> mu = barycentric_functions(q);
      Polygon2 piece = cell;
      for (const Affine2& m : mu) piece = clip(piece, m);
      if (piece.n >= 3) visit(piece, f, mu);
    }
  }

  // Distance from a deformed point to the deformed master surface.
  double distance_to_master(const Vec3& x) const {
    const auto closest = [this](int f, const Vec3& p) {
      const auto& t = master_.face[sz(f)];
      return closest_on_triangle(y(t[0]), y(t[1]), y(t[2]), f, p);
    };
    const auto index = [](const TriangleHit& h) { return h.facet; };
    return std::sqrt(tree_.nearest<TriangleHit>(x, closest, index, nearest_stack_).d2);
  }

 private:
  const Vec3& y(int j) const { return master_.y[sz(j)]; }

  static std::vector<FacetTree<3>::Facet> master_facets(const MasterSurface& m) {
    std::vector<FacetTree<3>::Facet> facets;
    facets.reserve(m.face.size());
    for (const auto& t : m.face) facets.push_back({m.y[sz(t[0])], m.y[sz(t[1])], m.y[sz(t[2])]});
    return facets;
  }

  // d_T (the normalized sum of the vertices' n2; minus the slave normal if it vanishes) and the
  // master triangles facing d_T whose boxes meet the box of the feet of T's vertices (closest
  // points and points along d_T), widened by kSearchMargin of T's longest edge.
  void find_candidates(int t) {
    const auto& s = star_.tri[sz(t)];
    const std::array<Vec3, 3> x{deformed(s[0]), deformed(s[1]), deformed(s[2])};
    Vec3 d = Vec3::Zero();
    for (int i : s) d += pointwise_.projection[sz(i)].normal;
    if (!(d.norm() > 0.0)) d = -(x[1] - x[0]).cross(x[2] - x[0]);
    d.normalize();
    direction_[sz(t)] = d;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    double longest = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
      const SlaveProjection3& p = pointwise_.projection[sz(s[i])];
      const auto& face = master_.face[sz(p.facet)];
      const Vec3 foot = p.phi(0) * y(face[0]) + p.phi(1) * y(face[1]) + p.phi(2) * y(face[2]);
      const Vec3 along = x[i] - (x[i] - foot).dot(d) * d;
      lo = lo.cwiseMin(foot).cwiseMin(along);
      hi = hi.cwiseMax(foot).cwiseMax(along);
      longest = std::max(longest, (x[(i + 1) % 3] - x[i]).norm());
    }
    const Vec3 margin = Vec3::Constant(kSearchMargin * longest);
    found_.clear();
    tree_.overlapping(lo - margin, hi + margin, found_, box_stack_);
    std::sort(found_.begin(), found_.end());
    for (int f : found_) {
      if (master_.normal[sz(f)].dot(d) > kEdgeOn) candidate_.push_back(f);
    }
  }

  const mesh::Mesh3& mesh_;
  const ContactPair3& pair_;
  const PointwiseContact3& pointwise_;
  const Eigen::VectorXd& w_;
  SlaveStar star_;
  MasterSurface master_;
  FacetTree<3> tree_;
  std::vector<Vec3> direction_;
  std::vector<int> candidate_start_, candidate_;
  std::vector<int> found_, box_stack_;
  mutable std::vector<std::pair<int, double>> nearest_stack_;
};

// One row of K (as mesh node -> coefficient vector) and g.
struct RowAccumulator {
  std::vector<std::pair<int, Vec3>> entries;
  double g = 0.0;
  void add(int node, const Vec3& v) {
    for (auto& [n, value] : entries) {
      if (n == node) {
        value += v;
        return;
      }
    }
    entries.emplace_back(node, v);
  }
  void clear() {
    entries.clear();
    g = 0.0;
  }
};

// The slave point at barycentric coordinates lambda of triangle t, deformed.
Vec3 deformed_point(const Segmentation& seg, int t, const Vec3& lambda) {
  const auto& s = seg.star().tri[sz(t)];
  return lambda(0) * seg.deformed(s[0]) + lambda(1) * seg.deformed(s[1]) + lambda(2) * seg.deformed(s[2]);
}

Vec3 at(const std::array<Affine2, 3>& f, const Vec2& p) { return {f[0](p), f[1](p), f[2](p)}; }

// int over one piece of k(w; .) and g(w), added to `row` (the rule of lac3d.hpp).
void integrate_piece(const mesh::Mesh3& mesh, const ContactPair3& pair, const Segmentation& seg, int t,
                     const TriangleView& v, const Polygon2& piece, int f, const std::array<Affine2, 3>& mu,
                     RowAccumulator& row) {
  const auto& s = seg.star().tri[sz(t)];
  const auto& face = seg.master().face[sz(f)];
  const std::array<Vec3, 3> Xs{seg.reference(s[0]), seg.reference(s[1]), seg.reference(s[2])};
  std::array<Vec3, 3> Xm;
  for (std::size_t j = 0; j < 3; ++j) Xm[j] = mesh.nodes[sz(pair.master[sz(face[j])])];
  std::array<Vec3, 3> slave_coef{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}, master_coef = slave_coef;
  for_each_quadrature_point(piece, [&](const Vec2& p, double weight) {
    const double c = weight * v.area_ratio;
    const Vec3 lambda = at(v.lambda, p), phi = at(mu, p);
    const Vec3 n2 = seg.master().normal_at(f, phi);
    const Vec3 X = lambda(0) * Xs[0] + lambda(1) * Xs[1] + lambda(2) * Xs[2];
    const Vec3 rho = phi(0) * Xm[0] + phi(1) * Xm[1] + phi(2) * Xm[2];
    row.g += c * (X - rho).dot(n2);  // (28)
    for (std::size_t i = 0; i < 3; ++i) {  // (27)
      slave_coef[i] -= c * lambda(static_cast<Eigen::Index>(i)) * n2;
      master_coef[i] += c * phi(static_cast<Eigen::Index>(i)) * n2;
    }
  });
  for (std::size_t i = 0; i < 3; ++i) {
    row.add(pair.slave[sz(s[i])], slave_coef[i]);
    row.add(pair.master[sz(face[i])], master_coef[i]);
  }
}

// Cell a of slave triangle t: its pieces, and the uncovered rest (partial coverage rule).
void integrate_cell(const mesh::Mesh3& mesh, const ContactPair3& pair, const Segmentation& seg, int t, int a,
                    RowAccumulator& row) {
  const TriangleView v = seg.view(t);
  if (v.edge_on) {  // no piece: the whole cell is uncovered
    Vec3 centroid = Vec3::Constant(kCellCentroidOther);
    centroid(a) = kCellCentroidVertex;
    row.g += seg.reference_area(t) / 3.0 * seg.distance_to_master(deformed_point(seg, t, centroid));
    return;
  }
  const Polygon2 cell = Segmentation::cell(v, a);
  PolygonMoments covered;
  seg.for_each_piece(t, v, cell, [&](const Polygon2& piece, int f, const std::array<Affine2, 3>& mu) {
    const PolygonMoments m = moments(piece);
    covered.area += m.area;
    covered.moment += m.moment;
    integrate_piece(mesh, pair, seg, t, v, piece, f, mu, row);
  });
  const PolygonMoments whole = moments(cell);
  const double uncovered = whole.area - covered.area;
  if (!(uncovered > kUncoveredTolerance * whole.area)) return;
  const Vec2 centroid = (whole.moment - covered.moment) / uncovered;
  row.g += v.area_ratio * uncovered * seg.distance_to_master(deformed_point(seg, t, at(v.lambda, centroid)));
}

void check_inputs(const mesh::Mesh3& mesh, const ContactPair3& pair, const ContactQuadrature& quadrature,
                  const PointwiseContact3& pointwise, const Eigen::VectorXd& w) {
  const auto S = static_cast<Eigen::Index>(pair.slave.size());
  require(quadrature.discretization == Discretization::LAC && quadrature.W.rows() == S && quadrature.W.cols() == S,
          "integrate_lac_rows: the quadrature is '" + std::string(to_string(quadrature.discretization)) + "', " +
              std::to_string(quadrature.W.rows()) + " x " + std::to_string(quadrature.W.cols()) + ", but " +
              std::to_string(S) + " slave nodes need the " + std::to_string(S) + " x " + std::to_string(S) +
              " 'lac' quadrature");
  require(static_cast<Eigen::Index>(pointwise.projection.size()) == S,
          "integrate_lac_rows: " + std::to_string(pointwise.projection.size()) + " projections for " +
              std::to_string(S) + " slave nodes");
  require(w.size() == mesh.num_dofs(), "integrate_lac_rows: displacement has size " + std::to_string(w.size()) +
                                           " but the mesh has " + std::to_string(mesh.num_dofs()) + " DOFs");
  require(w.allFinite(), "integrate_lac_rows: the displacement has a non-finite entry");
  require(!pair.master_faces.empty(), "integrate_lac_rows: the master surface has no triangle");
}

// The slave triangles around the rows marked in `wanted`, after checking that their vertices
// were projected.
std::vector<char> needed_triangles(const SlaveStar& star, const std::vector<char>& wanted,
                                   const PointwiseContact3& pointwise) {
  std::vector<char> needed(star.tri.size(), 0);
  for (std::size_t r = 0; r < wanted.size(); ++r) {
    if (wanted[r] == 0) continue;
    for (int k = star.start[r]; k < star.start[r + 1]; ++k) {
      const int t = star.adj[sz(k)];
      needed[sz(t)] = 1;
      for (int s : star.tri[sz(t)]) {
        require(pointwise.projection[sz(s)].facet >= 0, "integrate_lac_rows: row " + std::to_string(r) +
                                                             " needs slave position " + std::to_string(s) +
                                                             ", which was not projected");
      }
    }
  }
  return needed;
}

}  // namespace

ConstraintRows integrate_lac_rows(const mesh::Mesh3& mesh, const ContactPair3& pair,
                                  const ContactQuadrature& quadrature, const PointwiseContact3& pointwise,
                                  const Eigen::VectorXd& w) {
  std::vector<int> all(pair.slave.size());
  for (std::size_t r = 0; r < all.size(); ++r) all[r] = static_cast<int>(r);
  return integrate_lac_rows(mesh, pair, quadrature, pointwise, w, all);
}

ConstraintRows integrate_lac_rows(const mesh::Mesh3& mesh, const ContactPair3& pair,
                                  const ContactQuadrature& quadrature, const PointwiseContact3& pointwise,
                                  const Eigen::VectorXd& w, std::span<const int> rows) {
  check_inputs(mesh, pair, quadrature, pointwise, w);
  const int R = static_cast<int>(pair.slave.size());
  std::vector<char> wanted(sz(R), 0);
  for (const int r : rows) {
    require(r >= 0 && r < R, "integrate_lac_rows: row " + std::to_string(r) + " outside [0, " + std::to_string(R) + ")");
    wanted[sz(r)] = 1;
  }
  SlaveStar star = slave_star(mesh, pair);
  const std::vector<char> needed = needed_triangles(star, wanted, pointwise);
  const Segmentation seg(mesh, pair, pointwise, w, std::move(star), needed);

  // The rows come in order: build the compressed row storage directly.
  std::vector<int> outer(sz(R + 1), 0), inner;
  std::vector<double> values;
  ConstraintRows out;
  out.g = Eigen::VectorXd::Zero(R);
  RowAccumulator row;
  for (int r = 0; r < R; ++r) {
    outer[sz(r)] = static_cast<int>(inner.size());
    if (wanted[sz(r)] == 0) continue;
    row.clear();
    for (int k = seg.star().start[sz(r)]; k < seg.star().start[sz(r + 1)]; ++k) {
      const int t = seg.star().adj[sz(k)];
      const auto& s = seg.star().tri[sz(t)];
      const int a = static_cast<int>(std::find(s.begin(), s.end(), r) - s.begin());
      integrate_cell(mesh, pair, seg, t, a, row);
    }
    std::sort(row.entries.begin(), row.entries.end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& [node, value] : row.entries) {
      for (int c = 0; c < 3; ++c) {
        if (value(c) == 0.0) continue;
        inner.push_back(3 * node + c);
        values.push_back(value(c));
      }
    }
    out.g(r) = row.g;
  }
  outer[sz(R)] = static_cast<int>(inner.size());
  out.K = Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor>>(
      R, mesh.num_dofs(), static_cast<Eigen::Index>(inner.size()), outer.data(), inner.data(), values.data());
  return out;
}

std::vector<int> lac_slave_positions(const ContactPair3& pair, std::span<const int> rows) {
  // Positions without the mesh: the slave faces hold mesh nodes, pair.slave is sorted.
  const int S = static_cast<int>(pair.slave.size());
  const auto position = [&pair](int v) {
    const auto it = std::lower_bound(pair.slave.begin(), pair.slave.end(), v);
    require(it != pair.slave.end() && *it == v,
            "lac_slave_positions: slave triangle node " + std::to_string(v) + " is not a slave node");
    return static_cast<int>(it - pair.slave.begin());
  };
  std::vector<char> wanted(sz(S), 0);
  for (const int r : rows) {
    require(r >= 0 && r < S, "lac_slave_positions: row " + std::to_string(r) + " outside [0, " + std::to_string(S) + ")");
    wanted[sz(r)] = 1;
  }
  std::vector<int> positions;
  for (const mesh::Face& f : pair.slave_faces) {
    std::array<int, 3> t{position(f.a), position(f.b), position(f.c)};
    if (wanted[sz(t[0])] == 0 && wanted[sz(t[1])] == 0 && wanted[sz(t[2])] == 0) continue;
    positions.insert(positions.end(), t.begin(), t.end());
  }
  std::sort(positions.begin(), positions.end());
  positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
  return positions;
}

LacCoverage3 lac_coverage(const mesh::Mesh3& mesh, const ContactPair3& pair, const PointwiseContact3& pointwise,
                          const Eigen::VectorXd& w) {
  const auto S = static_cast<Eigen::Index>(pair.slave.size());
  require(static_cast<Eigen::Index>(pointwise.projection.size()) == S && w.size() == mesh.num_dofs() &&
              w.allFinite() && !pair.master_faces.empty(),
          "lac_coverage: the projections, the displacement or the master surface do not match the pair");
  SlaveStar star = slave_star(mesh, pair);
  const std::vector<char> needed = needed_triangles(star, std::vector<char>(sz(static_cast<int>(S)), 1), pointwise);
  const Segmentation seg(mesh, pair, pointwise, w, std::move(star), needed);
  const int T = static_cast<int>(seg.star().tri.size());
  LacCoverage3 out;
  out.triangle_area = Eigen::VectorXd::Zero(T);
  out.covered_area = Eigen::VectorXd::Zero(T);
  out.row_covered = Eigen::VectorXd::Zero(S);
  for (int t = 0; t < T; ++t) {
    out.triangle_area(t) = seg.reference_area(t);
    const TriangleView v = seg.view(t);
    if (v.edge_on) continue;
    for (int a = 0; a < 3; ++a) {
      double area = 0.0;
      seg.for_each_piece(t, v, Segmentation::cell(v, a),
                         [&area](const Polygon2& piece, int, const std::array<Affine2, 3>&) { area += moments(piece).area; });
      out.covered_area(t) += v.area_ratio * area;
      out.row_covered(seg.star().tri[sz(t)][sz(a)]) += v.area_ratio * area;
    }
  }
  return out;
}

}  // namespace contactrb::contact
