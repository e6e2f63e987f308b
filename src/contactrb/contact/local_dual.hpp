#pragma once
// Forward-mode dual numbers over a few local inputs, for the analytic linearization of the
// contact maps (contact_linearization.cpp): a value and its partial derivatives with respect to
// at most kDualWidth seeded inputs (the DOFs one constraint row depends on; rows with more
// inputs are differentiated in several passes, kDualWidth inputs at a time). Internal to the
// contact module. Only the slots [0, n) are set (no zero fill of the whole array: a dual is
// created per operation, and on hertz-a level 0 the fill was most of the linearization's time);
// a slot at or beyond n reads as zero (slot()).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace contactrb::contact::detail {

inline constexpr int kDualWidth = 24;

struct Dual {
  double v = 0.0;
  int n = 0;  // slots [0, n) are set, the others are zero
  std::array<double, kDualWidth> d;  // NOLINT: deliberately not filled beyond n

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT(google-explicit-constructor): constants mix freely
  static Dual input(double value, int slot) {
    Dual x(value);
    if (slot >= 0 && slot < kDualWidth) {
      x.n = slot + 1;
      for (int i = 0; i < slot; ++i) x.d[static_cast<std::size_t>(i)] = 0.0;
      x.d[static_cast<std::size_t>(slot)] = 1.0;
    }
    return x;
  }
  double slot(int i) const { return i >= 0 && i < n && i < kDualWidth ? d[static_cast<std::size_t>(i)] : 0.0; }
};

// r = alpha a + beta b on the derivatives (values set by the caller).
inline Dual combine(double value, double alpha, const Dual& a, double beta, const Dual& b) {
  Dual r(value);
  // n is always in [0, kDualWidth]; the clamps tell the compiler so (-Warray-bounds).
  const std::size_t na = static_cast<std::size_t>(std::clamp(a.n, 0, kDualWidth));
  const std::size_t nb = static_cast<std::size_t>(std::clamp(b.n, 0, kDualWidth));
  const std::size_t common = std::min(na, nb);
  for (std::size_t i = 0; i < common; ++i) r.d[i] = alpha * a.d[i] + beta * b.d[i];
  for (std::size_t i = common; i < na; ++i) r.d[i] = alpha * a.d[i];
  for (std::size_t i = common; i < nb; ++i) r.d[i] = beta * b.d[i];
  r.n = static_cast<int>(std::max(na, nb));
  return r;
}
inline Dual scale(double value, double alpha, const Dual& a) {
  Dual r(value);
  const std::size_t na = static_cast<std::size_t>(std::clamp(a.n, 0, kDualWidth));
  for (std::size_t i = 0; i < na; ++i) r.d[i] = alpha * a.d[i];
  r.n = static_cast<int>(na);
  return r;
}

inline Dual operator+(const Dual& a, const Dual& b) { return combine(a.v + b.v, 1.0, a, 1.0, b); }
inline Dual operator-(const Dual& a, const Dual& b) { return combine(a.v - b.v, 1.0, a, -1.0, b); }
inline Dual operator-(const Dual& a) { return scale(-a.v, -1.0, a); }
inline Dual operator*(const Dual& a, const Dual& b) { return combine(a.v * b.v, b.v, a, a.v, b); }
inline Dual operator*(double s, const Dual& a) { return scale(s * a.v, s, a); }
inline Dual operator*(const Dual& a, double s) { return scale(s * a.v, s, a); }
inline Dual operator/(const Dual& a, const Dual& b) {
  const double q = a.v / b.v;
  return combine(q, 1.0 / b.v, a, -q / b.v, b);
}
inline Dual operator/(const Dual& a, double s) { return scale(a.v / s, 1.0 / s, a); }
inline Dual operator+(const Dual& a, double s) { return scale(a.v + s, 1.0, a); }
inline Dual operator+(double s, const Dual& a) { return scale(a.v + s, 1.0, a); }
inline Dual operator-(double s, const Dual& a) { return scale(s - a.v, -1.0, a); }
inline Dual operator-(const Dual& a, double s) { return scale(a.v - s, 1.0, a); }
inline Dual& operator+=(Dual& a, const Dual& b) { return a = a + b; }
inline Dual sqrt(const Dual& a) {
  const double r = std::sqrt(a.v);
  return scale(r, r > 0.0 ? 0.5 / r : 0.0, a);
}

struct DVec2 {
  Dual x, y;
  const Dual& operator[](int c) const { return c == 0 ? x : y; }
  double vx() const { return x.v; }
  double vy() const { return y.v; }
  Eigen::Vector2d value() const { return {x.v, y.v}; }
};
inline DVec2 constant(const Eigen::Vector2d& v) { return {Dual(v.x()), Dual(v.y())}; }
inline DVec2 operator+(const DVec2& a, const DVec2& b) { return {a.x + b.x, a.y + b.y}; }
inline DVec2 operator-(const DVec2& a, const DVec2& b) { return {a.x - b.x, a.y - b.y}; }
inline DVec2 operator*(const Dual& s, const DVec2& a) { return {s * a.x, s * a.y}; }
inline DVec2 operator*(double s, const DVec2& a) { return {s * a.x, s * a.y}; }
inline DVec2 operator/(const DVec2& a, const Dual& s) { return {a.x / s, a.y / s}; }
inline Dual dot(const DVec2& a, const DVec2& b) { return a.x * b.x + a.y * b.y; }
inline Dual dot(const DVec2& a, const Eigen::Vector2d& b) { return a.x * b.x() + a.y * b.y(); }
inline Dual norm(const DVec2& a) { return sqrt(dot(a, a)); }

struct DVec3 {
  Dual x, y, z;
  Eigen::Vector3d value() const { return {x.v, y.v, z.v}; }
  const Dual& operator[](int c) const { return c == 0 ? x : c == 1 ? y : z; }
};
inline DVec3 constant3(const Eigen::Vector3d& v) { return {Dual(v.x()), Dual(v.y()), Dual(v.z())}; }
inline DVec3 operator+(const DVec3& a, const DVec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline DVec3 operator-(const DVec3& a, const DVec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline DVec3 operator*(const Dual& s, const DVec3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline DVec3 operator/(const DVec3& a, const Dual& s) { return {a.x / s, a.y / s, a.z / s}; }
inline Dual dot(const DVec3& a, const DVec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline DVec3 cross(const DVec3& a, const DVec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// g and the K entries of one row (or pointwise node) as duals, by DOF: K accumulates c n on the
// Dim DOFs of `node`; gap(geo) = g - K u with the derivative of u itself (geo.dof(d) is the dual
// value of DOF d). Dim = 2 (n a DVec2) or 3 (a DVec3).
template <int Dim, class Vec>
struct DualRowOf {
  Dual g;
  std::vector<std::pair<int, Dual>> K;
  void add(int node, const Dual& c, const Vec& n) {
    for (int comp = 0; comp < Dim; ++comp) {
      const int dof = Dim * node + comp;
      const Dual v = c * n[comp];
      auto it = std::find_if(K.begin(), K.end(), [dof](const auto& e) { return e.first == dof; });
      if (it == K.end()) {
        K.emplace_back(dof, v);
      } else {
        it->second += v;
      }
    }
  }
  template <class Geometry>
  Dual gap(const Geometry& geo) const {
    Dual d = g;
    for (const auto& [dof, k] : K) d = d - k * geo.dof(dof);
    return d;
  }
};
inline Dual norm(const DVec3& a) { return sqrt(dot(a, a)); }
// atan2(y, x) and its derivative (x dy - y dx) / (x^2 + y^2).
inline Dual atan2(const Dual& y, const Dual& x) {
  const double r2 = x.v * x.v + y.v * y.v;
  return combine(std::atan2(y.v, x.v), r2 > 0.0 ? -y.v / r2 : 0.0, x, r2 > 0.0 ? x.v / r2 : 0.0, y);
}

// Differentiates with respect to `inputs`, kDualWidth of them per pass: eval(window, count)
// runs with slot[inputs[start + q]] = q.
template <class Eval>
void in_passes(const std::vector<int>& inputs, std::vector<int>& slot, Eval&& eval) {
  for (std::size_t start = 0; start < inputs.size(); start += kDualWidth) {
    const int count = static_cast<int>(std::min<std::size_t>(kDualWidth, inputs.size() - start));
    for (int q = 0; q < count; ++q) slot[static_cast<std::size_t>(inputs[start + static_cast<std::size_t>(q)])] = q;
    eval(&inputs[start], count);
    for (int q = 0; q < count; ++q) slot[static_cast<std::size_t>(inputs[start + static_cast<std::size_t>(q)])] = -1;
  }
}

// D row r += weight d' (d = g - K u of the dual row) over the window of inputs.
inline void scatter_d(const Dual& d, int r, double weight, const int* window, int count,
               std::vector<Eigen::Triplet<double>>& d_trip) {
  for (int q = 0; q < count; ++q) {
    const double v = d.slot(q);
    if (v != 0.0) d_trip.emplace_back(r, window[q], weight * v);
  }
}

// H += load (K row)' on the movable rows (H = (K' lambda)' with lambda frozen).
template <class Row>
void scatter_h(const Row& row, double load, const int* window, int count, const std::vector<char>& movable,
               std::vector<Eigen::Triplet<double>>& h_trip) {
  if (load == 0.0) return;
  for (const auto& [dof, k] : row.K) {
    if (!movable[static_cast<std::size_t>(dof)]) continue;
    for (int q = 0; q < count; ++q) {
      const double v = k.slot(q);
      if (v != 0.0) h_trip.emplace_back(dof, window[q], load * v);
    }
  }
}

// The pointwise row of slave position s (Collocation, LACSimpson: rows = W * pointwise) into D
// (column s of W, Wc = W column-major) and H (its load, (W' lambda)_s), over the window of inputs.
template <class Row, class Geometry>
void scatter_pointwise(const Row& row, const Geometry& geo, const Eigen::SparseMatrix<double>& Wc, int s, double load,
                       const int* window, int count, const std::vector<char>& movable,
                       std::vector<Eigen::Triplet<double>>& d_trip, std::vector<Eigen::Triplet<double>>& h_trip) {
  const Dual d = row.gap(geo);
  for (Eigen::SparseMatrix<double>::InnerIterator it(Wc, s); it; ++it) {
    scatter_d(d, static_cast<int>(it.row()), it.value(), window, count, d_trip);
  }
  scatter_h(row, load, window, count, movable, h_trip);
}

// D (R x N) and H (N x N) from their triplets.
template <class Linearization>
void set_from_triplets(Linearization& lin, Eigen::Index R, Eigen::Index N,
                       const std::vector<Eigen::Triplet<double>>& d_trip,
                       const std::vector<Eigen::Triplet<double>>& h_trip) {
  lin.D.resize(R, N);
  lin.D.setFromTriplets(d_trip.begin(), d_trip.end());
  lin.H.resize(N, N);
  lin.H.setFromTriplets(h_trip.begin(), h_trip.end());
}

}  // namespace contactrb::contact::detail
