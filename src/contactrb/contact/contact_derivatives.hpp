#pragma once
// Analytic consistent linearization of the contact maps (internal to the contact module; the
// API is contact_linearization.hpp). The maps are differentiated exactly, by forward-mode dual
// numbers (local_dual.hpp) on the same formulas and the same discrete branches (closest segment,
// clamped or interior xi, LAC pieces) as the evaluation at u:
//   pointwise (Collocation, LACSimpson: rows = W * pointwise), slave node s on master segment k:
//     d_s = (x_s - p) . n2,  p = (1 - xi) y_k + xi y_k+1,  xi = (x_s - y_k).e / |e|^2 (or a clamped 0 / 1),
//     n2 = normalize((1 - xi) n_k + xi n_k+1), n_j the vertex normals (projection.hpp);
//   LAC: the segment-to-segment Gauss rule of lac_integration.hpp, with the projection abscissae,
//     the cut points and the Gauss points moving with u.
// Where a branch switches (xi reaching 0 or 1, the closest segment changing at a vertex) the
// maps are continuous and this is the one-sided Jacobian of the branch taken at u: an element of
// the generalized Jacobian, exact to round-off, instead of a difference quotient.
#include <vector>

#include "contactrb/contact/contact_linearization.hpp"

namespace contactrb::contact::detail {

// Movable DOFs row r of (K, g) can depend on: the slave nodes of I_r and the master chain
// positions from (first segment hit - 1) to (last segment hit + 2).
std::vector<std::vector<int>> row_inputs(const ContactPair& pair, const ContactQuadrature& quadrature,
                                         const PointwiseContact& pw, const std::vector<char>& movable);

// The pointwise maps (projection records, K rows, g) at u on the branches of `branches`.
PointwiseContact pointwise_on_branches(const mesh::Mesh& mesh, const ContactPair& pair, const Eigen::VectorXd& u,
                                       const PointwiseContact& branches);

// Fills lin.D and lin.H at u from lin.maps (the maps at u). lin.evaluations and lin.colours stay 0.
void analytic_linearization(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                            const Eigen::VectorXd& u, const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                            ContactLinearization& lin);

// 3D (contact_derivatives3.cpp): the same for the collocation rows of 3D (docs/contact.md, "Three
// dimensions"), slave node s on master triangle f = (t_0, t_1, t_2):
//   d_s = (x_s - p) . n2,  p = sum_i phi_i y_{t_i},  n2 = normalize(sum_i phi_i n_{t_i}),
//   phi: the face branch (x_s projected on the triangle's plane), an edge branch (one phi_i = 0,
//   the projection on the edge's line) or a vertex (constant), as the closest point at u;
//   n_j = normalize(sum over the triangles at j of angle_j(f) n_f), angles by atan2.
// Non-candidates: d_s = |x_s - p|, zero K row.
// Row inputs: the slave node of I_r and the master vertices of the triangles around each vertex
// of the triangle the node projects onto (their normals make the vertex normals n_j and the rim
// conormals).
std::vector<std::vector<int>> row_inputs(const ContactPair3& pair, const ContactQuadrature& quadrature,
                                         const PointwiseContact3& pw, const std::vector<char>& movable);
// 3D LAC rows (lac3d.hpp), linearized by coloured central differences only: row r reads the
// inputs of the pointwise maps at the slave nodes of its median dual cell's triangles (their
// projections make the directions d_T; W's row r holds these nodes) and the master vertices of
// the triangles around every master vertex K(u)'s row r holds (the triangles its clipped pieces
// touch, and the neighbours whose normals make the vertex normals n_j).
std::vector<std::vector<int>> lac_row_inputs(const ContactPair3& pair, const ContactQuadrature& quadrature,
                                             const PointwiseContact3& pw, const ConstraintRows& rows,
                                             const std::vector<char>& movable);
void analytic_linearization(const mesh::Mesh3& mesh, const ContactPair3& pair, const ContactQuadrature& quadrature,
                            const Eigen::VectorXd& u, const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                            ContactLinearization3& lin);

}  // namespace contactrb::contact::detail
