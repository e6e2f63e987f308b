#pragma once
// Consistent linearization of the contact maps for the semi-smooth Newton solver
// (docs/solvers.md, "Semi-smooth Newton"). At a displacement u and multipliers lambda:
//   d(u)       = g(u) - K(u) u          (R)  weighted signed gaps, d >= 0 is (26)
//   f_c(u)     = K(u)' lambda           (num_dofs) contact forces, lambda frozen
// and their Jacobians with respect to the movable DOFs:
//   D = d'(u)           (R x num_dofs)       -- includes the motion of the projection (xi),
//                                              of the continuous normal n2 and of rho
//   H = (K(u)' lambda)' (num_dofs x num_dofs) -- the geometric stiffness of the contact forces
// Two methods (LinearizationOptions::method):
//  Analytic (default): the maps of projection.hpp / lac_integration.hpp differentiated exactly
//    (forward-mode dual numbers on the same formulas and branches, contact_derivatives.hpp),
//    one pass over the constraint rows, exact to round-off.
//  FiniteDifference: column-coloured central differences (Curtis, Powell and Reid 1974): the
//    sparsity of row r is known from the projection (the slave nodes of I_r, and the master
//    nodes from one before the first to two after the last segment their projections hit,
//    which carry the vertex normals), columns that share no row are perturbed together, so a
//    linearization costs 2 x (number of colours) evaluations of the maps. Kept as the
//    independent check of the analytic one (tests/contact/test_contact_linearization.cpp).
//    Its error is truncation (step)^2 plus round-off eps |x| / step: on hertz-a level 6
//    (edges 1e-3 of the body) it stopped Newton's quadratic rate near 1e-9 (docs/solvers.md).
// In 3D (Mesh3, ContactPair3) the collocation rows have both methods (docs/solvers.md, "Three
// dimensions"): the rows of slave node s read its DOFs and those of every master vertex of the
// triangles around the vertices of the triangle it projects onto (their normals make the vertex
// normals n_j and the rim conormals). The LAC rows (lac3d.hpp) have FiniteDifference only, taken
// whatever the method asked, each colour re-evaluating only the rows it moves (docs/contact.md,
// "LAC in three dimensions", "Linearization"). The continuation on other branches
// (linearize_contact_on_branches) is 2D only.
// The maps are piecewise smooth (the closest segment switches at master vertices, where
// they are continuous, docs/contact.md): there the analytic derivative is the one-sided
// Jacobian of the branch taken at u, and the difference quotient a one-sided or averaged
// slope; both are elements of the generalized Jacobian (the latter up to O(step)).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

enum class LinearizationMethod { Analytic, FiniteDifference };
const char* to_string(LinearizationMethod value);  // "analytic" | "finite-difference"
LinearizationMethod linearization_method_from_string(const std::string& name);  // throws contactrb::Error

struct LinearizationOptions {
  LinearizationMethod method = LinearizationMethod::Analytic;
  // FiniteDifference only:
  // Finite-difference step, relative to the mean reference slave edge length. Central
  // differences: truncation (step)^2, round-off eps |x| / (step h); 1e-6 balances the two
  // for meshes with edges from 1e-1 to 1e-4 of the body size.
  double relative_step = 1e-6;
  ProjectionOptions projection;
};

// Values of the maps at u (no derivatives).
template <int Dim>
struct ContactMapsOf {
  PointwiseContactOf<Dim> pointwise;
  ConstraintRows rows;      // K(u), g(u)
  Eigen::VectorXd d;        // g(u) - K(u) u
};
using ContactMaps = ContactMapsOf<2>;
using ContactMaps3 = ContactMapsOf<3>;
// Throws contactrb::Error like project_slave_nodes (non-finite or overflowing u).
ContactMaps evaluate_contact_maps(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                                  const Eigen::VectorXd& u, const ProjectionOptions& options = {});
ContactMaps3 evaluate_contact_maps(const mesh::Mesh3& mesh, const ContactPair3& pair,
                                   const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                   const ProjectionOptions& options = {});

template <int Dim>
struct ContactLinearizationOf {
  ContactMapsOf<Dim> maps;                         // at u
  Eigen::SparseMatrix<double, Eigen::RowMajor> D;  // R x num_dofs, d'(u) on movable columns
  Eigen::SparseMatrix<double> H;                   // num_dofs x num_dofs, (K' lambda)' on movable rows/cols
  int colours = 0;      // FiniteDifference: colours of the columns
  int evaluations = 0;  // FiniteDifference: map evaluations (2 per colour)
};
using ContactLinearization = ContactLinearizationOf<2>;
using ContactLinearization3 = ContactLinearizationOf<3>;

// movable[i]: DOF i varies (free DOFs); the other columns and rows of D and H are zero.
// lambda: R multipliers; rows with lambda_r = 0 contribute nothing to H.
// Throws contactrb::Error on size mismatch or when the maps cannot be evaluated.
ContactLinearization linearize_contact(const mesh::Mesh& mesh, const ContactPair& pair,
                                       const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                       const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                       const LinearizationOptions& options = {});
// The same, with the maps at u already evaluated (evaluate_contact_maps(mesh, pair, quadrature,
// u, options.projection)): the semi-smooth Newton iterate holds them.
ContactLinearization linearize_contact(const mesh::Mesh& mesh, const ContactPair& pair,
                                       const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                       const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                       ContactMaps maps_at_u, const LinearizationOptions& options = {});
// 3D: the same (contact_derivatives.hpp for the analytic method of the collocation rows; the LAC
// rows by coloured differences whatever options.method says).
ContactLinearization3 linearize_contact(const mesh::Mesh3& mesh, const ContactPair3& pair,
                                        const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                        const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                        const LinearizationOptions& options = {});
ContactLinearization3 linearize_contact(const mesh::Mesh3& mesh, const ContactPair3& pair,
                                        const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                        const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                        ContactMaps3 maps_at_u, const LinearizationOptions& options = {});
// The maps continued on prescribed branches (linearize_contact_on_branches) exist in 2D only.
template <int Dim>
constexpr bool has_branch_continuation = Dim == 2;

// Branches of the piecewise smooth pointwise maps: the closest segment and whether xi is clamped
// (0 or 1, a vertex's wedge) or interior, and the candidate flag. Two projections lie on the same
// branch when all three agree, or when both are the same vertex seen from its two segments
// ((k, xi = 1) and (k + 1, xi = 0): the same maps and derivatives).
bool same_branch(const SlaveProjection& a, const SlaveProjection& b);

// The maps at u continued on prescribed branches (`branches`: one projection per slave node, e.g.
// those of a predicted iterate; on a branch that is not u's own, xi is the smooth continuation of
// the branch's formula, possibly slightly outside [0, 1]) and their analytic linearization there.
// The semi-smooth Newton step on these is exact for the branches the step lands on
// (hf/semismooth_newton.hpp, "branch passes"). Pointwise rows only (Collocation, LACSimpson);
// throws contactrb::Error for LAC or on size mismatch.
ContactLinearization linearize_contact_on_branches(const mesh::Mesh& mesh, const ContactPair& pair,
                                                   const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                                   const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                                   const PointwiseContact& branches);

}  // namespace contactrb::contact
