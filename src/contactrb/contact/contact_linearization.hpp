#pragma once
// Consistent linearization of the contact maps for the semi-smooth Newton solver
// (docs/solvers.md, "Semi-smooth Newton"). At a displacement u and multipliers lambda:
//   d(u)       = g(u) - K(u) u          (R)  weighted signed gaps, d >= 0 is (26)
//   f_c(u)     = K(u)' lambda           (num_dofs) contact forces, lambda frozen
// and their Jacobians with respect to the movable DOFs:
//   D = d'(u)           (R x num_dofs)       -- includes the motion of the projection (xi),
//                                              of the continuous normal n2 and of rho
//   H = (K(u)' lambda)' (num_dofs x num_dofs) -- the geometric stiffness of the contact forces
// Both are the exact maps of projection.hpp / lac_integration.hpp differentiated by
// column-coloured central differences (Curtis, Powell and Reid 1974): the sparsity of row r
// is known from the projection (the slave nodes of I_r, and the master nodes from one
// before the first to two after the last segment their projections hit, which carry the
// vertex normals), columns that share no row are perturbed together, so a linearization
// costs 2 x (number of colours) evaluations of the maps, independent of the mesh size.
// The maps are piecewise smooth (the closest segment switches at master vertices, where
// they are continuous, docs/contact.md): there the difference quotient is a one-sided or
// averaged slope, an element of the generalized Jacobian up to O(step).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

struct LinearizationOptions {
  // Finite-difference step, relative to the mean reference slave edge length. Central
  // differences: truncation (step)^2, round-off eps |x| / (step h); 1e-6 balances the two
  // for meshes with edges from 1e-1 to 1e-4 of the body size.
  double relative_step = 1e-6;
  ProjectionOptions projection;
};

// Values of the maps at u (no derivatives).
struct ContactMaps {
  PointwiseContact pointwise;
  ConstraintRows rows;      // K(u), g(u)
  Eigen::VectorXd d;        // g(u) - K(u) u
};
// Throws contactrb::Error like project_slave_nodes (non-finite or overflowing u).
ContactMaps evaluate_contact_maps(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                                  const Eigen::VectorXd& u, const ProjectionOptions& options = {});

struct ContactLinearization {
  ContactMaps maps;                                // at u
  Eigen::SparseMatrix<double, Eigen::RowMajor> D;  // R x num_dofs, d'(u) on movable columns
  Eigen::SparseMatrix<double> H;                   // num_dofs x num_dofs, (K' lambda)' on movable rows/cols
  int colours = 0;
  int evaluations = 0;  // map evaluations (2 per colour)
};

// movable[i]: DOF i varies (free DOFs); the other columns and rows of D and H are zero.
// lambda: R multipliers; rows with lambda_r = 0 contribute nothing to H.
// Throws contactrb::Error on size mismatch or when the maps cannot be evaluated.
ContactLinearization linearize_contact(const mesh::Mesh& mesh, const ContactPair& pair,
                                       const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                       const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                       const LinearizationOptions& options = {});

}  // namespace contactrb::contact
