#include "contactrb/contact/contact_derivatives.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "contactrb/contact/local_dual.hpp"
#include "contactrb/contact/master_polyline.hpp"

namespace contactrb::contact::detail {

namespace {

using Vec2 = Eigen::Vector2d;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

void sort_unique(std::vector<int>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// The deformed geometry as dual numbers: node positions X + u whose DOFs carry the derivative
// slots of the current pass (slot[dof] >= 0), everything else constant.
class DualGeometry {
 public:
  DualGeometry(const mesh::Mesh& mesh, const ContactPair& pair, const Eigen::VectorXd& u, const std::vector<int>& slot)
      : mesh_(mesh), pair_(pair), u_(u), slot_(slot) {
    closed_ = pair.master.size() > 2 && pair.master.front() == pair.master.back();
    M_ = static_cast<int>(pair.master.size()) - 1;
  }
  bool closed() const { return closed_; }
  int segments() const { return M_; }

  Dual dof(int i) const { return Dual::input(u_(i), slot_[static_cast<std::size_t>(i)]); }
  DVec2 node(int v) const {
    const Vec2& X = mesh_.nodes[static_cast<std::size_t>(v)];
    return {Dual::input(X.x() + u_(2 * v), slot_[static_cast<std::size_t>(2 * v)]),
            Dual::input(X.y() + u_(2 * v + 1), slot_[static_cast<std::size_t>(2 * v + 1)])};
  }
  const Vec2& reference(int v) const { return mesh_.nodes[static_cast<std::size_t>(v)]; }
  // Chain position j (wrapped on a closed chain) -> mesh node.
  int master_node(int j) const { return pair_.master[static_cast<std::size_t>(wrap(j))]; }
  DVec2 y(int j) const { return node(master_node(j)); }
  DVec2 edge(int q) const { return y(q + 1) - y(q); }
  Dual length(int q) const { return norm(edge(q)); }
  // Outward normal of segment q: (dy, -dx) / |e| (master_polyline.cpp).
  DVec2 segment_normal(int q) const {
    const DVec2 e = edge(q);
    const Dual l = norm(e);
    return {e.y / l, -e.x / l};
  }
  // n_j: the normalized average of the adjacent segment normals; an open chain's ends take
  // their only segment's normal.
  DVec2 vertex_normal(int j) const {
    if (!closed_ && j == 0) return segment_normal(0);
    if (!closed_ && j == M_) return segment_normal(M_ - 1);
    const DVec2 nl = segment_normal(j - 1), nr = segment_normal(j);
    const DVec2 s = nl + nr;
    const Dual l = norm(s);
    return l.v > 0.0 ? s / l : nl;
  }
  // n2 = normalize((1 - xi) n_k + xi n_k+1) (MasterPolyline::normal_at).
  DVec2 normal_at(int k, const Dual& xi) const {
    const DVec2 na = vertex_normal(k), nb = vertex_normal(k + 1);
    const DVec2 m = (1.0 - xi) * na + xi * nb;
    const Dual l = norm(m);
    return l.v > 0.0 ? m / l : segment_normal(k);
  }
  // Unclamped projection parameter of x on the line of segment k.
  Dual t_raw(int k, const DVec2& x) const {
    const DVec2 a = y(k), e = edge(k);
    return dot(x - a, e) / dot(e, e);
  }
  // Arc length from chain vertex j0 to the unwrapped vertex J (J - j0 may be negative, or cross
  // the start of a closed chain): only the segments in between, so the derivative stays local.
  Dual arc(int j0, int J) const {
    Dual s(0.0);
    for (int q = std::min(j0, J); q < std::max(j0, J); ++q) s += length(q);
    return J >= j0 ? s : -s;
  }

 private:
  int wrap(int j) const { return closed_ ? ((j % M_) + M_) % M_ : j; }

  const mesh::Mesh& mesh_;
  const ContactPair& pair_;
  const Eigen::VectorXd& u_;
  const std::vector<int>& slot_;
  bool closed_ = false;
  int M_ = 0;
};

// xi of a projection as a dual: the clamped values 0 and 1 are constants (the branch taken at u).
Dual projection_xi(const DualGeometry& geo, const SlaveProjection& p, const DVec2& x) {
  if (p.xi == 0.0) return Dual(0.0);
  if (p.xi == 1.0) return Dual(1.0);
  return geo.t_raw(p.segment, x);
}

using DualRow = DualRowOf<2, DVec2>;  // one row's g and K entries as duals (local_dual.hpp)

// Pointwise maps of slave position s (projection.cpp (27)-(28)): g_s and the K row.
DualRow pointwise_row(const DualGeometry& geo, const ContactPair& pair, const PointwiseContact& pw, int s) {
  const SlaveProjection& p = pw.projection[static_cast<std::size_t>(s)];
  const int node = pair.slave[static_cast<std::size_t>(s)];
  const int k = p.segment;
  const DVec2 x = geo.node(node);
  const Dual xi = projection_xi(geo, p, x);
  DualRow row;
  if (!p.candidate) {  // g = distance to the master (an end vertex), zero K row
    const DVec2 a = geo.y(k), e = geo.edge(k);
    row.g = norm(x - (a + xi * e));
    return row;
  }
  const DVec2 n2 = geo.normal_at(k, xi);
  const Vec2& Xa = geo.reference(geo.master_node(k));
  const Vec2& Xb = geo.reference(geo.master_node(k + 1));
  const DVec2 rho = constant(Xa) + xi * constant(Xb - Xa);
  row.g = dot(constant(geo.reference(node)) - rho, n2);
  row.add(geo.master_node(k), 1.0 - xi, n2);
  row.add(geo.master_node(k + 1), xi, n2);
  row.add(node, Dual(-1.0), n2);
  return row;
}

// Master abscissa of a projection (lac_integration.cpp node_abscissa) relative to chain vertex
// j0, the projection's segment counted `shift` turns round a closed chain.
Dual node_arc(const DualGeometry& geo, const SlaveProjection& p, const DVec2& x, int j0, int shift) {
  const int k = p.segment;
  const Dual base = geo.arc(j0, k + shift * geo.segments());
  if (p.candidate || geo.closed()) return base + projection_xi(geo, p, x) * geo.length(k);
  return base + geo.t_raw(k, x) * geo.length(k);
}

double node_abscissa(const MasterPolyline& m, const SlaveProjection& p, const Vec2& x) {
  const int k = p.segment;
  const double L0 = m.abscissa[static_cast<std::size_t>(k)];
  const double len = m.abscissa[static_cast<std::size_t>(k + 1)] - L0;
  if (p.candidate || m.closed) return L0 + p.xi * len;
  const Vec2& a = m.y[static_cast<std::size_t>(k)];
  const Vec2 e = m.y[static_cast<std::size_t>(k + 1)] - a;
  return L0 + ((x - a).dot(e) / e.squaredNorm()) * len;
}

int locate(const MasterPolyline& m, double s) {
  const auto it = std::upper_bound(m.abscissa.begin(), m.abscissa.end(), s);
  const int k = static_cast<int>(it - m.abscissa.begin()) - 1;
  return std::clamp(k, 0, m.num_segments() - 1);
}

// One slave edge of an exactly integrated LAC row (lac_integration.cpp integrate_edge, line by
// line): the branches (cuts, pieces, segments, clamping) from the double values at u, the
// values and derivatives from the duals.
void lac_edge(const DualGeometry& geo, const mesh::Mesh& mesh, const ContactPair& pair, const MasterPolyline& m,
              const PointwiseContact& pw, const Eigen::VectorXd& w, int edge, DualRow& row) {
  static const double kGauss[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  const int na = pair.slave[static_cast<std::size_t>(edge)];
  const int nb = pair.slave[static_cast<std::size_t>(edge + 1)];
  const Vec2& Xa = mesh.nodes[static_cast<std::size_t>(na)];
  const Vec2& Xb = mesh.nodes[static_cast<std::size_t>(nb)];
  const Vec2 xa = Xa + w.segment<2>(2 * na);
  const Vec2 xb = Xb + w.segment<2>(2 * nb);
  const DVec2 xa_d = geo.node(na), xb_d = geo.node(nb);
  const double len = (Xb - Xa).norm();
  const double L = m.length();
  const int M = m.num_segments();
  const SlaveProjection& pa = pw.projection[static_cast<std::size_t>(edge)];
  const SlaveProjection& pb = pw.projection[static_cast<std::size_t>(edge + 1)];

  const double sa = node_abscissa(m, pa, xa);
  double sb = node_abscissa(m, pb, xb);
  int shift_b = 0;
  if (m.closed) {
    if (sb - sa > 0.5 * L) {
      sb -= L;
      --shift_b;
    }
    if (sa - sb > 0.5 * L) {
      sb += L;
      ++shift_b;
    }
  }
  const int j0 = pa.segment;  // abscissae of the duals: relative to this vertex
  const Dual sa_d = node_arc(geo, pa, xa_d, j0, 0);
  const Dual sb_d = node_arc(geo, pb, xb_d, j0, shift_b);

  struct Cut {
    double t;
    Dual td;
  };
  std::vector<Cut> cuts = {{0.0, Dual(0.0)}, {1.0, Dual(1.0)}};
  const double lo = std::min(sa, sb), hi = std::max(sa, sb);
  if (hi > lo) {
    const double shift_min = m.closed ? std::floor(lo / L) - 1.0 : 0.0;
    const double shift_max = m.closed ? std::floor(hi / L) + 1.0 : 0.0;
    for (double shift = shift_min; shift <= shift_max; shift += 1.0) {
      for (int j = 0; j <= M; ++j) {
        const double v = m.abscissa[static_cast<std::size_t>(j)] + shift * L;
        if (v > lo && v < hi) {
          const Dual v_d = geo.arc(j0, j + static_cast<int>(shift) * M);
          cuts.push_back({(v - sa) / (sb - sa), (v_d - sa_d) / (sb_d - sa_d)});
        }
      }
    }
    std::sort(cuts.begin(), cuts.end(), [](const Cut& a, const Cut& b) { return a.t < b.t; });
  }

  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double t0 = cuts[i].t, t1 = cuts[i + 1].t;
    if (!(t1 > t0)) continue;
    const Dual& t0_d = cuts[i].td;
    const Dual& t1_d = cuts[i + 1].td;
    const Dual c = 0.5 * len * (t1_d - t0_d);
    double s_mid = sa + 0.5 * (t0 + t1) * (sb - sa);
    double offset = 0.0;
    int turns = 0;
    if (m.closed) {
      turns = static_cast<int>(std::floor(s_mid / L));
      offset = std::floor(s_mid / L) * L;
    }
    s_mid -= offset;
    const bool beyond = !m.closed && (s_mid < 0.0 || s_mid > L);
    const int k = locate(m, s_mid);
    const double Lk = m.abscissa[static_cast<std::size_t>(k)];
    const double lk = m.abscissa[static_cast<std::size_t>(k + 1)] - Lk;
    const int ma = pair.master[static_cast<std::size_t>(k)];
    const int mb = pair.master[static_cast<std::size_t>(k + 1)];
    for (double gq : kGauss) {
      const double t = t0 + gq * (t1 - t0);
      const Dual t_d = t0_d + gq * (t1_d - t0_d);
      if (beyond) {
        const DVec2 x = xa_d + t_d * (xb_d - xa_d);
        row.g += c * norm(x - (s_mid < 0.0 ? geo.y(0) : geo.y(M)));
        continue;
      }
      const double s = sa + t * (sb - sa) - offset;
      const double raw = (s - Lk) / lk;
      Dual xi;
      if (raw < 0.0) {
        xi = Dual(0.0);
      } else if (raw > 1.0) {
        xi = Dual(1.0);
      } else {
        xi = (sa_d + t_d * (sb_d - sa_d) - geo.arc(j0, k + turns * M)) / geo.length(k);
      }
      const DVec2 n2 = geo.normal_at(k, xi);
      const DVec2 X = constant(Xa) + t_d * constant(Xb - Xa);
      const DVec2 rho = constant(geo.reference(ma)) + xi * constant(geo.reference(mb) - geo.reference(ma));
      row.g += c * dot(X - rho, n2);
      row.add(na, -((1.0 - t_d) * c), n2);
      row.add(nb, -(t_d * c), n2);
      row.add(ma, (1.0 - xi) * c, n2);
      row.add(mb, xi * c, n2);
    }
  }
}

}  // namespace

std::vector<std::vector<int>> row_inputs(const ContactPair& pair, const ContactQuadrature& quadrature,
                                         const PointwiseContact& pw, const std::vector<char>& movable) {
  const int R = static_cast<int>(quadrature.W.rows());
  const bool closed = pair.master.size() > 2 && pair.master.front() == pair.master.back();
  const int M = static_cast<int>(pair.master.size()) - 1;  // segments
  const int vertices = closed ? M : M + 1;                  // distinct chain positions
  auto add_node = [&](std::vector<int>& out, int node) {
    for (int c = 0; c < 2; ++c) {
      const int dof = 2 * node + c;
      if (movable[static_cast<std::size_t>(dof)]) out.push_back(dof);
    }
  };
  auto add_position = [&](std::vector<int>& out, int pos) {
    if (closed) {
      pos = ((pos % vertices) + vertices) % vertices;
    } else if (pos < 0 || pos >= vertices) {
      return;
    }
    add_node(out, pair.master[static_cast<std::size_t>(pos)]);
  };
  std::vector<std::vector<int>> inputs(static_cast<std::size_t>(R));
  for (int r = 0; r < R; ++r) {
    std::vector<int>& in = inputs[static_cast<std::size_t>(r)];
    int lo = M, hi = -1;
    for (RowSparse::InnerIterator it(quadrature.W, r); it; ++it) {
      const int p = static_cast<int>(it.col());
      add_node(in, pair.slave[static_cast<std::size_t>(p)]);
      const int k = pw.projection[static_cast<std::size_t>(p)].segment;
      if (k < 0) continue;
      lo = std::min(lo, k);
      hi = std::max(hi, k);
    }
    if (hi >= 0) {
      if (closed && hi - lo > M / 2) {  // the hits wrap around the closed chain's start
        for (int pos = hi - 1; pos <= lo + M + 2; ++pos) add_position(in, pos);
      } else {
        for (int pos = lo - 1; pos <= hi + 2; ++pos) add_position(in, pos);
      }
    }
    sort_unique(in);
  }
  return inputs;
}

PointwiseContact pointwise_on_branches(const mesh::Mesh& mesh, const ContactPair& pair, const Eigen::VectorXd& u,
                                       const PointwiseContact& branches) {
  const int S = static_cast<int>(pair.slave.size());
  const std::vector<int> no_slots(static_cast<std::size_t>(mesh.num_dofs()), -1);  // values only
  const DualGeometry geo(mesh, pair, u, no_slots);
  PointwiseContact out;
  out.projection.resize(static_cast<std::size_t>(S));
  out.g.setZero(S);
  out.K.resize(S, mesh.num_dofs());
  out.K.reserve(Eigen::VectorXi::Constant(S, 6));
  for (int s = 0; s < S; ++s) {
    const SlaveProjection& b = branches.projection[static_cast<std::size_t>(s)];
    SlaveProjection& p = out.projection[static_cast<std::size_t>(s)];
    p = b;
    if (b.segment < 0) continue;
    const DVec2 x = geo.node(pair.slave[static_cast<std::size_t>(s)]);
    if (b.xi != 0.0 && b.xi != 1.0) p.xi = geo.t_raw(b.segment, x).v;  // the continued interior branch
    const DualRow row = pointwise_row(geo, pair, out, s);
    out.g(s) = row.g.v;
    if (!p.candidate) continue;
    const Dual xi = projection_xi(geo, p, x);
    p.normal = geo.normal_at(p.segment, xi).value();
    for (const auto& [dof, k] : row.K) {
      if (k.v != 0.0) out.K.coeffRef(s, dof) += k.v;
    }
  }
  out.K.makeCompressed();
  return out;
}

void analytic_linearization(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                            const Eigen::VectorXd& u, const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                            ContactLinearization& lin) {
  const int N = mesh.num_dofs();
  const int R = static_cast<int>(quadrature.W.rows());
  const PointwiseContact& pw = lin.maps.pointwise;
  std::vector<int> slot(static_cast<std::size_t>(N), -1);
  const DualGeometry geo(mesh, pair, u, slot);
  std::vector<Eigen::Triplet<double>> d_trip, h_trip;

  if (quadrature.discretization == Discretization::LAC) {
    const MasterPolyline m = deformed_master(mesh, pair.master, u);
    const std::vector<std::vector<int>> inputs = row_inputs(pair, quadrature, pw, movable);
    const int S = static_cast<int>(pair.slave.size());
    const int E = S - 1;
    for (int r = 0; r < R; ++r) {
      in_passes(inputs[static_cast<std::size_t>(r)], slot, [&](const int* window, int count) {
        DualRow row;
        for (int e = 2 * r; e < std::min(2 * r + 2, E); ++e) lac_edge(geo, mesh, pair, m, pw, u, e, row);
        scatter_d(row.gap(geo), r, 1.0, window, count, d_trip);
        scatter_h(row, lambda(r), window, count, movable, h_trip);
      });
    }
  } else {
    // rows = W * pointwise: D = W d_pt', H = sum_s (W' lambda)_s K_pt,s'.
    const Eigen::SparseMatrix<double> Wc = quadrature.W;  // column access: the rows of slave node s
    const Eigen::VectorXd load = quadrature.W.transpose() * lambda;
    const bool closed = pair.master.size() > 2 && pair.master.front() == pair.master.back();
    const int M = static_cast<int>(pair.master.size()) - 1;
    std::vector<int> in;
    for (int s = 0; s < Wc.cols(); ++s) {
      const int k = pw.projection[static_cast<std::size_t>(s)].segment;
      if (k < 0 || Wc.outerIndexPtr()[s + 1] == Wc.outerIndexPtr()[s]) continue;
      in.clear();
      auto add_node = [&](int node) {
        for (int c = 0; c < 2; ++c) {
          if (movable[static_cast<std::size_t>(2 * node + c)]) in.push_back(2 * node + c);
        }
      };
      add_node(pair.slave[static_cast<std::size_t>(s)]);
      for (int j = k - 1; j <= k + 2; ++j) {  // n_k, n_k+1 use segments k - 1 .. k + 1
        if (!closed && (j < 0 || j > M)) continue;
        add_node(geo.master_node(j));
      }
      sort_unique(in);
      in_passes(in, slot, [&](const int* window, int count) {
        scatter_pointwise(pointwise_row(geo, pair, pw, s), geo, Wc, s, load(s), window, count, movable, d_trip,
                          h_trip);
      });
    }
  }
  set_from_triplets(lin, R, N, d_trip, h_trip);
}

}  // namespace contactrb::contact::detail
