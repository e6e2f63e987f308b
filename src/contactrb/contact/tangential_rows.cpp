#include "contactrb/contact/tangential_rows.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <array>
#include <string>
#include <vector>

#include "contactrb/common/error.hpp"

namespace contactrb::contact {

template <>
Eigen::Matrix<double, 2, 1> tangent_basis<2>(const Eigen::Matrix<double, 2, 1>& n) {
  return Eigen::Vector2d(n.y(), -n.x());
}

// 3D (docs/solvers.md, "Friction", "Three dimensions"): with k the component of largest |n_k|
// and e the unit axis k + 1 (mod 3), tau_1 = normalize(e - (e . n) n), tau_2 = n x tau_1. The
// pair depends smoothly on n while k does not change, that is away from the directions where
// two components of n have the same magnitude (45 degrees from an axis): small sliding on a
// contact zone facing an axis never crosses them. n = (0, 0, 1): tau = (e_x, e_y).
template <>
Eigen::Matrix<double, 3, 2> tangent_basis<3>(const Eigen::Matrix<double, 3, 1>& n) {
  Eigen::Index k = 0;
  n.cwiseAbs().maxCoeff(&k);
  const Eigen::Vector3d e = Eigen::Vector3d::Unit((k + 1) % 3);
  Eigen::Matrix<double, 3, 2> tau;
  tau.col(0) = (e - e.dot(n) * n).normalized();
  tau.col(1) = n.cross(tau.col(0));
  return tau;
}

namespace {

inline std::size_t sz(Eigen::Index i) { return static_cast<std::size_t>(i); }

template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;

// The mesh nodes (t_0, ..., t_{Dim-1}) of the master facet a slave node projects on and the
// weights of its closest point on them (2D: (1 - xi, xi); 3D: phi).
std::array<int, 2> facet_nodes(const ContactPair& pair, const NodeProjection<2>& p) {
  return {pair.master[sz(p.segment)], pair.master[sz(p.segment + 1)]};
}
std::array<int, 3> facet_nodes(const ContactPair3& pair, const NodeProjection<3>& p) {
  const std::array<int, 3>& f = pair.master_faces[sz(p.facet)];
  return {pair.master[sz(f[0])], pair.master[sz(f[1])], pair.master[sz(f[2])]};
}
Eigen::Vector2d facet_weights(const NodeProjection<2>& p) { return Eigen::Vector2d(1.0 - p.xi, p.xi); }
Eigen::Vector3d facet_weights(const NodeProjection<3>& p) { return p.phi; }

// The unclamped facet parameters xi (Dim - 1) of the point of the facet's plane closest to a
// slave node, at the deformed positions x = (x_s, x_{t_0}, ..., x_{t_{Dim-1}}), and their
// derivative d xi_k = sum_n g[n].col(k) . dw_n (n = 0 the slave node, n = 1 + i facet node t_i).
template <int Dim>
struct ParameterDerivative {
  Vec<Dim - 1> xi;
  std::array<Eigen::Matrix<double, Dim, Dim - 1>, Dim + 1> g;
};

// 2D: xi = (x_s - x_a) . e / |e|^2, e = x_b - x_a.
ParameterDerivative<2> parameter_derivative(const std::array<Eigen::Vector2d, 3>& x) {
  const Eigen::Vector2d e = x[2] - x[1], sa = x[0] - x[1];
  ParameterDerivative<2> d;
  d.xi(0) = sa.dot(e) / e.squaredNorm();
  const Eigen::Vector2d gb = (sa - 2.0 * d.xi(0) * e) / e.squaredNorm();  // the coefficient of dw_b - dw_a
  d.g[0] = e / e.squaredNorm();
  d.g[1] = -d.g[0] - gb;
  d.g[2] = gb;
  return d;
}

// 3D: E = (x_1 - x_0, x_2 - x_0), G = E'E, xi = G^-1 E'(x_s - x_0), r = x_s - x_0 - E xi (normal to
// the facet). From E'r = 0: G d xi = dE' r + E' dq, dq = dw_s - sum_i phi_i dw_{t_i}, phi the
// weights (1 - xi_0 - xi_1, xi_0, xi_1).
ParameterDerivative<3> parameter_derivative(const std::array<Eigen::Vector3d, 4>& x) {
  Eigen::Matrix<double, 3, 2> E;
  E << x[2] - x[1], x[3] - x[1];
  const Eigen::Matrix2d Gi = (E.transpose() * E).inverse();
  const Eigen::Vector3d p = x[0] - x[1];
  ParameterDerivative<3> d;
  d.xi = Gi * (E.transpose() * p);
  const Eigen::Vector3d r = p - E * d.xi;
  const Eigen::Vector3d phi(1.0 - d.xi(0) - d.xi(1), d.xi(0), d.xi(1));
  const Eigen::Matrix<double, 3, 2> m = E * Gi;  // column k: sum_i Gi(k, i) e_i
  d.g[0] = m;
  for (int i = 0; i < 3; ++i) d.g[sz(1 + i)] = -phi(i) * m;
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i < 2; ++i) {  // dE_i = dw_{t_{i+1}} - dw_{t_0}
      d.g[sz(2 + i)].col(k) += Gi(k, i) * r;
      d.g[1].col(k) -= Gi(k, i) * r;
    }
  }
  return d;
}

// The quadrature W (R x S) acting on Dim - 1 rows per slave node: W itself in 2D, W (x) I in 3D.
template <int Dim>
Eigen::SparseMatrix<double, Eigen::RowMajor> tangential_weights(const ContactQuadrature& quadrature) {
  constexpr int M = Dim - 1;
  if constexpr (M == 1) {
    return quadrature.W;
  } else {
    std::vector<Eigen::Triplet<double>> trip;
    for (int r = 0; r < quadrature.W.outerSize(); ++r) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator w(quadrature.W, r); w; ++w) {
        for (int j = 0; j < M; ++j) trip.emplace_back(M * r + j, M * w.col() + j, w.value());
      }
    }
    Eigen::SparseMatrix<double, Eigen::RowMajor> WM(M * quadrature.W.rows(), M * quadrature.W.cols());
    WM.setFromTriplets(trip.begin(), trip.end());
    return WM;
  }
}

template <int Dim>
void require_collocation(const ContactQuadrature& quadrature) {
  require(quadrature.discretization == Discretization::Collocation,
          std::string("friction needs the collocation rows (one per slave node), not '") +
              to_string(quadrature.discretization) + "'");
}

// The pointwise tangential rows of slave position q.
template <int Dim>
void add_pointwise_rows(const ContactPairOf<Dim>& pair, const NodeProjection<Dim>& p, int q,
                        std::vector<Eigen::Triplet<double>>& trip) {
  constexpr int M = Dim - 1;
  if (!p.candidate) return;
  const Eigen::Matrix<double, Dim, M> tau = tangent_basis<Dim>(p.normal);
  const std::array<int, Dim> t = facet_nodes(pair, p);
  const Vec<Dim> weights = facet_weights(p);
  const int s = pair.slave[sz(q)];
  for (int j = 0; j < M; ++j) {
    for (int c = 0; c < Dim; ++c) {
      for (int i = 0; i < Dim; ++i) trip.emplace_back(M * q + j, Dim * t[sz(i)] + c, weights(i) * tau(c, j));
      trip.emplace_back(M * q + j, Dim * s + c, -tau(c, j));
    }
  }
}

}  // namespace

template <int Dim>
Eigen::SparseMatrix<double, Eigen::RowMajor> tangential_rows(const mesh::SimplexMesh<Dim>& mesh,
                                                             const ContactPairOf<Dim>& pair,
                                                             const ContactQuadrature& quadrature,
                                                             const PointwiseContactOf<Dim>& pointwise) {
  require_collocation<Dim>(quadrature);
  const auto S = static_cast<Eigen::Index>(pair.slave.size());
  require(static_cast<Eigen::Index>(pointwise.projection.size()) == S && quadrature.W.cols() == S,
          "tangential_rows: " + std::to_string(pointwise.projection.size()) + " projections and " +
              std::to_string(quadrature.W.cols()) + " quadrature columns for " + std::to_string(S) + " slave nodes");
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(sz((Dim - 1) * Dim * (Dim + 1) * S));
  for (Eigen::Index q = 0; q < S; ++q) {
    add_pointwise_rows<Dim>(pair, pointwise.projection[sz(q)], static_cast<int>(q), trip);
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> pointwise_rows((Dim - 1) * S, mesh.num_dofs());
  pointwise_rows.setFromTriplets(trip.begin(), trip.end());
  return tangential_weights<Dim>(quadrature) * pointwise_rows;
}

namespace {

// The deformed positions (x_s, x_{t_0}, ...) of a slave node and its facet's nodes.
template <int Dim>
std::array<Vec<Dim>, Dim + 1> deformed_positions(const mesh::SimplexMesh<Dim>& mesh, int s,
                                                 const std::array<int, Dim>& t, const Eigen::VectorXd& w) {
  std::array<Vec<Dim>, Dim + 1> x;
  auto deformed = [&](int node) -> Vec<Dim> {
    return mesh.nodes[sz(node)] + w.template segment<Dim>(Dim * node);
  };
  x[0] = deformed(s);
  for (int i = 0; i < Dim; ++i) x[sz(i + 1)] = deformed(t[sz(i)]);
  return x;
}

// The undeformed edges L_k = X_{t_{k+1}} - X_{t_0} of a facet (columns).
template <int Dim>
Eigen::Matrix<double, Dim, Dim - 1> undeformed_edges(const mesh::SimplexMesh<Dim>& mesh, const std::array<int, Dim>& t) {
  Eigen::Matrix<double, Dim, Dim - 1> L;
  for (int k = 0; k < Dim - 1; ++k) L.col(k) = mesh.nodes[sz(t[sz(k + 1)])] - mesh.nodes[sz(t[0])];
  return L;
}

}  // namespace

template <int Dim>
std::vector<Eigen::Matrix<double, Dim, 1>> material_points(const mesh::SimplexMesh<Dim>& mesh,
                                                           const ContactPairOf<Dim>& pair,
                                                           const PointwiseContactOf<Dim>& pointwise,
                                                           const Eigen::VectorXd& w) {
  require(pointwise.projection.size() == pair.slave.size() && w.size() == mesh.num_dofs(),
          "material_points: " + std::to_string(pointwise.projection.size()) + " projections for " +
              std::to_string(pair.slave.size()) + " slave nodes, " + std::to_string(w.size()) + " displacements for " +
              std::to_string(mesh.num_dofs()) + " DOFs");
  std::vector<Eigen::Matrix<double, Dim, 1>> rho(pair.slave.size());
  for (std::size_t q = 0; q < rho.size(); ++q) {
    const NodeProjection<Dim>& p = pointwise.projection[q];
    rho[q] = p.rho;
    if (!p.candidate) continue;
    const std::array<int, Dim> t = facet_nodes(pair, p);
    const ParameterDerivative<Dim> d = parameter_derivative(deformed_positions<Dim>(mesh, pair.slave[q], t, w));
    const Eigen::Matrix<double, Dim, Dim - 1> L = undeformed_edges<Dim>(mesh, t);
    rho[q] = mesh.nodes[sz(t[0])];
    for (int k = 0; k < Dim - 1; ++k) rho[q] += d.xi(k) * L.col(k);
  }
  return rho;
}

template <int Dim>
Eigen::VectorXd tangential_slip(const PointwiseContactOf<Dim>& now, const std::vector<Eigen::Matrix<double, Dim, 1>>& rho,
                                const std::vector<Eigen::Matrix<double, Dim, 1>>& rho_previous) {
  constexpr int M = Dim - 1;
  require(now.projection.size() == rho.size() && rho.size() == rho_previous.size(),
          "tangential_slip: " + std::to_string(now.projection.size()) + " projections, " + std::to_string(rho.size()) +
              " material points now and " + std::to_string(rho_previous.size()) + " before");
  Eigen::VectorXd slip = Eigen::VectorXd::Zero(M * static_cast<Eigen::Index>(now.projection.size()));
  for (std::size_t q = 0; q < now.projection.size(); ++q) {
    const NodeProjection<Dim>& p = now.projection[q];
    if (!p.candidate) continue;
    slip.template segment<M>(M * static_cast<Eigen::Index>(q)) =
        tangent_basis<Dim>(p.normal).transpose() * (rho[q] - rho_previous[q]);
  }
  return slip;
}

namespace {

// For each candidate slave position q: its nodes (s, t_0, ...), its tangents and d xi at w.
template <int Dim, typename Visit>
void for_each_candidate(const mesh::SimplexMesh<Dim>& mesh, const ContactPairOf<Dim>& pair,
                        const ContactQuadrature& quadrature, const PointwiseContactOf<Dim>& pointwise,
                        const Eigen::VectorXd& w, const char* what, Visit visit) {
  require_collocation<Dim>(quadrature);
  require(pointwise.projection.size() == pair.slave.size() &&
              quadrature.W.cols() == static_cast<Eigen::Index>(pair.slave.size()) && w.size() == mesh.num_dofs(),
          std::string(what) + ": sizes do not match the slave nodes and the DOFs");
  for (std::size_t q = 0; q < pair.slave.size(); ++q) {
    const NodeProjection<Dim>& p = pointwise.projection[q];
    if (!p.candidate) continue;
    const std::array<int, Dim> t = facet_nodes(pair, p);
    std::array<int, Dim + 1> nodes;
    nodes[0] = pair.slave[q];
    for (int i = 0; i < Dim; ++i) nodes[sz(i + 1)] = t[sz(i)];
    visit(static_cast<int>(q), nodes, tangent_basis<Dim>(p.normal),
          parameter_derivative(deformed_positions<Dim>(mesh, pair.slave[q], t, w)));
  }
}

}  // namespace

template <int Dim>
Eigen::SparseMatrix<double, Eigen::RowMajor> slip_rows(const mesh::SimplexMesh<Dim>& mesh,
                                                       const ContactPairOf<Dim>& pair,
                                                       const ContactQuadrature& quadrature,
                                                       const PointwiseContactOf<Dim>& pointwise,
                                                       const Eigen::VectorXd& w) {
  constexpr int M = Dim - 1;
  std::vector<Eigen::Triplet<double>> trip;
  for_each_candidate<Dim>(mesh, pair, quadrature, pointwise, w, "slip_rows",
                          [&](int q, const std::array<int, Dim + 1>& nodes, const Eigen::Matrix<double, Dim, M>& tau,
                              const ParameterDerivative<Dim>& d) {
                            std::array<int, Dim> t;
                            for (int i = 0; i < Dim; ++i) t[sz(i)] = nodes[sz(i + 1)];
                            // -(d slip_j) = -sum_k (tau_j . L_k) d xi_k: the rows of delta = -|I_r| slip.
                            const Eigen::Matrix<double, M, M> scale = -(tau.transpose() * undeformed_edges<Dim>(mesh, t));
                            for (int j = 0; j < M; ++j) {
                              for (int n = 0; n <= Dim; ++n) {
                                const Vec<Dim> coef = d.g[sz(n)] * scale.row(j).transpose();
                                for (int c = 0; c < Dim; ++c) trip.emplace_back(M * q + j, Dim * nodes[sz(n)] + c, coef(c));
                              }
                            }
                          });
  Eigen::SparseMatrix<double, Eigen::RowMajor> pointwise_rows(M * static_cast<Eigen::Index>(pair.slave.size()),
                                                              mesh.num_dofs());
  pointwise_rows.setFromTriplets(trip.begin(), trip.end());
  return tangential_weights<Dim>(quadrature) * pointwise_rows;
}

template <int Dim>
Eigen::SparseMatrix<double> tangential_stiffness(const mesh::SimplexMesh<Dim>& mesh, const ContactPairOf<Dim>& pair,
                                                 const ContactQuadrature& quadrature,
                                                 const PointwiseContactOf<Dim>& pointwise, const Eigen::VectorXd& w,
                                                 const Eigen::VectorXd& lambda_t) {
  constexpr int M = Dim - 1;
  require(lambda_t.size() == M * quadrature.W.rows(), "tangential_stiffness: lambda_t has " +
                                                          std::to_string(lambda_t.size()) + " entries for " +
                                                          std::to_string(quadrature.W.rows()) + " rows");
  const Eigen::VectorXd per_node = tangential_weights<Dim>(quadrature).transpose() * lambda_t;  // |I_r| lambda_t,r at slave q
  std::vector<Eigen::Triplet<double>> trip;
  for_each_candidate<Dim>(mesh, pair, quadrature, pointwise, w, "tangential_stiffness",
                          [&](int q, const std::array<int, Dim + 1>& nodes, const Eigen::Matrix<double, Dim, M>& tau,
                              const ParameterDerivative<Dim>& d) {
                            const Eigen::Matrix<double, M, 1> force = per_node.template segment<M>(M * q);
                            if ((force.array() == 0.0).all()) return;
                            const Vec<Dim> f = tau * force;
                            // The force on t_0 has weight 1 - sum_k xi_k, on t_{k+1} weight xi_k.
                            for (int row_node = 1; row_node <= Dim; ++row_node) {
                              for (int k = 0; k < M; ++k) {
                                if (row_node != 1 && row_node != k + 2) continue;
                                const double sign = row_node == 1 ? -1.0 : 1.0;
                                for (int i = 0; i < Dim; ++i) {
                                  for (int n = 0; n <= Dim; ++n) {
                                    for (int c = 0; c < Dim; ++c) {
                                      trip.emplace_back(Dim * nodes[sz(row_node)] + i, Dim * nodes[sz(n)] + c,
                                                        sign * f(i) * d.g[sz(n)](c, k));
                                    }
                                  }
                                }
                              }
                            }
                          });
  Eigen::SparseMatrix<double> H(mesh.num_dofs(), mesh.num_dofs());
  H.setFromTriplets(trip.begin(), trip.end());
  return H;
}

#define CONTACTRB_TANGENTIAL_ROWS(Dim)                                                                                  \
  template Eigen::SparseMatrix<double> tangential_stiffness<Dim>(                                                       \
      const mesh::SimplexMesh<Dim>&, const ContactPairOf<Dim>&, const ContactQuadrature&, const PointwiseContactOf<Dim>&, \
      const Eigen::VectorXd&, const Eigen::VectorXd&);                                                                  \
  template Eigen::SparseMatrix<double, Eigen::RowMajor> slip_rows<Dim>(const mesh::SimplexMesh<Dim>&,                   \
                                                                       const ContactPairOf<Dim>&,                       \
                                                                       const ContactQuadrature&,                        \
                                                                       const PointwiseContactOf<Dim>&,                  \
                                                                       const Eigen::VectorXd&);                         \
  template std::vector<Eigen::Matrix<double, Dim, 1>> material_points<Dim>(                                             \
      const mesh::SimplexMesh<Dim>&, const ContactPairOf<Dim>&, const PointwiseContactOf<Dim>&, const Eigen::VectorXd&); \
  template Eigen::VectorXd tangential_slip<Dim>(const PointwiseContactOf<Dim>&,                                         \
                                                const std::vector<Eigen::Matrix<double, Dim, 1>>&,                      \
                                                const std::vector<Eigen::Matrix<double, Dim, 1>>&);                     \
  template Eigen::SparseMatrix<double, Eigen::RowMajor> tangential_rows<Dim>(                                           \
      const mesh::SimplexMesh<Dim>&, const ContactPairOf<Dim>&, const ContactQuadrature&, const PointwiseContactOf<Dim>&);
CONTACTRB_TANGENTIAL_ROWS(2)
CONTACTRB_TANGENTIAL_ROWS(3)
#undef CONTACTRB_TANGENTIAL_ROWS

}  // namespace contactrb::contact
