#include "contactrb/contact/lac_integration.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/master_polyline.hpp"

namespace contactrb::contact {

namespace {

using Vec2 = Eigen::Vector2d;

const Vec2& ref(const mesh::Mesh& mesh, int node) { return mesh.nodes[static_cast<std::size_t>(node)]; }

// Master abscissa of a slave node's projection: L_k + xi |segment k| for a candidate; for a
// non-candidate (beyond an end of an open chain) the abscissa of its projection on the line
// of the end segment, i.e. extrapolated beyond 0 or L.
double node_abscissa(const MasterPolyline& m, const SlaveProjection& p, const Vec2& x) {
  const int k = p.segment;
  const double L0 = m.abscissa[static_cast<std::size_t>(k)];
  const double len = m.abscissa[static_cast<std::size_t>(k + 1)] - L0;
  if (p.candidate || m.closed) return L0 + p.xi * len;
  const Vec2& a = m.y[static_cast<std::size_t>(k)];
  const Vec2 e = m.y[static_cast<std::size_t>(k + 1)] - a;
  const double t_raw = (x - a).dot(e) / e.squaredNorm();
  // Beyond the start t_raw < 0, beyond the end t_raw > 1 (candidate rule of projection.cpp).
  return L0 + t_raw * len;
}

// Segment holding abscissa s in [0, L] (the lower one at an interior vertex, clamped into the chain).
int locate(const MasterPolyline& m, double s) {
  const auto it = std::upper_bound(m.abscissa.begin(), m.abscissa.end(), s);
  const int k = static_cast<int>(it - m.abscissa.begin()) - 1;
  return std::clamp(k, 0, m.num_segments() - 1);
}

// Last slave chain position of macro-segment r: 2r + 2, or 2r + 1 for a single-edge last row.
int last_slave_of_row(int r, int num_slave) { return std::min(2 * r + 2, num_slave - 1); }

struct RowAssembler {
  std::vector<Eigen::Triplet<double>> entries;
  void add(int row, int node, double c, const Vec2& n) {
    if (c == 0.0) return;
    entries.emplace_back(row, 2 * node, c * n.x());
    entries.emplace_back(row, 2 * node + 1, c * n.y());
  }
};

// Adds int over slave edge (na, nb) of k(w; .) and g(w) to row r.
void integrate_edge(const mesh::Mesh& mesh, const ContactPair& pair, const MasterPolyline& m,
                    const PointwiseContact& pointwise, const Eigen::VectorXd& w, int edge, int r,
                    RowAssembler& K, Eigen::VectorXd& g) {
  // 2-point Gauss on [0, 1].
  static const double kGauss[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  const int na = pair.slave[static_cast<std::size_t>(edge)];
  const int nb = pair.slave[static_cast<std::size_t>(edge + 1)];
  const Vec2& Xa = ref(mesh, na);
  const Vec2& Xb = ref(mesh, nb);
  const Vec2 xa = Xa + w.segment<2>(2 * na);
  const Vec2 xb = Xb + w.segment<2>(2 * nb);
  const double len = (Xb - Xa).norm();
  const double L = m.length();
  const int M = m.num_segments();

  const double sa = node_abscissa(m, pointwise.projection[static_cast<std::size_t>(edge)], xa);
  double sb = node_abscissa(m, pointwise.projection[static_cast<std::size_t>(edge + 1)], xb);
  if (m.closed) {  // the shorter way round the loop
    if (sb - sa > 0.5 * L) sb -= L;
    if (sa - sb > 0.5 * L) sb += L;
  }

  // Split [0, 1] where S(t) = sa + t (sb - sa) crosses a master vertex (the ends included).
  std::vector<double> cuts = {0.0, 1.0};
  const double lo = std::min(sa, sb), hi = std::max(sa, sb);
  if (hi > lo) {
    const double shift_min = m.closed ? std::floor(lo / L) - 1.0 : 0.0;
    const double shift_max = m.closed ? std::floor(hi / L) + 1.0 : 0.0;
    for (double shift = shift_min; shift <= shift_max; shift += 1.0) {
      for (int j = 0; j <= M; ++j) {
        const double v = m.abscissa[static_cast<std::size_t>(j)] + shift * L;
        if (v > lo && v < hi) cuts.push_back((v - sa) / (sb - sa));
      }
    }
    std::sort(cuts.begin(), cuts.end());
  }

  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double t0 = cuts[i], t1 = cuts[i + 1];
    if (!(t1 > t0)) continue;
    const double c = 0.5 * (t1 - t0) * len;  // Gauss weight times the line element
    double s_mid = sa + 0.5 * (t0 + t1) * (sb - sa);
    double offset = 0.0;  // closed chain: S modulo L
    if (m.closed) offset = std::floor(s_mid / L) * L;
    s_mid -= offset;
    const bool beyond = !m.closed && (s_mid < 0.0 || s_mid > L);
    const int k = locate(m, s_mid);
    const double Lk = m.abscissa[static_cast<std::size_t>(k)];
    const double lk = m.abscissa[static_cast<std::size_t>(k + 1)] - Lk;
    const int ma = pair.master[static_cast<std::size_t>(k)];
    const int mb = pair.master[static_cast<std::size_t>(k + 1)];
    for (double gq : kGauss) {
      const double t = t0 + gq * (t1 - t0);
      const Vec2 X = (1.0 - t) * Xa + t * Xb;
      if (beyond) {
        // No master faces this piece: zero K, g = distance to the master end (> 0).
        const Vec2 x = (1.0 - t) * xa + t * xb;
        g(r) += c * (x - (s_mid < 0.0 ? m.y.front() : m.y.back())).norm();
        continue;
      }
      const double s = sa + t * (sb - sa) - offset;
      const double xi = std::clamp((s - Lk) / lk, 0.0, 1.0);
      const Vec2 n2 = m.normal_at(k, xi);
      const Vec2 rho = (1.0 - xi) * ref(mesh, ma) + xi * ref(mesh, mb);
      g(r) += c * (X - rho).dot(n2);
      K.add(r, na, -(1.0 - t) * c, n2);
      K.add(r, nb, -t * c, n2);
      K.add(r, ma, (1.0 - xi) * c, n2);
      K.add(r, mb, xi * c, n2);
    }
  }
}

}  // namespace

ConstraintRows integrate_lac_rows(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                                  const PointwiseContact& pointwise, const Eigen::VectorXd& w) {
  std::vector<int> all(static_cast<std::size_t>(quadrature.W.rows()));
  for (std::size_t r = 0; r < all.size(); ++r) all[r] = static_cast<int>(r);
  return integrate_lac_rows(mesh, pair, quadrature, pointwise, w, all);
}

ConstraintRows integrate_lac_rows(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                                  const PointwiseContact& pointwise, const Eigen::VectorXd& w,
                                  std::span<const int> rows) {
  const int S = static_cast<int>(pair.slave.size());
  const int E = S - 1;
  const int R = (E + 1) / 2;
  require(S >= 2 && quadrature.W.rows() == R && quadrature.W.cols() == S,
          "integrate_lac_rows: the quadrature is " + std::to_string(quadrature.W.rows()) + " x " +
              std::to_string(quadrature.W.cols()) + " but " + std::to_string(S) + " slave nodes need " +
              std::to_string(R) + " LAC rows");
  require(static_cast<int>(pointwise.projection.size()) == S,
          "integrate_lac_rows: " + std::to_string(pointwise.projection.size()) + " projections for " +
              std::to_string(S) + " slave nodes");
  require(w.size() == mesh.num_dofs(), "integrate_lac_rows: displacement has size " + std::to_string(w.size()) +
                                           " but the mesh has " + std::to_string(mesh.num_dofs()) + " DOFs");
  const MasterPolyline m = deformed_master(mesh, pair.master, w);
  RowAssembler K;
  K.entries.reserve(rows.size() * 64);
  ConstraintRows out;
  out.g = Eigen::VectorXd::Zero(R);
  std::vector<char> done(static_cast<std::size_t>(R), 0);
  for (const int r : rows) {
    if (r < 0 || r >= R) {
      throw Error("integrate_lac_rows: row " + std::to_string(r) + " outside [0, " + std::to_string(R) + ")");
    }
    if (done[static_cast<std::size_t>(r)] != 0) continue;  // a repeated row
    done[static_cast<std::size_t>(r)] = 1;
    for (int s = 2 * r; s <= last_slave_of_row(r, S); ++s) {
      if (pointwise.projection[static_cast<std::size_t>(s)].segment < 0) {
        throw Error("integrate_lac_rows: row " + std::to_string(r) + " needs slave position " + std::to_string(s) +
                    ", which was not projected");
      }
    }
    for (int e = 2 * r; e < std::min(2 * r + 2, E); ++e) integrate_edge(mesh, pair, m, pointwise, w, e, r, K, out.g);
  }
  out.K.resize(R, mesh.num_dofs());
  out.K.setFromTriplets(K.entries.begin(), K.entries.end());
  out.K.prune(0.0);
  out.K.makeCompressed();
  return out;
}

std::vector<int> lac_slave_positions(std::span<const int> rows, int num_slave) {
  std::vector<int> positions;
  for (const int r : rows) {
    for (int s = 2 * r; s <= last_slave_of_row(r, num_slave); ++s) positions.push_back(s);
  }
  std::sort(positions.begin(), positions.end());
  positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
  return positions;
}

}  // namespace contactrb::contact
