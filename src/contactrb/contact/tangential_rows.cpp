#include "contactrb/contact/tangential_rows.hpp"

#include <string>
#include <vector>

#include "contactrb/common/error.hpp"

namespace contactrb::contact {

template <>
Eigen::Matrix<double, 2, 1> tangent_basis<2>(const Eigen::Matrix<double, 2, 1>& n) {
  return Eigen::Vector2d(n.y(), -n.x());
}

namespace {

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

template std::vector<Eigen::Vector2d> material_points<2>(const mesh::Mesh&, const ContactPair&, const PointwiseContact&,
                                                         const Eigen::VectorXd&);
template Eigen::VectorXd tangential_slip<2>(const PointwiseContact&, const std::vector<Eigen::Vector2d>&,
                                            const std::vector<Eigen::Vector2d>&);
template Eigen::SparseMatrix<double, Eigen::RowMajor> tangential_rows<2>(const mesh::SimplexMesh<2>&,
                                                                         const ContactPair&, const ContactQuadrature&,
                                                                         const PointwiseContact&);

}  // namespace contactrb::contact
