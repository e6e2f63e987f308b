#pragma once
// A bounding-volume tree over the facets of a master surface that has no chain order (3D
// triangles): median splits of the facet centroids along the longest axis, boxes as volumes.
// The 2D master polyline keeps its chain tree (projection.cpp), which splits index ranges
// and bounds them with capsules. Internal to the contact module.
#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace contactrb::contact {

template <int Dim>
class FacetTree {
 public:
  using Point = Eigen::Matrix<double, Dim, 1>;

  // lo[k], hi[k]: the bounding box of facet k (its vertices).
  FacetTree(std::vector<Point> lo, std::vector<Point> hi) : lo_(std::move(lo)), hi_(std::move(hi)) {
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
    stack.emplace_back(0, box_distance2(nodes_.front(), x));
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
      const double dl = box_distance2(nodes_[static_cast<std::size_t>(n.left)], x);
      const double dr = box_distance2(nodes_[static_cast<std::size_t>(n.right)], x);
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

 private:
  // Facets per leaf: small enough to prune well, large enough to keep the tree shallow.
  static constexpr int kLeafFacets = 8;

  struct Node {
    Point min, max;
    int lo = 0, hi = 0;  // positions [lo, hi) in order_
    int left = -1, right = -1;
  };

  static double box_distance2(const Node& n, const Point& x) {
    return (x - x.cwiseMax(n.min).cwiseMin(n.max)).squaredNorm();
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

  std::vector<Point> lo_, hi_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

}  // namespace contactrb::contact
