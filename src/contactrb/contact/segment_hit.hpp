#pragma once
// The closest point of a point x on one master segment, shared by the HF projection
// (projection.cpp) and the online magic-point evaluation (online/online_magic.cpp), which must
// pick the same segment in floating point. Inline: it is the inner loop of both searches.
#include <Eigen/Core>
#include <limits>

namespace contactrb::contact {

struct SegmentHit {
  double d2 = std::numeric_limits<double>::infinity();
  int segment = -1;
  double t_raw = 0.0;  // unclamped projection parameter on the segment's line
  double xi = 0.0;     // in [0, 1]
};

// Closest point of x on segment k = (a, b), clamped into the segment's bounding box so that
// the computed squared distance is never below the computed distance to any box holding the
// segment (this makes tree pruning exact in floating point, not only in exact arithmetic).
inline SegmentHit closest_on_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, int k,
                                     const Eigen::Vector2d& x) {
  const Eigen::Vector2d e = b - a;
  SegmentHit h;
  h.segment = k;
  h.t_raw = (x - a).dot(e) / e.squaredNorm();
  Eigen::Vector2d p;
  if (h.t_raw <= 0.0) {
    h.xi = 0.0;
    p = a;
  } else if (h.t_raw >= 1.0) {
    h.xi = 1.0;
    p = b;
  } else {
    h.xi = h.t_raw;
    p = (a + h.xi * e).cwiseMax(a.cwiseMin(b)).cwiseMin(a.cwiseMax(b));
  }
  h.d2 = (x - p).squaredNorm();
  return h;
}

}  // namespace contactrb::contact
