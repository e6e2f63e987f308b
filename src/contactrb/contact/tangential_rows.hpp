#pragma once
// The tangential rows of frictional contact (docs/solvers.md, "Friction"): for each slave node s
// that faces the master (a candidate of projection.hpp), the Dim - 1 rows
//   t(w; v)_{s,j} = ((1 - xi) v_a + xi v_b - v_s) . tau_j,
// the normal row (27) of projection.hpp with the unit normal n2 replaced by the unit tangents
// tau_j of the master at the projection point: the displacement of the master point minus that
// of the slave node, along tau_j. The same quadrature W as the normal rows weights them (row r
// of T is int_{I_r} t(w; .) psi_r), so that a tangential multiplier is a traction, like the
// normal one a pressure. Collocation only: one normal row and Dim - 1 tangential rows per slave
// node. Row (Dim - 1) r + j of T is tangent j of constraint row r.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

// The unit tangents tau_j (columns) of the master at a projection point with unit normal n2.
// 2D: tau = (n2_y, -n2_x), n2 turned clockwise (on a master below the slave, n2 = (0, 1) and
// tau = (1, 0): +x).
template <int Dim>
Eigen::Matrix<double, Dim, Dim - 1> tangent_basis(const Eigen::Matrix<double, Dim, 1>& normal);

// (Dim - 1) R x num_dofs. Throws contactrb::Error for a discretization other than Collocation
// (friction needs one constraint row per slave node) or on sizes that do not match.
template <int Dim>
Eigen::SparseMatrix<double, Eigen::RowMajor> tangential_rows(const mesh::SimplexMesh<Dim>& mesh,
                                                             const ContactPairOf<Dim>& pair,
                                                             const ContactQuadrature& quadrature,
                                                             const PointwiseContactOf<Dim>& pointwise);

template <>
Eigen::Matrix<double, 2, 1> tangent_basis<2>(const Eigen::Matrix<double, 2, 1>& normal);
// The slip of each slave node relative to the master since a previous configuration, along the
// tangents at u (Dim - 1 entries per slave node): tau_j . (rho - rho_prev), rho the undeformed
// position of the master point the node projects on (NodeProjection::rho), now and then. A
// material measure: zero when slave and master move together, whatever their motion; its
// derivative at zero gap is -T_r / |I_r| up to the master's stretch (docs/solvers.md, "Friction").
// Non-candidates: zero. Sizes must match (throws contactrb::Error).
template <int Dim>
Eigen::VectorXd tangential_slip(const PointwiseContactOf<Dim>& now, const PointwiseContactOf<Dim>& previous);

extern template Eigen::VectorXd tangential_slip<2>(const PointwiseContact&, const PointwiseContact&);
extern template Eigen::SparseMatrix<double, Eigen::RowMajor> tangential_rows<2>(const mesh::SimplexMesh<2>&,
                                                                                const ContactPair&,
                                                                                const ContactQuadrature&,
                                                                                const PointwiseContact&);

}  // namespace contactrb::contact
