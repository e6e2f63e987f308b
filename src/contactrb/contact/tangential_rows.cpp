#include "contactrb/contact/tangential_rows.hpp"

#include <array>
#include <string>
#include <vector>

#include "contactrb/common/error.hpp"

namespace contactrb::contact {

template <>
Eigen::Matrix<double, 2, 1> tangent_basis<2>(const Eigen::Matrix<double, 2, 1>& n) {
  return Eigen::Vector2d(n.y(), -n.x());
}

namespace {

// d xi = g_s . dw_s + g_a . dw_a + g_b . dw_b for the unclamped parameter xi = (x_s - x_a) . e /
// |e|^2 of a slave node on its segment (e = x_b - x_a, at the deformed positions).
struct XiDerivative {
  double xi = 0.0;
  Eigen::Vector2d g_s, g_a, g_b;
};
XiDerivative xi_derivative(const Eigen::Vector2d& xs, const Eigen::Vector2d& xa, const Eigen::Vector2d& xb) {
  const Eigen::Vector2d e = xb - xa, sa = xs - xa;
  XiDerivative d;
  d.xi = sa.dot(e) / e.squaredNorm();
  const Eigen::Vector2d gb = (sa - 2.0 * d.xi * e) / e.squaredNorm();  // the coefficient of dw_b - dw_a
  d.g_s = e / e.squaredNorm();
  d.g_a = -d.g_s - gb;
  d.g_b = gb;
  return d;
}

// The pointwise tangential rows of slave position q (2D: its master segment's two nodes).
void add_pointwise_rows(const ContactPair& pair, const SlaveProjection& p, int q,
                        std::vector<Eigen::Triplet<double>>& trip) {
  if (!p.candidate) return;
  const Eigen::Vector2d tau = tangent_basis<2>(p.normal);
  const int s = pair.slave[static_cast<std::size_t>(q)];
  const int a = pair.master[static_cast<std::size_t>(p.segment)];
  const int b = pair.master[static_cast<std::size_t>(p.segment + 1)];
  for (int c = 0; c < 2; ++c) {
    trip.emplace_back(q, 2 * a + c, (1.0 - p.xi) * tau(c));
    trip.emplace_back(q, 2 * b + c, p.xi * tau(c));
    trip.emplace_back(q, 2 * s + c, -tau(c));
  }
}

}  // namespace

template <int Dim>
Eigen::SparseMatrix<double, Eigen::RowMajor> tangential_rows(const mesh::SimplexMesh<Dim>& mesh,
                                                             const ContactPairOf<Dim>& pair,
                                                             const ContactQuadrature& quadrature,
                                                             const PointwiseContactOf<Dim>& pointwise) {
  static_assert(Dim == 2, "tangential rows: 2D (the 3D facets follow the same layout)");
  require(quadrature.discretization == Discretization::Collocation,
          std::string("friction needs the collocation rows (one per slave node), not '") +
              to_string(quadrature.discretization) + "'");
  const auto S = static_cast<Eigen::Index>(pair.slave.size());
  require(static_cast<Eigen::Index>(pointwise.projection.size()) == S && quadrature.W.cols() == S,
          "tangential_rows: " + std::to_string(pointwise.projection.size()) + " projections and " +
              std::to_string(quadrature.W.cols()) + " quadrature columns for " + std::to_string(S) + " slave nodes");
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(6 * S));
  for (Eigen::Index q = 0; q < S; ++q) {
    add_pointwise_rows(pair, pointwise.projection[static_cast<std::size_t>(q)], static_cast<int>(q), trip);
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> pointwise_rows((Dim - 1) * S, mesh.num_dofs());
  pointwise_rows.setFromTriplets(trip.begin(), trip.end());
  return quadrature.W * pointwise_rows;
}

template <int Dim>
std::vector<Eigen::Matrix<double, Dim, 1>> material_points(const mesh::SimplexMesh<Dim>& mesh,
                                                           const ContactPairOf<Dim>& pair,
                                                           const PointwiseContactOf<Dim>& pointwise,
                                                           const Eigen::VectorXd& w) {
  static_assert(Dim == 2, "material points: 2D (the 3D facets follow the same layout)");
  require(pointwise.projection.size() == pair.slave.size() && w.size() == mesh.num_dofs(),
          "material_points: " + std::to_string(pointwise.projection.size()) + " projections for " +
              std::to_string(pair.slave.size()) + " slave nodes, " + std::to_string(w.size()) + " displacements for " +
              std::to_string(mesh.num_dofs()) + " DOFs");
  std::vector<Eigen::Matrix<double, Dim, 1>> rho(pair.slave.size());
  auto deformed = [&](int node) -> Eigen::Vector2d {
    return mesh.nodes[static_cast<std::size_t>(node)] + w.template segment<2>(2 * node);
  };
  for (std::size_t q = 0; q < rho.size(); ++q) {
    const SlaveProjection& p = pointwise.projection[q];
    rho[q] = p.rho;
    if (!p.candidate) continue;
    const int a = pair.master[static_cast<std::size_t>(p.segment)];
    const int b = pair.master[static_cast<std::size_t>(p.segment + 1)];
    const Eigen::Vector2d e = deformed(b) - deformed(a);
    const double xi = (deformed(pair.slave[q]) - deformed(a)).dot(e) / e.squaredNorm();
    rho[q] = mesh.nodes[static_cast<std::size_t>(a)] +
             xi * (mesh.nodes[static_cast<std::size_t>(b)] - mesh.nodes[static_cast<std::size_t>(a)]);
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

// For each candidate slave position q: its nodes (s, a, b), its tangent and d xi at w.
template <typename Visit>
void for_each_candidate(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                        const PointwiseContact& pointwise, const Eigen::VectorXd& w, const char* what, Visit visit) {
  require(quadrature.discretization == Discretization::Collocation,
          std::string("friction needs the collocation rows (one per slave node), not '") +
              to_string(quadrature.discretization) + "'");
  require(pointwise.projection.size() == pair.slave.size() &&
              quadrature.W.cols() == static_cast<Eigen::Index>(pair.slave.size()) && w.size() == mesh.num_dofs(),
          std::string(what) + ": sizes do not match the slave nodes and the DOFs");
  auto deformed = [&](int node) -> Eigen::Vector2d {
    return mesh.nodes[static_cast<std::size_t>(node)] + w.segment<2>(2 * node);
  };
  for (std::size_t q = 0; q < pair.slave.size(); ++q) {
    const SlaveProjection& p = pointwise.projection[q];
    if (!p.candidate) continue;
    const std::array<int, 3> nodes{pair.slave[q], pair.master[static_cast<std::size_t>(p.segment)],
                                   pair.master[static_cast<std::size_t>(p.segment + 1)]};
    visit(static_cast<int>(q), nodes, tangent_basis<2>(p.normal),
          xi_derivative(deformed(nodes[0]), deformed(nodes[1]), deformed(nodes[2])));
  }
}

}  // namespace

template <int Dim>
Eigen::SparseMatrix<double, Eigen::RowMajor> slip_rows(const mesh::SimplexMesh<Dim>& mesh,
                                                       const ContactPairOf<Dim>& pair,
                                                       const ContactQuadrature& quadrature,
                                                       const PointwiseContactOf<Dim>& pointwise,
                                                       const Eigen::VectorXd& w) {
  static_assert(Dim == 2, "slip rows: 2D (the 3D facets follow the same layout)");
  std::vector<Eigen::Triplet<double>> trip;
  for_each_candidate(mesh, pair, quadrature, pointwise, w, "slip_rows",
                     [&](int q, const std::array<int, 3>& nodes, const Eigen::Vector2d& tau, const XiDerivative& d) {
                       const Eigen::Vector2d L = mesh.nodes[static_cast<std::size_t>(nodes[2])] -
                                                 mesh.nodes[static_cast<std::size_t>(nodes[1])];
                       // -(d slip) = -(tau . L) d xi: the rows of delta = -|I_r| slip (|I_r| from W).
                       const double scale = -tau.dot(L);
                       const std::array<const Eigen::Vector2d*, 3> g{&d.g_s, &d.g_a, &d.g_b};
                       for (int k = 0; k < 3; ++k) {
                         for (int c = 0; c < 2; ++c) trip.emplace_back(q, 2 * nodes[static_cast<std::size_t>(k)] + c, scale * (*g[static_cast<std::size_t>(k)])(c));
                       }
                     });
  Eigen::SparseMatrix<double, Eigen::RowMajor> pointwise_rows((Dim - 1) * static_cast<Eigen::Index>(pair.slave.size()),
                                                              mesh.num_dofs());
  pointwise_rows.setFromTriplets(trip.begin(), trip.end());
  return quadrature.W * pointwise_rows;
}

template <int Dim>
Eigen::SparseMatrix<double> tangential_stiffness(const mesh::SimplexMesh<Dim>& mesh, const ContactPairOf<Dim>& pair,
                                                 const ContactQuadrature& quadrature,
                                                 const PointwiseContactOf<Dim>& pointwise, const Eigen::VectorXd& w,
                                                 const Eigen::VectorXd& lambda_t) {
  static_assert(Dim == 2, "tangential stiffness: 2D (the 3D facets follow the same layout)");
  require(lambda_t.size() == (Dim - 1) * quadrature.W.rows(), "tangential_stiffness: lambda_t has " +
                                                                  std::to_string(lambda_t.size()) + " entries for " +
                                                                  std::to_string(quadrature.W.rows()) + " rows");
  const Eigen::VectorXd per_node = quadrature.W.transpose() * lambda_t;  // |I_r| lambda_t,r at slave q
  std::vector<Eigen::Triplet<double>> trip;
  for_each_candidate(mesh, pair, quadrature, pointwise, w, "tangential_stiffness",
                     [&](int q, const std::array<int, 3>& nodes, const Eigen::Vector2d& tau, const XiDerivative& d) {
                       const double force = per_node(q);
                       if (force == 0.0) return;
                       const std::array<const Eigen::Vector2d*, 3> g{&d.g_s, &d.g_a, &d.g_b};
                       for (int row_node = 1; row_node <= 2; ++row_node) {  // a: -d xi, b: +d xi
                         const double sign = row_node == 1 ? -1.0 : 1.0;
                         for (int i = 0; i < 2; ++i) {
                           for (int k = 0; k < 3; ++k) {
                             for (int c = 0; c < 2; ++c) {
                               trip.emplace_back(2 * nodes[static_cast<std::size_t>(row_node)] + i,
                                                 2 * nodes[static_cast<std::size_t>(k)] + c,
                                                 sign * force * tau(i) * (*g[static_cast<std::size_t>(k)])(c));
                             }
                           }
                         }
                       }
                     });
  Eigen::SparseMatrix<double> H(mesh.num_dofs(), mesh.num_dofs());
  H.setFromTriplets(trip.begin(), trip.end());
  return H;
}

template Eigen::SparseMatrix<double> tangential_stiffness<2>(const mesh::Mesh&, const ContactPair&,
                                                             const ContactQuadrature&, const PointwiseContact&,
                                                             const Eigen::VectorXd&, const Eigen::VectorXd&);
template Eigen::SparseMatrix<double, Eigen::RowMajor> slip_rows<2>(const mesh::Mesh&, const ContactPair&,
                                                                   const ContactQuadrature&, const PointwiseContact&,
                                                                   const Eigen::VectorXd&);
template std::vector<Eigen::Vector2d> material_points<2>(const mesh::Mesh&, const ContactPair&, const PointwiseContact&,
                                                         const Eigen::VectorXd&);
template Eigen::VectorXd tangential_slip<2>(const PointwiseContact&, const std::vector<Eigen::Vector2d>&,
                                            const std::vector<Eigen::Vector2d>&);
template Eigen::SparseMatrix<double, Eigen::RowMajor> tangential_rows<2>(const mesh::SimplexMesh<2>&,
                                                                         const ContactPair&, const ContactQuadrature&,
                                                                         const PointwiseContact&);

}  // namespace contactrb::contact
