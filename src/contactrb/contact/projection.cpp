#include "contactrb/contact/projection.hpp"

#include <algorithm>
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
#include "contactrb/contact/lac_integration.hpp"
#include "contactrb/contact/master_polyline.hpp"
#include "contactrb/contact/segment_hit.hpp"

namespace contactrb::contact {

namespace {

using Vec2 = Eigen::Vector2d;

// Segments per tree leaf: small enough to prune well, large enough to keep the tree shallow.
constexpr int kLeafSegments = 8;
// Relative slack on the capsule lower bound of a tree node, far above the round-off of the
// distances it combines (~1e-15 relative), so pruning never drops the exact answer.
constexpr double kBoundSlack = 1e-9;

Vec2 position(const mesh::Mesh& mesh, const Eigen::VectorXd& w, int node) {
  return mesh.nodes[static_cast<std::size_t>(node)] + w.segment<2>(2 * node);
}

SegmentHit closest_on_segment(const MasterPolyline& m, int k, const Vec2& x) {
  return contact::closest_on_segment(m.y[static_cast<std::size_t>(k)], m.y[static_cast<std::size_t>(k + 1)], k, x);
}

// Lexicographic order on (squared distance, segment index): the answer of every search.
bool better(const SegmentHit& h, const SegmentHit& best) {
  return h.d2 < best.d2 || (h.d2 == best.d2 && h.segment < best.segment);
}

SegmentHit search_all_pairs(const MasterPolyline& m, const Vec2& x) {
  SegmentHit best;
  for (int k = 0; k < m.num_segments(); ++k) {
    const SegmentHit h = closest_on_segment(m, k, x);
    if (better(h, best)) best = h;
  }
  return best;
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

void check_node(const mesh::Mesh& mesh, int v, const char* role) {
  if (v < 0 || v >= mesh.num_nodes()) {
    throw Error(std::string("project_slave_nodes: ") + role + " node " + std::to_string(v) + " outside [0, " +
                std::to_string(mesh.num_nodes()) + ")");
  }
}

}  // namespace

PointwiseContact project_slave_nodes(const mesh::Mesh& mesh, const ContactPair& pair, const Eigen::VectorXd& w,
                                     const ProjectionOptions& options) {
  std::vector<int> all(pair.slave.size());
  for (std::size_t s = 0; s < all.size(); ++s) all[s] = static_cast<int>(s);
  return project_slave_nodes(mesh, pair, w, all, options);
}

PointwiseContact project_slave_nodes(const mesh::Mesh& mesh, const ContactPair& pair, const Eigen::VectorXd& w,
                                     std::span<const int> positions, const ProjectionOptions& options) {
  require(w.size() == mesh.num_dofs(), "project_slave_nodes: displacement has size " + std::to_string(w.size()) +
                                           " but the mesh has " + std::to_string(mesh.num_dofs()) + " DOFs (" +
                                           std::to_string(mesh.num_nodes()) + " nodes)");
  // Messages are built only on failure: these checks run once per entry on every call.
  if (!w.allFinite()) {
    Eigen::Index i = 0;
    while (std::isfinite(w(i))) ++i;
    throw Error("project_slave_nodes: displacement entry " + std::to_string(i) + " (node " + std::to_string(i / 2) +
                ") is not finite");
  }
  require(pair.master.size() >= 2, "project_slave_nodes: the master chain has " +
                                       std::to_string(pair.master.size()) + " node(s); at least 2 are needed");
  require(options.end_tolerance >= 0.0, "project_slave_nodes: end_tolerance must be >= 0");
  for (int v : pair.slave) check_node(mesh, v, "slave");
  for (int v : pair.master) check_node(mesh, v, "master");

  const MasterPolyline m = deformed_master(mesh, pair.master, w);
  const int M = m.num_segments();
  const bool use_tree = options.search == SearchMethod::Tree ||
                        (options.search == SearchMethod::Automatic && M >= options.tree_min_segments);
  std::unique_ptr<SegmentTree> tree;
  if (use_tree) tree = std::make_unique<SegmentTree>(m);
  std::vector<std::pair<int, double>> stack;

  const int S = static_cast<int>(pair.slave.size());
  PointwiseContact out;
  out.projection.resize(static_cast<std::size_t>(S));
  out.g.setZero(S);
  // Rows are filled in order with at most 6 entries each: reserve and insert directly
  // (no triplet sort, no O(num_dofs) transposition).
  out.K.resize(S, mesh.num_dofs());
  out.K.reserve(Eigen::VectorXi::Constant(S, 6));
  for (const int s : positions) {
    if (s < 0 || s >= S) {
      throw Error("project_slave_nodes: slave position " + std::to_string(s) + " outside [0, " + std::to_string(S) + ")");
    }
    if (out.projection[static_cast<std::size_t>(s)].segment >= 0) continue;  // a repeated position
    const int node = pair.slave[static_cast<std::size_t>(s)];
    const Vec2 x = position(mesh, w, node);
    const SegmentHit h = use_tree ? tree->nearest(x, stack) : search_all_pairs(m, x);
    // No segment at a finite distance: the coordinates are finite but their squared distances
    // overflow (from about 1e154 on). The search then keeps its initial segment -1, which must
    // never be used as an index.
    if (h.segment < 0 || !std::isfinite(h.d2)) {
      std::ostringstream os;
      os << "project_slave_nodes: the distance from slave node " << node
         << " to the master boundary is not finite (positions of magnitude " << x.cwiseAbs().maxCoeff()
         << " overflow double precision when squared)";
      throw Error(os.str());
    }
    const int a = pair.master[static_cast<std::size_t>(h.segment)];
    const int b = pair.master[static_cast<std::size_t>(h.segment + 1)];

    SlaveProjection& p = out.projection[static_cast<std::size_t>(s)];
    p.segment = h.segment;
    p.xi = h.xi;
    p.normal = m.normal_at(h.segment, h.xi);  // the continuous normal field
    p.rho = (1.0 - h.xi) * mesh.nodes[static_cast<std::size_t>(a)] + h.xi * mesh.nodes[static_cast<std::size_t>(b)];
    p.distance = std::sqrt(h.d2);
    const bool before_start = h.segment == 0 && h.t_raw < -options.end_tolerance;
    const bool after_end = h.segment == M - 1 && h.t_raw > 1.0 + options.end_tolerance;
    p.candidate = m.closed || !(before_start || after_end);

    if (!p.candidate) {
      out.g(s) = p.distance;  // zero row: 0 <= distance never binds
      continue;
    }
    // (28): g = (X_s - rho) . n2
    out.g(s) = (mesh.nodes[static_cast<std::size_t>(node)] - p.rho).dot(p.normal);
    // (27): k(w; v)_s = ((1 - xi) v_a + xi v_b - v_s) . n2
    // coeffRef (not insert): a hand-made pair may share a node between slave and master.
    for (int c = 0; c < 2; ++c) {
      if (1.0 - h.xi != 0.0) out.K.coeffRef(s, 2 * a + c) += (1.0 - h.xi) * p.normal(c);
      if (h.xi != 0.0) out.K.coeffRef(s, 2 * b + c) += h.xi * p.normal(c);
      out.K.coeffRef(s, 2 * node + c) -= p.normal(c);
    }
  }
  out.K.makeCompressed();
  return out;
}

ConstraintRows constraint_rows(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                              const PointwiseContact& pointwise, const Eigen::VectorXd& w) {
  require(quadrature.W.cols() == pointwise.K.rows() && pointwise.g.size() == pointwise.K.rows(),
          "constraint_rows: quadrature has " + std::to_string(quadrature.W.cols()) +
              " slave columns but the pointwise contact has " + std::to_string(pointwise.K.rows()) + " K rows and " +
              std::to_string(pointwise.g.size()) + " gap entries");
  require(static_cast<std::size_t>(quadrature.W.cols()) == pair.slave.size(),
          "constraint_rows: quadrature has " + std::to_string(quadrature.W.cols()) + " slave columns but the pair has " +
              std::to_string(pair.slave.size()) + " slave nodes");
  // Exact segment-to-segment integration over each macro-segment (lac_integration.hpp).
  if (quadrature.discretization == Discretization::LAC) return integrate_lac_rows(mesh, pair, quadrature, pointwise, w);
  ConstraintRows rows;
  // (10)-(11) with the quadrature of (61) / (62).
  rows.K = quadrature.W * pointwise.K;
  rows.g = quadrature.W * pointwise.g;
  return rows;
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
