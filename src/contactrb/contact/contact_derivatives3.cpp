// The analytic linearization of the 3D collocation rows (contact_derivatives.hpp): the
// pointwise maps of projection.cpp and master_surface.cpp in dual numbers, on the branches the
// projection took at u.
#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "contactrb/contact/contact_derivatives.hpp"
#include "contactrb/contact/local_dual.hpp"

namespace contactrb::contact::detail {

namespace {

using Vec3 = Eigen::Vector3d;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

std::size_t sz(int i) { return static_cast<std::size_t>(i); }

void sort_unique(std::vector<int>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// CSR: the master triangles at each master vertex (positions in pair.master).
struct VertexFaces {
  std::vector<int> start, faces;
  explicit VertexFaces(const ContactPair3& pair) : start(pair.master.size() + 1, 0) {
    for (const auto& t : pair.master_faces) {
      for (int v : t) ++start[sz(v) + 1];
    }
    for (std::size_t v = 0; v + 1 < start.size(); ++v) start[v + 1] += start[v];
    faces.resize(sz(start.back()));
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < pair.master_faces.size(); ++f) {
      for (int v : pair.master_faces[f]) faces[sz(fill[sz(v)]++)] = static_cast<int>(f);
    }
  }
};

// The deformed master surface and slave nodes as dual numbers (the DOFs with a slot of the
// current pass carry derivatives).
class DualSurface {
 public:
  DualSurface(const mesh::Mesh3& mesh, const ContactPair3& pair, const VertexFaces& around, const Eigen::VectorXd& u,
              const std::vector<int>& slot)
      : mesh_(mesh), pair_(pair), around_(around), u_(u), slot_(slot) {}

  DVec3 node(int v) const {
    const Vec3& X = mesh_.nodes[sz(v)];
    return {Dual::input(X.x() + u_(3 * v), slot_[sz(3 * v)]), Dual::input(X.y() + u_(3 * v + 1), slot_[sz(3 * v + 1)]),
            Dual::input(X.z() + u_(3 * v + 2), slot_[sz(3 * v + 2)])};
  }
  DVec3 y(int j) const { return node(pair_.master[sz(j)]); }
  const std::array<int, 3>& face(int f) const { return pair_.master_faces[sz(f)]; }
  // Unit normal of triangle f (master_surface.cpp deformed_master).
  DVec3 face_normal(int f) const {
    const auto& t = face(f);
    const DVec3 n = cross(y(t[1]) - y(t[0]), y(t[2]) - y(t[0]));
    return n / norm(n);
  }
  // n_j: the angle-weighted average of the normals of the triangles at j (master_surface.cpp
  // vertex_normals; its shortcut for coplanar triangles returns the same value).
  DVec3 vertex_normal(int j) const {
    DVec3 sum{Dual(0.0), Dual(0.0), Dual(0.0)};
    for (int k = around_.start[sz(j)]; k < around_.start[sz(j) + 1]; ++k) {
      const int f = around_.faces[sz(k)];
      const auto& t = face(f);
      const int i = static_cast<int>(std::find(t.begin(), t.end(), j) - t.begin());
      const DVec3 p = y(j);
      const DVec3 e1 = y(t[sz((i + 1) % 3)]) - p, e2 = y(t[sz((i + 2) % 3)]) - p;
      sum = sum + atan2(norm(cross(e1, e2)), dot(e1, e2)) * face_normal(f);
    }
    const Dual len = norm(sum);
    return len.v > 0.0 ? sum / len : face_normal(around_.faces[sz(around_.start[sz(j)])]);  // a fold
  }
  // n2 = normalize(sum_i phi_i n_{t_i}) (MasterSurface::normal_at), on the branch of the
  // projection's own coordinates `at`.
  DVec3 normal_at(int f, const Vec3& at, const std::array<Dual, 3>& phi) const {
    const auto& t = face(f);
    for (int i = 0; i < 3; ++i) {
      if (at(i) == 1.0) return vertex_normal(t[sz(i)]);
    }
    DVec3 n = phi[0] * vertex_normal(t[0]);
    n = n + phi[1] * vertex_normal(t[1]);
    n = n + phi[2] * vertex_normal(t[2]);
    const Dual len = norm(n);
    return len.v > 0.0 ? n / len : face_normal(f);
  }
  // The barycentric coordinates of the closest point on the branch of `p` (triangle_hit.hpp):
  // the face (x projected on the plane), an edge (on its line) or a vertex (constants).
  std::array<Dual, 3> phi(const SlaveProjection3& p, const DVec3& x) const {
    const auto& t = face(p.facet);
    const int zeros = (p.phi(0) == 0.0) + (p.phi(1) == 0.0) + (p.phi(2) == 0.0);
    if (zeros >= 2) return {Dual(p.phi(0)), Dual(p.phi(1)), Dual(p.phi(2))};
    if (zeros == 1) {
      int k = 0;
      while (p.phi(k) != 0.0) ++k;
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const DVec3 a = y(t[sz(i)]), e = y(t[sz(j)]) - a;
      const Dual s = dot(x - a, e) / dot(e, e);
      std::array<Dual, 3> out{Dual(0.0), Dual(0.0), Dual(0.0)};
      out[sz(i)] = 1.0 - s;
      out[sz(j)] = s;
      return out;
    }
    const DVec3 a = y(t[0]), ab = y(t[1]) - a, ac = y(t[2]) - a, ap = x - a;
    const Dual m11 = dot(ab, ab), m12 = dot(ab, ac), m22 = dot(ac, ac), r1 = dot(ab, ap), r2 = dot(ac, ap);
    const Dual det = m11 * m22 - m12 * m12;
    const Dual v = (m22 * r1 - m12 * r2) / det, w = (m11 * r2 - m12 * r1) / det;
    return {1.0 - v - w, v, w};
  }
  const Vec3& reference(int v) const { return mesh_.nodes[sz(v)]; }
  Dual dof(int i) const { return Dual::input(u_(i), slot_[sz(i)]); }

 private:
  const mesh::Mesh3& mesh_;
  const ContactPair3& pair_;
  const VertexFaces& around_;
  const Eigen::VectorXd& u_;
  const std::vector<int>& slot_;
};

using DualRow3 = DualRowOf<3, DVec3>;  // one row's g and K entries as duals (local_dual.hpp)

// Pointwise maps of slave position s (projection.hpp (27)-(28), 3D).
DualRow3 pointwise_row(const DualSurface& geo, const ContactPair3& pair, const PointwiseContact3& pw, int s) {
  const SlaveProjection3& p = pw.projection[sz(s)];
  const int node = pair.slave[sz(s)];
  const auto& t = geo.face(p.facet);
  const DVec3 x = geo.node(node);
  const std::array<Dual, 3> phi = geo.phi(p, x);
  DualRow3 row;
  if (!p.candidate) {  // g = distance to the master, zero K row
    DVec3 q = phi[0] * geo.y(t[0]);
    q = q + phi[1] * geo.y(t[1]);
    q = q + phi[2] * geo.y(t[2]);
    row.g = norm(x - q);
    return row;
  }
  const DVec3 n2 = geo.normal_at(p.facet, p.phi, phi);
  DVec3 rho = phi[0] * constant3(geo.reference(pair.master[sz(t[0])]));
  rho = rho + phi[1] * constant3(geo.reference(pair.master[sz(t[1])]));
  rho = rho + phi[2] * constant3(geo.reference(pair.master[sz(t[2])]));
  row.g = dot(constant3(geo.reference(node)) - rho, n2);
  for (int i = 0; i < 3; ++i) row.add(pair.master[sz(t[sz(i)])], phi[sz(i)], n2);
  row.add(node, Dual(-1.0), n2);
  return row;
}

// Appends the movable DOFs of slave position p's pointwise maps: its node and the master vertices
// of the triangles around each vertex of the triangle it projects onto.
void add_node_inputs(const ContactPair3& pair, const VertexFaces& around, const PointwiseContact3& pw,
                     const std::vector<char>& movable, std::size_t p, std::vector<int>& in) {
  const auto add_node = [&movable, &in](int node) {
    for (int c = 0; c < 3; ++c) {
      if (movable[sz(3 * node + c)]) in.push_back(3 * node + c);
    }
  };
  add_node(pair.slave[p]);
  const int f = pw.projection[p].facet;
  if (f < 0) return;
  for (int v : pair.master_faces[sz(f)]) {
    for (int k = around.start[sz(v)]; k < around.start[sz(v) + 1]; ++k) {
      for (int w : pair.master_faces[sz(around.faces[sz(k)])]) add_node(pair.master[sz(w)]);
    }
  }
}

}  // namespace

std::vector<std::vector<int>> row_inputs(const ContactPair3& pair, const ContactQuadrature& quadrature,
                                         const PointwiseContact3& pw, const std::vector<char>& movable) {
  const VertexFaces around(pair);
  std::vector<std::vector<int>> inputs(sz(static_cast<int>(quadrature.W.rows())));
  for (int r = 0; r < quadrature.W.rows(); ++r) {
    std::vector<int>& in = inputs[sz(r)];
    for (RowSparse::InnerIterator it(quadrature.W, r); it; ++it) {
      add_node_inputs(pair, around, pw, movable, static_cast<std::size_t>(it.col()), in);
    }
    sort_unique(in);
  }
  return inputs;
}

std::vector<std::vector<int>> lac_row_inputs(const ContactPair3& pair, const ContactQuadrature& quadrature,
                                             const PointwiseContact3& pw, const ConstraintRows& rows,
                                             const std::vector<char>& movable) {
  std::vector<std::vector<int>> inputs = row_inputs(pair, quadrature, pw, movable);
  const VertexFaces around(pair);
  const auto add_node = [&movable](int node, std::vector<int>& in) {
    for (int c = 0; c < 3; ++c) {
      if (movable[sz(3 * node + c)]) in.push_back(3 * node + c);
    }
  };
  for (int r = 0; r < rows.K.rows(); ++r) {
    std::vector<int>& in = inputs[sz(r)];
    for (RowSparse::InnerIterator it(rows.K, r); it; ++it) {
      const int node = static_cast<int>(it.col()) / 3;
      const auto m = std::lower_bound(pair.master.begin(), pair.master.end(), node);
      if (m == pair.master.end() || *m != node) continue;  // a slave node: in W's row already
      const int j = static_cast<int>(m - pair.master.begin());
      for (int k = around.start[sz(j)]; k < around.start[sz(j) + 1]; ++k) {
        for (int v : pair.master_faces[sz(around.faces[sz(k)])]) add_node(pair.master[sz(v)], in);
      }
    }
    sort_unique(in);
  }
  return inputs;
}

void analytic_linearization(const mesh::Mesh3& mesh, const ContactPair3& pair, const ContactQuadrature& quadrature,
                            const Eigen::VectorXd& u, const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                            ContactLinearization3& lin) {
  const int N = mesh.num_dofs();
  const int R = static_cast<int>(quadrature.W.rows());
  const PointwiseContact3& pw = lin.maps.pointwise;
  std::vector<int> slot(sz(N), -1);
  const VertexFaces around(pair);
  const DualSurface geo(mesh, pair, around, u, slot);
  std::vector<Eigen::Triplet<double>> d_trip, h_trip;
  // rows = W * pointwise: D = W d_pt', H = sum_s (W' lambda)_s K_pt,s'.
  const Eigen::SparseMatrix<double> Wc = quadrature.W;  // column access: the rows of slave node s
  const Eigen::VectorXd load = quadrature.W.transpose() * lambda;
  std::vector<int> in;
  for (int s = 0; s < Wc.cols(); ++s) {
    if (pw.projection[sz(s)].facet < 0 || Wc.outerIndexPtr()[s + 1] == Wc.outerIndexPtr()[s]) continue;
    in.clear();
    add_node_inputs(pair, around, pw, movable, sz(s), in);
    sort_unique(in);
    in_passes(in, slot, [&](const int* window, int count) {
      scatter_pointwise(pointwise_row(geo, pair, pw, s), geo, Wc, s, load(s), window, count, movable, d_trip, h_trip);
    });
  }
  set_from_triplets(lin, R, N, d_trip, h_trip);
}

}  // namespace contactrb::contact::detail
