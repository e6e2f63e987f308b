#pragma once
// Convex polygons in a plane, clipped by half-planes {f >= 0} of affine functions
// (Sutherland-Hodgman), their area and first moment, and a quadrature exact for quadratic
// integrands (the 3D LAC, lac3d.hpp). Internal to the contact module.
//
// Clipping by affine functions (barycentric coordinates of a triangle, differences of them)
// rather than by oriented edges makes the result independent of the orientation of the
// polygons: a projected slave triangle and a projected master triangle face opposite ways.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>

namespace contactrb::contact {

// f(x) = a . x + c on the plane.
struct Affine2 {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  double c = 0.0;
  double operator()(const Eigen::Vector2d& x) const { return a.dot(x) + c; }
  Affine2 operator-(const Affine2& o) const { return {a - o.a, c - o.c}; }
};

// z-component of the cross product of two plane vectors.
inline double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

// The barycentric coordinates of triangle (q0, q1, q2) as affine functions on the plane
// (mu_i(q_j) = delta_ij), mu_i(p) = cross2(q_{i+1} - p, q_{i+2} - p) / cross2(q1 - q0, q2 - q0).
// The triangle must have non-zero area.
inline std::array<Affine2, 3> barycentric_functions(const std::array<Eigen::Vector2d, 3>& q) {
  const double D = cross2(q[1] - q[0], q[2] - q[0]);
  std::array<Affine2, 3> mu;
  for (std::size_t i = 0; i < 3; ++i) {
    const Eigen::Vector2d& A = q[(i + 1) % 3];
    const Eigen::Vector2d& B = q[(i + 2) % 3];
    mu[i].a = Eigen::Vector2d(A.y() - B.y(), B.x() - A.x()) / D;
    mu[i].c = cross2(A, B) / D;
  }
  return mu;
}

// A convex polygon of at most kMax vertices: a triangle clipped by k half-planes has at most
// 3 + k, and the 3D LAC clips a quadrilateral by three.
struct Polygon2 {
  static constexpr int kMax = 16;
  std::array<Eigen::Vector2d, kMax> p;
  int n = 0;
  // Beyond kMax (only when round-off makes f change sign more than twice along a sliver of
  // zero width) further vertices are dropped: the sliver's area is zero to round-off.
  void push(const Eigen::Vector2d& x) {
    if (n < kMax) p[static_cast<std::size_t>(n++)] = x;
  }
  const Eigen::Vector2d& operator[](int i) const { return p[static_cast<std::size_t>(i)]; }
};

// Sutherland-Hodgman against one half-plane: the part of `in` where f >= 0.
inline Polygon2 clip(const Polygon2& in, const Affine2& f) {
  Polygon2 out;
  if (in.n == 0) return out;
  double fp = f(in[in.n - 1]);
  for (int i = 0; i < in.n; ++i) {
    const Eigen::Vector2d& p = in[(i + in.n - 1) % in.n];
    const Eigen::Vector2d& q = in[i];
    const double fq = f(q);
    if ((fp >= 0.0) != (fq >= 0.0)) out.push(p + (fp / (fp - fq)) * (q - p));
    if (fq >= 0.0) out.push(q);
    fp = fq;
  }
  return out;
}

// Area (absolute) and first moment (integral of x) of a polygon, by the fan from vertex 0.
struct PolygonMoments {
  double area = 0.0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
};

inline PolygonMoments moments(const Polygon2& poly) {
  PolygonMoments m;
  double signed_area = 0.0;
  Eigen::Vector2d signed_moment = Eigen::Vector2d::Zero();
  for (int i = 1; i + 1 < poly.n; ++i) {
    const double a = 0.5 * cross2(poly[i] - poly[0], poly[i + 1] - poly[0]);
    signed_area += a;
    signed_moment += a * (poly[0] + poly[i] + poly[i + 1]) / 3.0;
  }
  const double sign = signed_area < 0.0 ? -1.0 : 1.0;
  m.area = sign * signed_area;
  m.moment = sign * signed_moment;
  return m;
}

// Calls visit(x, weight) at the points of a rule exact for quadratic polynomials on the
// polygon: the fan from vertex 0, three points per triangle (barycentric (2/3, 1/6, 1/6) and
// permutations, weight area / 3).
template <class Visit>
void for_each_quadrature_point(const Polygon2& poly, Visit&& visit) {
  for (int i = 1; i + 1 < poly.n; ++i) {
    const Eigen::Vector2d& a = poly[0];
    const Eigen::Vector2d& b = poly[i];
    const Eigen::Vector2d& c = poly[i + 1];
    const double w = std::abs(cross2(b - a, c - a)) / 6.0;  // area / 3
    if (w == 0.0) continue;
    visit((4.0 * a + b + c) / 6.0, w);
    visit((a + 4.0 * b + c) / 6.0, w);
    visit((a + b + 4.0 * c) / 6.0, w);
  }
}

}  // namespace contactrb::contact
