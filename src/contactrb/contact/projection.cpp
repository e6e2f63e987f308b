#include "contactrb/contact/projection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/lac3d.hpp"
#include "contactrb/contact/lac_integration.hpp"
#include "contactrb/contact/master_polyline.hpp"
#include "contactrb/contact/facet_tree.hpp"
#include "contactrb/contact/master_surface.hpp"
#include "contactrb/contact/segment_hit.hpp"
#include "contactrb/contact/triangle_hit.hpp"

namespace contactrb::contact {

namespace {

using Vec2 = Eigen::Vector2d;

// Segments per tree leaf: small enough to prune well, large enough to keep the tree shallow.
constexpr int kLeafSegments = 8;
// Relative slack on the capsule lower bound of a tree node, far above the round-off of the
// distances it combines (~1e-15 relative), so pruning never drops the exact answer.
constexpr double kBoundSlack = 1e-9;

using Vec3 = Eigen::Vector3d;

template <int Dim>
typename mesh::SimplexMesh<Dim>::Point position(const mesh::SimplexMesh<Dim>& mesh, const Eigen::VectorXd& w, int node) {
  return mesh.nodes[static_cast<std::size_t>(node)] + w.segment<Dim>(Dim * node);
}

SegmentHit closest_on_segment(const MasterPolyline& m, int k, const Vec2& x) {
  return contact::closest_on_segment(m.y[static_cast<std::size_t>(k)], m.y[static_cast<std::size_t>(k + 1)], k, x);
}

// Lexicographic order on (squared distance, segment index): the answer of every search.
bool better(const SegmentHit& h, const SegmentHit& best) {
  return h.d2 < best.d2 || (h.d2 == best.d2 && h.segment < best.segment);
}

// Increasing k: the lowest index wins a tie. Only (d2, k) is carried through the loop (the
// hit is recomputed once at the end) so that it stays in registers.
SegmentHit search_all_pairs(const MasterPolyline& m, const Vec2& x) {
  double best_d2 = std::numeric_limits<double>::infinity();
  int best = -1;
  for (int k = 0; k < m.num_segments(); ++k) {
    const double d2 = closest_on_segment(m, k, x).d2;
    if (d2 < best_d2) {
      best_d2 = d2;
      best = k;
    }
  }
  return best < 0 ? SegmentHit{} : closest_on_segment(m, best, x);
}

double point_segment_distance2(const Vec2& x, const Vec2& a, const Vec2& b) {
  const Vec2 e = b - a;
  const double ee = e.squaredNorm();
  const double t = ee > 0.0 ? std::clamp((x - a).dot(e) / ee, 0.0, 1.0) : 0.0;
  return (x - (a + t * e)).squaredNorm();
}

// Bounding-volume tree over index ranges of the master chain. Consecutive segments of a chain
// are neighbours in space, so splitting the index range in halves gives tight volumes without
// any sorting (build O(M log M)). Each node bounds its piece of polyline twice: by its
// axis-aligned box (exact in floating point, see closest_on_segment) and by a capsule around
// its chord (first to last vertex, radius = largest vertex distance to the chord). On a
// curved master the capsule is far tighter (its radius shrinks like the square of the piece
// length) and keeps the nodes visited per query about logarithmic even for slave nodes far
// from the master; with boxes alone they grow like sqrt(M).
class SegmentTree {
 public:
  explicit SegmentTree(const MasterPolyline& m) : m_(m) {
    nodes_.reserve(static_cast<std::size_t>(2 * (m.num_segments() / kLeafSegments + 1)));
    build(0, m.num_segments());
  }

  // stack: scratch space (tree node, squared distance to its box), reused across queries.
  SegmentHit nearest(const Vec2& x, std::vector<std::pair<int, double>>& stack) const {
    SegmentHit best;
    stack.clear();
    stack.emplace_back(0, lower_bound2(nodes_.front(), x));
    while (!stack.empty()) {
      const auto [id, lb] = stack.back();
      stack.pop_back();
      // Prune only when strictly farther: an equally distant segment with a lower index
      // must still win the tie, exactly as in search_all_pairs.
      if (lb > best.d2) continue;  // lb: lower_bound2 of the node
      const TreeNode& n = nodes_[static_cast<std::size_t>(id)];
      if (n.left < 0) {
        for (int k = n.lo; k < n.hi; ++k) {
          const SegmentHit h = closest_on_segment(m_, k, x);
          if (better(h, best)) best = h;
        }
        continue;
      }
      const double dl = lower_bound2(nodes_[static_cast<std::size_t>(n.left)], x);
      const double dr = lower_bound2(nodes_[static_cast<std::size_t>(n.right)], x);
      // Nearer child on top of the stack, visited first.
      if (dl <= dr) {
        stack.emplace_back(n.right, dr);
        stack.emplace_back(n.left, dl);
      } else {
        stack.emplace_back(n.left, dl);
        stack.emplace_back(n.right, dr);
      }
    }
    return best;
  }

 private:
  struct TreeNode {
    Vec2 min, max;        // bounding box of vertices lo..hi
    double radius = 0.0;  // capsule: largest distance of vertices lo..hi to chord (y_lo, y_hi)
    int lo = 0, hi = 0;   // segments [lo, hi)
    int left = -1, right = -1;
  };

  // Lower bound of the squared distance from x to any point of the node's polyline piece.
  double lower_bound2(const TreeNode& n, const Vec2& x) const {
    const double box = (x - x.cwiseMax(n.min).cwiseMin(n.max)).squaredNorm();
    const double chord = std::sqrt(point_segment_distance2(x, m_.y[static_cast<std::size_t>(n.lo)],
                                                           m_.y[static_cast<std::size_t>(n.hi)]));
    const double capsule = chord - n.radius - kBoundSlack * (chord + (n.max - n.min).norm());
    return capsule > 0.0 ? std::max(box, capsule * capsule) : box;
  }

  int build(int lo, int hi) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_.back().lo = lo;
    nodes_.back().hi = hi;
    double radius = 0.0;
    for (int v = lo + 1; v < hi; ++v) {
      radius = std::max(radius, point_segment_distance2(m_.y[static_cast<std::size_t>(v)], m_.y[static_cast<std::size_t>(lo)],
                                                        m_.y[static_cast<std::size_t>(hi)]));
    }
    nodes_.back().radius = std::sqrt(radius);
    if (hi - lo <= kLeafSegments) {
      Vec2 mn = m_.y[static_cast<std::size_t>(lo)], mx = mn;
      for (int v = lo + 1; v <= hi; ++v) {
        mn = mn.cwiseMin(m_.y[static_cast<std::size_t>(v)]);
        mx = mx.cwiseMax(m_.y[static_cast<std::size_t>(v)]);
      }
      nodes_[static_cast<std::size_t>(id)].min = mn;
      nodes_[static_cast<std::size_t>(id)].max = mx;
      return id;
    }
    const int mid = lo + (hi - lo) / 2;
    const int left = build(lo, mid);
    const int right = build(mid, hi);
    TreeNode& n = nodes_[static_cast<std::size_t>(id)];
    n.left = left;
    n.right = right;
    n.min = nodes_[static_cast<std::size_t>(left)].min.cwiseMin(nodes_[static_cast<std::size_t>(right)].min);
    n.max = nodes_[static_cast<std::size_t>(left)].max.cwiseMax(nodes_[static_cast<std::size_t>(right)].max);
    return id;
  }

  const MasterPolyline& m_;
  std::vector<TreeNode> nodes_;
};

template <int Dim>
void check_node(const mesh::SimplexMesh<Dim>& mesh, int v, const char* role) {
  if (v < 0 || v >= mesh.num_nodes()) {
    throw Error(std::string("project_slave_nodes: ") + role + " node " + std::to_string(v) + " outside [0, " +
                std::to_string(mesh.num_nodes()) + ")");
  }
}

// The master nodes of a row of K and their weights: (1 - xi, xi) on a segment in 2D, the
// barycentric coordinates on a triangle in 3D.
template <int Dim>
struct FacetWeights {
  std::array<int, Dim> node{};
  std::array<double, Dim> phi{};
};

// The per-dimension piece of the projection: the deformed master, the search for the closest
// facet, and what a hit means (record, row weights, candidate rule). MasterSearch<2> is the
// polyline with its chain tree, MasterSearch<3> the triangulated surface with a FacetTree.
template <int Dim>
class MasterSearch;

template <>
class MasterSearch<2> {
 public:
  using Hit = SegmentHit;
  MasterSearch(const mesh::Mesh& mesh, const ContactPair& pair, const Eigen::VectorXd& w,
               const ProjectionOptions& options)
      : pair_(pair), m_(deformed_master(mesh, pair.master, w)), end_tolerance_(options.end_tolerance) {
    const bool use_tree = options.search == SearchMethod::Tree ||
                          (options.search == SearchMethod::Automatic && m_.num_segments() >= options.tree_min_segments);
    if (use_tree) tree_ = std::make_unique<SegmentTree>(m_);
  }

  static int facet(const Hit& h) { return h.segment; }

  Hit nearest(const Vec2& x) { return tree_ ? tree_->nearest(x, stack_) : search_all_pairs(m_, x); }

  // Fills the segment, xi, n2, rho and the candidate flag (end-of-chain rule, docs/contact.md).
  FacetWeights<2> locate(const mesh::Mesh& mesh, const Hit& h, const Vec2& /*x*/, SlaveProjection& p) const {
    const int a = pair_.master[static_cast<std::size_t>(h.segment)];
    const int b = pair_.master[static_cast<std::size_t>(h.segment + 1)];
    p.segment = h.segment;
    p.xi = h.xi;
    p.normal = m_.normal_at(h.segment, h.xi);  // the continuous normal field
    p.rho = (1.0 - h.xi) * mesh.nodes[static_cast<std::size_t>(a)] + h.xi * mesh.nodes[static_cast<std::size_t>(b)];
    const bool before_start = h.segment == 0 && h.t_raw < -end_tolerance_;
    const bool after_end = h.segment == m_.num_segments() - 1 && h.t_raw > 1.0 + end_tolerance_;
    p.candidate = m_.closed || !(before_start || after_end);
    return {{a, b}, {1.0 - h.xi, h.xi}};
  }

 private:
  const ContactPair& pair_;
  MasterPolyline m_;
  double end_tolerance_;
  std::unique_ptr<SegmentTree> tree_;
  std::vector<std::pair<int, double>> stack_;
};

template <>
class MasterSearch<3> {
 public:
  using Hit = TriangleHit;
  MasterSearch(const mesh::Mesh3& mesh, const ContactPair3& pair, const Eigen::VectorXd& w,
               const ProjectionOptions& options)
      : pair_(pair),
        m_(deformed_master(mesh, pair, w)),
        end_tolerance_(options.end_tolerance),
        rim_angle_(options.rim_angle_tolerance) {
    const bool use_tree = options.search == SearchMethod::Tree ||
                          (options.search == SearchMethod::Automatic && m_.num_facets() >= options.tree_min_segments);
    if (use_tree) {
      std::vector<FacetTree<3>::Facet> facets;
      facets.reserve(m_.face.size());
      for (const auto& t : m_.face) facets.push_back({y(t[0]), y(t[1]), y(t[2])});
      tree_ = std::make_unique<FacetTree<3>>(std::move(facets));
    }
  }

  static int facet(const Hit& h) { return h.facet; }

  Hit nearest(const Vec3& x) {
    const auto closest = [this](int f, const Vec3& p) { return closest_on(f, p); };
    if (tree_) return tree_->nearest<Hit>(x, closest, &MasterSearch::facet, stack_);
    // As search_all_pairs in 2D: increasing f, only (d2, f) carried through the loop.
    double best_d2 = std::numeric_limits<double>::infinity();
    int best = -1;
    for (int f = 0; f < m_.num_facets(); ++f) {
      const double d2 = closest_on(f, x).d2;
      if (d2 < best_d2) {
        best_d2 = d2;
        best = f;
      }
    }
    return best < 0 ? Hit{} : closest_on(best, x);
  }

  // Fills the triangle, phi, n2, rho and the candidate flag (rim rule, docs/contact.md).
  FacetWeights<3> locate(const mesh::Mesh3& mesh, const Hit& h, const Vec3& x, SlaveProjection3& p) const {
    const auto& t = m_.face[static_cast<std::size_t>(h.facet)];
    FacetWeights<3> row;
    p.facet = h.facet;
    p.phi = h.phi;
    p.normal = m_.normal_at(h.facet, h.phi);  // the continuous normal field
    p.rho.setZero();
    for (int i = 0; i < 3; ++i) {
      row.node[static_cast<std::size_t>(i)] = pair_.master[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])];
      row.phi[static_cast<std::size_t>(i)] = h.phi(i);
      p.rho += h.phi(i) * mesh.nodes[static_cast<std::size_t>(row.node[static_cast<std::size_t>(i)])];
    }
    p.candidate = !beyond_rim(h, x);
    return row;
  }

 private:
  const Vec3& y(int j) const { return m_.y[static_cast<std::size_t>(j)]; }

  Hit closest_on(int f, const Vec3& x) const {
    const auto& t = m_.face[static_cast<std::size_t>(f)];
    return closest_on_triangle(y(t[0]), y(t[1]), y(t[2]), f, x);
  }

  bool beyond(int rim, const Vec3& x, const Vec3& p) const {
    return (x - p).dot(m_.rim_conormal[static_cast<std::size_t>(rim)]) >
           end_tolerance_ * m_.rim_length[static_cast<std::size_t>(rim)] + rim_angle_ * (x - p).norm();
  }

  // The closest point lies on an edge (one phi_i = 0) or a vertex (two) of the triangle; the
  // node is beyond the master when that edge, or a rim edge at that vertex, faces it.
  bool beyond_rim(const Hit& h, const Vec3& x) const {
    const auto& t = m_.face[static_cast<std::size_t>(h.facet)];
    const int zeros = (h.phi(0) == 0.0) + (h.phi(1) == 0.0) + (h.phi(2) == 0.0);
    if (zeros == 1) {
      int i = 0;
      while (h.phi(i) != 0.0) ++i;
      const int rim = m_.face_rim[static_cast<std::size_t>(h.facet)][static_cast<std::size_t>(i)];
      return rim >= 0 && beyond(rim, x, h.phi(0) * y(t[0]) + h.phi(1) * y(t[1]) + h.phi(2) * y(t[2]));
    }
    if (zeros == 2) {
      int i = 0;
      h.phi.maxCoeff(&i);  // the vertex (its coordinate is 1)
      const int v = t[static_cast<std::size_t>(i)];
      for (int r = m_.vertex_rim_start[static_cast<std::size_t>(v)]; r < m_.vertex_rim_start[static_cast<std::size_t>(v + 1)];
           ++r) {
        if (beyond(m_.vertex_rim[static_cast<std::size_t>(r)], x, y(v))) return true;
      }
    }
    return false;
  }

  const ContactPair3& pair_;
  MasterSurface m_;
  double end_tolerance_;
  double rim_angle_;
  std::unique_ptr<FacetTree<3>> tree_;
  std::vector<std::pair<int, double>> stack_;
};

void check_pair(const mesh::Mesh& mesh, const ContactPair& pair) {
  require(pair.master.size() >= 2, "project_slave_nodes: the master chain has " +
                                       std::to_string(pair.master.size()) + " node(s); at least 2 are needed");
  for (int v : pair.slave) check_node(mesh, v, "slave");
  for (int v : pair.master) check_node(mesh, v, "master");
}

void check_pair(const mesh::Mesh3& mesh, const ContactPair3& pair) {
  require(!pair.master_faces.empty(), "project_slave_nodes: the master surface has no triangle");
  for (int v : pair.slave) check_node(mesh, v, "slave");
  for (int v : pair.master) check_node(mesh, v, "master");
  const int M = static_cast<int>(pair.master.size());
  for (const auto& t : pair.master_faces) {
    for (int j : t) {
      require(j >= 0 && j < M, "project_slave_nodes: master triangle vertex " + std::to_string(j) + " outside [0, " +
                                   std::to_string(M) + ") (positions in pair.master)");
    }
  }
  const int F = static_cast<int>(pair.master_faces.size());
  for (const auto& [f, i] : pair.master_rim) {
    require(f >= 0 && f < F && i >= 0 && i < 3, "project_slave_nodes: master rim edge (" + std::to_string(f) + ", " +
                                                    std::to_string(i) + ") outside the master triangles");
  }
}

template <int Dim>
void check_displacement(const mesh::SimplexMesh<Dim>& mesh, const Eigen::VectorXd& w) {
  require(w.size() == mesh.num_dofs(), "project_slave_nodes: displacement has size " + std::to_string(w.size()) +
                                           " but the mesh has " + std::to_string(mesh.num_dofs()) + " DOFs (" +
                                           std::to_string(mesh.num_nodes()) + " nodes)");
  // Messages are built only on failure: these checks run once per entry on every call.
  if (!w.allFinite()) {
    Eigen::Index i = 0;
    while (std::isfinite(w(i))) ++i;
    throw Error("project_slave_nodes: displacement entry " + std::to_string(i) + " (node " +
                std::to_string(i / Dim) + ") is not finite");
  }
}

bool located(const SlaveProjection& p) { return p.segment >= 0; }
bool located(const SlaveProjection3& p) { return p.facet >= 0; }

// (27)-(28) at every listed slave node: one code path for both dimensions around the
// per-dimension MasterSearch.
template <int Dim>
PointwiseContactOf<Dim> project(const mesh::SimplexMesh<Dim>& mesh, const ContactPairOf<Dim>& pair,
                                const Eigen::VectorXd& w, std::span<const int> positions,
                                const ProjectionOptions& options) {
  check_displacement(mesh, w);
  check_pair(mesh, pair);
  require(options.end_tolerance >= 0.0, "project_slave_nodes: end_tolerance must be >= 0");
  MasterSearch<Dim> search(mesh, pair, w, options);

  const int S = static_cast<int>(pair.slave.size());
  PointwiseContactOf<Dim> out;
  out.projection.resize(static_cast<std::size_t>(S));
  out.g.setZero(S);
  // Rows are filled in order with at most (Dim + 1) Dim entries each: reserve and insert
  // directly (no triplet sort, no O(num_dofs) transposition).
  out.K.resize(S, mesh.num_dofs());
  out.K.reserve(Eigen::VectorXi::Constant(S, (Dim + 1) * Dim));
  for (const int s : positions) {
    if (s < 0 || s >= S) {
      throw Error("project_slave_nodes: slave position " + std::to_string(s) + " outside [0, " + std::to_string(S) + ")");
    }
    auto& p = out.projection[static_cast<std::size_t>(s)];
    if (located(p)) continue;  // a repeated position
    const int node = pair.slave[static_cast<std::size_t>(s)];
    const auto x = position(mesh, w, node);
    const auto h = search.nearest(x);
    // No facet at a finite distance: the coordinates are finite but their squared distances
    // overflow (from about 1e154 on). The search then keeps its initial facet -1, which must
    // never be used as an index.
    if (MasterSearch<Dim>::facet(h) < 0 || !std::isfinite(h.d2)) {
      std::ostringstream os;
      os << "project_slave_nodes: the distance from slave node " << node
         << " to the master boundary is not finite (positions of magnitude " << x.cwiseAbs().maxCoeff()
         << " overflow double precision when squared)";
      throw Error(os.str());
    }
    const FacetWeights<Dim> row = search.locate(mesh, h, x, p);
    p.distance = std::sqrt(h.d2);
    if (!p.candidate) {
      out.g(s) = p.distance;  // zero row: 0 <= distance never binds
      continue;
    }
    // (28): g = (X_s - rho) . n2
    out.g(s) = (mesh.nodes[static_cast<std::size_t>(node)] - p.rho).dot(p.normal);
    // (27): k(w; v)_s = (sum_i phi_i v_{t_i} - v_s) . n2
    // coeffRef (not insert): a hand-made pair may share a node between slave and master.
    for (int c = 0; c < Dim; ++c) {
      for (int i = 0; i < Dim; ++i) {
        const double phi = row.phi[static_cast<std::size_t>(i)];
        if (phi != 0.0) out.K.coeffRef(s, Dim * row.node[static_cast<std::size_t>(i)] + c) += phi * p.normal(c);
      }
      out.K.coeffRef(s, Dim * node + c) -= p.normal(c);
    }
  }
  out.K.makeCompressed();
  return out;
}

std::vector<int> all_positions(std::size_t S) {
  std::vector<int> all(S);
  for (std::size_t s = 0; s < S; ++s) all[s] = static_cast<int>(s);
  return all;
}

void check_rows(const ContactQuadrature& quadrature, Eigen::Index pointwise_rows, Eigen::Index gaps,
                std::size_t slaves) {
  require(quadrature.W.cols() == pointwise_rows && gaps == pointwise_rows,
          "constraint_rows: quadrature has " + std::to_string(quadrature.W.cols()) +
              " slave columns but the pointwise contact has " + std::to_string(pointwise_rows) + " K rows and " +
              std::to_string(gaps) + " gap entries");
  require(static_cast<std::size_t>(quadrature.W.cols()) == slaves,
          "constraint_rows: quadrature has " + std::to_string(quadrature.W.cols()) + " slave columns but the pair has " +
              std::to_string(slaves) + " slave nodes");
}

template <int Dim>
ConstraintRows weighted_rows(const ContactQuadrature& quadrature, const PointwiseContactOf<Dim>& pointwise) {
  ConstraintRows rows;
  // (10)-(11) with the quadrature of (61) / (62).
  rows.K = quadrature.W * pointwise.K;
  rows.g = quadrature.W * pointwise.g;
  return rows;
}

}  // namespace

PointwiseContact project_slave_nodes(const mesh::Mesh& mesh, const ContactPair& pair, const Eigen::VectorXd& w,
                                     const ProjectionOptions& options) {
  return project<2>(mesh, pair, w, all_positions(pair.slave.size()), options);
}

PointwiseContact project_slave_nodes(const mesh::Mesh& mesh, const ContactPair& pair, const Eigen::VectorXd& w,
                                     std::span<const int> positions, const ProjectionOptions& options) {
  return project<2>(mesh, pair, w, positions, options);
}

PointwiseContact3 project_slave_nodes(const mesh::Mesh3& mesh, const ContactPair3& pair, const Eigen::VectorXd& w,
                                      const ProjectionOptions& options) {
  return project<3>(mesh, pair, w, all_positions(pair.slave.size()), options);
}

PointwiseContact3 project_slave_nodes(const mesh::Mesh3& mesh, const ContactPair3& pair, const Eigen::VectorXd& w,
                                      std::span<const int> positions, const ProjectionOptions& options) {
  return project<3>(mesh, pair, w, positions, options);
}

ConstraintRows constraint_rows(const mesh::Mesh3& mesh, const ContactPair3& pair,
                               const ContactQuadrature& quadrature, const PointwiseContact3& pointwise,
                               const Eigen::VectorXd& w) {
  check_rows(quadrature, pointwise.K.rows(), pointwise.g.size(), pair.slave.size());
  require(quadrature.discretization != Discretization::LACSimpson,
          "constraint_rows: the 'lac-simpson' discretization is not available in 3D (use 'lac' or 'collocation')");
  // Exact integration over the median dual cells, segmented by the master triangles (lac3d.hpp).
  if (quadrature.discretization == Discretization::LAC) return integrate_lac_rows(mesh, pair, quadrature, pointwise, w);
  return weighted_rows(quadrature, pointwise);
}

ConstraintRows constraint_rows(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                              const PointwiseContact& pointwise, const Eigen::VectorXd& w) {
  check_rows(quadrature, pointwise.K.rows(), pointwise.g.size(), pair.slave.size());
  // Exact segment-to-segment integration over each macro-segment (lac_integration.hpp).
  if (quadrature.discretization == Discretization::LAC) return integrate_lac_rows(mesh, pair, quadrature, pointwise, w);
  return weighted_rows(quadrature, pointwise);
}

const char* to_string(SearchMethod value) {
  switch (value) {
    case SearchMethod::Automatic: return "automatic";
    case SearchMethod::AllPairs: return "all-pairs";
    case SearchMethod::Tree: return "tree";
  }
  return "unknown";
}

SearchMethod search_method_from_string(const std::string& name) {
  using enum SearchMethod;
  return enum_from_string(name, "projection search method", std::array{Automatic, AllPairs, Tree});
}

}  // namespace contactrb::contact
