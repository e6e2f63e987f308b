#pragma once
// A bounding-volume tree over the facets of a master surface that has no chain order (3D
// triangles): median splits of the facet centroids along the longest axis. Each node bounds
// its piece of surface twice: by its axis-aligned box (exact in floating point, see
// closest_on_triangle) and by a cylinder around its mean plane (axis n = the mean facet
// normal through the vertex centroid c, radius = the largest distance of a vertex to the
// axis, half height = the largest distance of a vertex to the plane). On a curved master the
// cylinder is far thinner than the box (its height shrinks like the square of the piece size),
// as the capsules of the 2D chain tree (projection.cpp). The 2D master polyline keeps that chain tree, which needs no sorting.
// Vertices = Dim + 1 holds cells instead (triangles in 2D, tetrahedra in 3D): boxes only, for the
// point location of the level transfer (hf/level_transfer.cpp).
// Internal to the contact module and the level transfer.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace contactrb::contact {

template <int Dim, int Vertices = Dim>
class FacetTree {
 public:
  using Point = Eigen::Matrix<double, Dim, 1>;

  using Facet = std::array<Point, Vertices>;

  explicit FacetTree(std::vector<Facet> facets) : facets_(std::move(facets)) {
    lo_.reserve(facets_.size());
    hi_.reserve(facets_.size());
    for (const Facet& f : facets_) {
      Point mn = f[0], mx = f[0];
      for (const Point& p : f) {
        mn = mn.cwiseMin(p);
        mx = mx.cwiseMax(p);
      }
      lo_.push_back(mn);
      hi_.push_back(mx);
    }
    order_.resize(lo_.size());
    std::iota(order_.begin(), order_.end(), 0);
    if (!order_.empty()) build(0, static_cast<int>(order_.size()));
  }

  // The facet minimizing (squared distance, facet index) lexicographically, as a search over
  // all facets would return it. closest(k, x) returns a hit with members d2 and the facet
  // index `index(hit)`, its closest point clamped into the facet's box (triangle_hit.hpp), so
  // that box pruning is exact in floating point. stack: scratch space reused across queries.
  template <class Hit, class Closest, class Index>
  Hit nearest(const Point& x, Closest&& closest, Index&& index, std::vector<std::pair<int, double>>& stack) const {
    Hit best;
    if (nodes_.empty()) return best;
    stack.clear();
    stack.emplace_back(0, lower_bound2(nodes_.front(), x));
    while (!stack.empty()) {
      const auto [id, lb] = stack.back();
      stack.pop_back();
      // Strictly farther only: an equally distant facet with a lower index must still win.
      if (lb > best.d2) continue;
      const Node& n = nodes_[static_cast<std::size_t>(id)];
      if (n.left < 0) {
        for (int j = n.lo; j < n.hi; ++j) {
          const Hit h = closest(order_[static_cast<std::size_t>(j)], x);
          if (h.d2 < best.d2 || (h.d2 == best.d2 && index(h) < index(best))) best = h;
        }
        continue;
      }
      const double dl = lower_bound2(nodes_[static_cast<std::size_t>(n.left)], x);
      const double dr = lower_bound2(nodes_[static_cast<std::size_t>(n.right)], x);
      if (dl <= dr) {  // nearer child on top of the stack, visited first
        stack.emplace_back(n.right, dr);
        stack.emplace_back(n.left, dl);
      } else {
        stack.emplace_back(n.left, dl);
        stack.emplace_back(n.right, dr);
      }
    }
    return best;
  }

  // Appends to `out` the facets whose bounding box meets the box [lo, hi] (in tree order):
  // the candidate master facets of a region (the 3D LAC, lac3d.cpp). stack: scratch space.
  void overlapping(const Point& lo, const Point& hi, std::vector<int>& out, std::vector<int>& stack) const {
    if (nodes_.empty()) return;
    const auto meets = [&lo, &hi](const Point& mn, const Point& mx) {
      return (mn.array() <= hi.array()).all() && (lo.array() <= mx.array()).all();
    };
    stack.clear();
    stack.push_back(0);
    while (!stack.empty()) {
      const Node& n = nodes_[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      if (!meets(n.min, n.max)) continue;
      if (n.left >= 0) {
        stack.push_back(n.right);
        stack.push_back(n.left);
        continue;
      }
      for (int j = n.lo; j < n.hi; ++j) {
        const std::size_t k = static_cast<std::size_t>(order_[static_cast<std::size_t>(j)]);
        if (meets(lo_[k], hi_[k])) out.push_back(static_cast<int>(k));
      }
    }
  }

  int num_facets() const { return static_cast<int>(facets_.size()); }
  const Facet& facet(int k) const { return facets_[static_cast<std::size_t>(k)]; }

 private:
  // Facets per leaf: small enough to prune well, large enough to keep the tree shallow.
  static constexpr int kLeafFacets = 8;

  // Relative slack on the cylinder lower bound, far above the round-off of the products it
  // combines (~1e-15 relative), so pruning never drops the exact answer.
  static constexpr double kBoundSlack = 1e-9;

  struct Node {
    Point min, max;
    Point centre = Point::Zero(), axis = Point::Zero();  // axis: unit mean normal, or zero (no cylinder)
    double radius = 0.0, half_height = 0.0;
    int lo = 0, hi = 0;  // positions [lo, hi) in order_
    int left = -1, right = -1;
  };

  // Lower bound of the squared distance from x to any point of the node's facets: every such
  // point is a convex combination of vertices, so it lies in the box and in the cylinder.
  static double lower_bound2(const Node& n, const Point& x) {
    const double box = (x - x.cwiseMax(n.min).cwiseMin(n.max)).squaredNorm();
    if (n.axis.isZero()) return box;  // no cylinder: cells, or facets whose normals cancel exactly
    const Point d = x - n.centre;
    const double h = d.dot(n.axis);
    const double lateral = (d - h * n.axis).norm();
    const double a = std::max(0.0, std::abs(h) - n.half_height), b = std::max(0.0, lateral - n.radius);
    const double cylinder = std::sqrt(a * a + b * b) - kBoundSlack * (d.norm() + (n.max - n.min).norm());
    return cylinder > 0.0 ? std::max(box, cylinder * cylinder) : box;
  }

  static Point facet_normal(const Facet& f) {
    if constexpr (Dim == 3) {
      return (f[1] - f[0]).cross(f[2] - f[0]);
    } else {
      return Point(f[1].y() - f[0].y(), f[0].x() - f[1].x());
    }
  }

  const Facet& facet_at(int j) const { return facets_[static_cast<std::size_t>(order_[static_cast<std::size_t>(j)])]; }

  // The cylinder of facets [lo, hi) around their mean plane (cells have no plane: none).
  void set_cylinder(Node& n) const {
    if constexpr (Vertices != Dim) return;
    Point sum = Point::Zero(), centre = Point::Zero();
    for (int j = n.lo; j < n.hi; ++j) {
      sum += facet_normal(facet_at(j));
      for (const Point& p : facet_at(j)) centre += p;
    }
    const double len = sum.norm();
    if (!(len > 0.0)) return;
    n.axis = sum / len;
    n.centre = centre / static_cast<double>(Vertices * (n.hi - n.lo));
    for (int j = n.lo; j < n.hi; ++j) {
      for (const Point& p : facet_at(j)) {
        const Point d = p - n.centre;
        const double h = d.dot(n.axis);
        n.half_height = std::max(n.half_height, std::abs(h));
        n.radius = std::max(n.radius, (d - h * n.axis).norm());
      }
    }
  }

  int build(int lo, int hi) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Point mn = lo_[static_cast<std::size_t>(order_[static_cast<std::size_t>(lo)])], mx = mn;
    Point cmin = Point::Constant(std::numeric_limits<double>::infinity()), cmax = -cmin;
    for (int j = lo; j < hi; ++j) {
      const std::size_t k = static_cast<std::size_t>(order_[static_cast<std::size_t>(j)]);
      mn = mn.cwiseMin(lo_[k]);
      mx = mx.cwiseMax(hi_[k]);
      const Point c = lo_[k] + hi_[k];
      cmin = cmin.cwiseMin(c);
      cmax = cmax.cwiseMax(c);
    }
    Node& n = nodes_.back();
    n.min = mn;
    n.max = mx;
    n.lo = lo;
    n.hi = hi;
    set_cylinder(n);
    if (hi - lo <= kLeafFacets) return id;
    int axis = 0;
    (cmax - cmin).maxCoeff(&axis);
    const int mid = lo + (hi - lo) / 2;
    // Ties in the centroid coordinate go by facet index: the tree does not depend on the
    // standard library's nth_element.
    const auto less = [this, axis](int a, int b) {
      const double ca = lo_[static_cast<std::size_t>(a)](axis) + hi_[static_cast<std::size_t>(a)](axis);
      const double cb = lo_[static_cast<std::size_t>(b)](axis) + hi_[static_cast<std::size_t>(b)](axis);
      return ca < cb || (ca == cb && a < b);
    };
    std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi, less);
    const int left = build(lo, mid);
    const int right = build(mid, hi);
    nodes_[static_cast<std::size_t>(id)].left = left;
    nodes_[static_cast<std::size_t>(id)].right = right;
    return id;
  }

  std::vector<Facet> facets_;
  std::vector<Point> lo_, hi_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

}  // namespace contactrb::contact
