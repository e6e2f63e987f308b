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

}  // namespace contactrb::contact::detail
