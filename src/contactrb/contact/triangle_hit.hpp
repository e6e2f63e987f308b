#pragma once
// The closest point of a point x on one master triangle: the 3D counterpart of
// segment_hit.hpp, the one piece of the projection that differs between 2D and 3D.
// Inline: it is the inner loop of the searches.
#include <Eigen/Core>
#include <limits>

namespace contactrb::contact {

struct TriangleHit {
  double d2 = std::numeric_limits<double>::infinity();
  int facet = -1;
  // Barycentric coordinates of the closest point, (phi_a, phi_b, phi_c), non-negative, sum 1.
  // Exactly 0 for the vertices a region excludes: one zero on an edge, two on a vertex.
  Eigen::Vector3d phi{1.0, 0.0, 0.0};
};

// Closest point of x on triangle k = (a, b, c) by its Voronoi regions (vertex, edge, face),
// Ericson, "Real-Time Collision Detection", 5.1.5. As in closest_on_segment the point is
// clamped into the triangle's bounding box before the distance is taken, so the computed
// squared distance is never below the computed distance to any box holding the triangle
// (exact tree pruning in floating point).
inline TriangleHit closest_on_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                       int k, const Eigen::Vector3d& x) {
  using Vec3 = Eigen::Vector3d;
  TriangleHit h;
  h.facet = k;
  const Vec3 ab = b - a, ac = c - a, ap = x - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  Vec3 p;
  if (d1 <= 0.0 && d2 <= 0.0) {  // vertex a
    h.phi = Vec3(1.0, 0.0, 0.0);
    p = a;
  } else {
    const Vec3 bp = x - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    const Vec3 cp = x - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= 0.0 && d4 <= d3) {  // vertex b
      h.phi = Vec3(0.0, 1.0, 0.0);
      p = b;
    } else if (d6 >= 0.0 && d5 <= d6) {  // vertex c
      h.phi = Vec3(0.0, 0.0, 1.0);
      p = c;
    } else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {  // edge ab
      const double t = d1 / (d1 - d3);
      h.phi = Vec3(1.0 - t, t, 0.0);
      p = a + t * ab;
    } else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {  // edge ac
      const double t = d2 / (d2 - d6);
      h.phi = Vec3(1.0 - t, 0.0, t);
      p = a + t * ac;
    } else if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {  // edge bc
      const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      h.phi = Vec3(0.0, 1.0 - t, t);
      p = b + t * (c - b);
    } else {  // inside the face
      const double denom = 1.0 / (va + vb + vc);
      const double v = vb * denom, w = vc * denom;
      h.phi = Vec3(1.0 - v - w, v, w);
      p = a + v * ab + w * ac;
    }
  }
  p = p.cwiseMax(a.cwiseMin(b).cwiseMin(c)).cwiseMin(a.cwiseMax(b).cwiseMax(c));
  h.d2 = (x - p).squaredNorm();
  return h;
}

}  // namespace contactrb::contact
