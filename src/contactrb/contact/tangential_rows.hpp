#pragma once
// The tangential rows of frictional contact (docs/solvers.md, "Friction"): for each slave node s
// that faces the master (a candidate of projection.hpp), the Dim - 1 rows
//   t(w; v)_{s,j} = ((1 - xi) v_a + xi v_b - v_s) . tau_j,
// the normal row (27) of projection.hpp with the unit normal n2 replaced by the unit tangents
// tau_j of the master at the projection point: the displacement of the master point minus that
// of the slave node, along tau_j. The same quadrature W as the normal rows weights them (row r
// of T is int_{I_r} t(w; .) psi_r), so that a tangential multiplier is a traction, like the
// normal one a pressure. Collocation only: one normal row and Dim - 1 tangential rows per slave
// node. Row (Dim - 1) r + j of T is tangent j of constraint row r. In 3D the master point is
// sum_i phi_i v_{t_i} over the triangle (t_0, t_1, t_2) of the projection (NodeProjection<3>).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

// The unit tangents tau_j (columns) of the master at a projection point with unit normal n2.
// 2D: tau = (n2_y, -n2_x), n2 turned clockwise (on a master below the slave, n2 = (0, 1) and
// tau = (1, 0): +x). 3D: with k the component of n2 of largest magnitude and e the unit axis
// k + 1 (mod 3), tau_1 = normalize(e - (e . n2) n2), tau_2 = n2 x tau_1: smooth in n2 away from
// the directions 45 degrees from an axis (docs/solvers.md, "Friction"); n2 = (0, 0, 1) gives
// (e_x, e_y), n2 = (0, 0, -1) gives (e_x, -e_y).
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
template <>
Eigen::Matrix<double, 3, 2> tangent_basis<3>(const Eigen::Matrix<double, 3, 1>& normal);
// The undeformed position of the master point each slave node projects on, with the parameter
// of its facet not clamped to the facet (2D: rho = X_a + xi (X_b - X_a), xi = (x_s - x_a) .
// (x_b - x_a) / |x_b - x_a|^2 at the deformed positions x = X + w; 3D: rho = sum_i phi_i X_{t_i}
// with phi the barycentric coordinates of the projection of x_s on the plane of the deformed
// triangle): a material point of the master, continued past the ends of an open master chain (the
// rim of a master surface), where the closest point stops.
// Non-candidates: their record's rho. Throws contactrb::Error on sizes that do not match.
template <int Dim>
std::vector<Eigen::Matrix<double, Dim, 1>> material_points(const mesh::SimplexMesh<Dim>& mesh,
                                                           const ContactPairOf<Dim>& pair,
                                                           const PointwiseContactOf<Dim>& pointwise,
                                                           const Eigen::VectorXd& w);

// The slip of each slave node relative to the master since a previous configuration, along the
// tangents at u (Dim - 1 entries per slave node): tau_j . (rho - rho_prev), rho the
// material_points now and then. A material measure: zero when slave and master move together,
// whatever their motion; its derivative at zero gap is -T_r / |I_r| up to the master's stretch
// (docs/solvers.md, "Friction"). Non-candidates: zero. Sizes must match (throws contactrb::Error).
template <int Dim>
Eigen::VectorXd tangential_slip(const PointwiseContactOf<Dim>& now, const std::vector<Eigen::Matrix<double, Dim, 1>>& rho,
                                const std::vector<Eigen::Matrix<double, Dim, 1>>& rho_previous);

// The derivative of the weighted slip -|I_r| slip_r(w) (the rows of delta in hf/friction.hpp)
// with respect to w at the projections `pointwise` of w, the tangents held fixed (their change
// multiplies the slip itself): (Dim - 1) R x num_dofs. In 2D, with e = x_b - x_a and
// L = X_b - X_a, d slip = (tau . L) / |e|^2 [e . (dw_s - dw_a) + (x_s - x_a - 2 xi e) . (dw_b - dw_a)].
// In 3D, with E = (x_{t_1} - x_{t_0}, x_{t_2} - x_{t_0}), G = E'E, the parameters xi = G^-1 E'(x_s -
// x_{t_0}) and r = x_s - x_{t_0} - E xi: G d xi = dE' r + E' (dw_s - sum_i phi_i dw_{t_i}), and
// d slip_j = sum_k (tau_j . L_k) d xi_k with L_k = X_{t_{k+1}} - X_{t_0}.
// At zero gap and without stretch it is T (tangential_rows). Collocation only (throws
// contactrb::Error otherwise or on sizes that do not match).
template <int Dim>
Eigen::SparseMatrix<double, Eigen::RowMajor> slip_rows(const mesh::SimplexMesh<Dim>& mesh,
                                                       const ContactPairOf<Dim>& pair,
                                                       const ContactQuadrature& quadrature,
                                                       const PointwiseContactOf<Dim>& pointwise,
                                                       const Eigen::VectorXd& w);

// The derivative of the tangential contact forces T(w)' lambda_t through the motion of the
// projection point (xi), the tangents held fixed: num_dofs x num_dofs (the tangential
// counterpart of H = (K' lambda)' of contact_linearization.hpp). In 2D the forces
// |I_r| lambda_t,r ((1 - xi) tau on a, xi tau on b, -tau on s) change by |I_r| lambda_t,r tau
// (-d xi on a, +d xi on b), d xi as in slip_rows; in 3D the force f = |I_r| sum_j lambda_t,rj tau_j
// changes by -f (d xi_0 + d xi_1) on t_0 and f d xi_k on t_{k+1}. Collocation only.
template <int Dim>
Eigen::SparseMatrix<double> tangential_stiffness(const mesh::SimplexMesh<Dim>& mesh, const ContactPairOf<Dim>& pair,
                                                 const ContactQuadrature& quadrature,
                                                 const PointwiseContactOf<Dim>& pointwise, const Eigen::VectorXd& w,
                                                 const Eigen::VectorXd& lambda_t);

#define CONTACTRB_TANGENTIAL_ROWS_EXTERN(Dim)                                                                           \
  extern template Eigen::SparseMatrix<double> tangential_stiffness<Dim>(                                                \
      const mesh::SimplexMesh<Dim>&, const ContactPairOf<Dim>&, const ContactQuadrature&, const PointwiseContactOf<Dim>&, \
      const Eigen::VectorXd&, const Eigen::VectorXd&);                                                                  \
  extern template Eigen::SparseMatrix<double, Eigen::RowMajor> slip_rows<Dim>(                                          \
      const mesh::SimplexMesh<Dim>&, const ContactPairOf<Dim>&, const ContactQuadrature&, const PointwiseContactOf<Dim>&, \
      const Eigen::VectorXd&);                                                                                          \
  extern template std::vector<Eigen::Matrix<double, Dim, 1>> material_points<Dim>(                                      \
      const mesh::SimplexMesh<Dim>&, const ContactPairOf<Dim>&, const PointwiseContactOf<Dim>&, const Eigen::VectorXd&); \
  extern template Eigen::VectorXd tangential_slip<Dim>(const PointwiseContactOf<Dim>&,                                  \
                                                       const std::vector<Eigen::Matrix<double, Dim, 1>>&,               \
                                                       const std::vector<Eigen::Matrix<double, Dim, 1>>&);              \
  extern template Eigen::SparseMatrix<double, Eigen::RowMajor> tangential_rows<Dim>(                                    \
      const mesh::SimplexMesh<Dim>&, const ContactPairOf<Dim>&, const ContactQuadrature&, const PointwiseContactOf<Dim>&);
CONTACTRB_TANGENTIAL_ROWS_EXTERN(2)
CONTACTRB_TANGENTIAL_ROWS_EXTERN(3)
#undef CONTACTRB_TANGENTIAL_ROWS_EXTERN

}  // namespace contactrb::contact
