#pragma once
// Exactly integrated LAC rows (Discretization::LAC, docs/contact.md "Exact LAC integration"):
// segment-to-segment integration of the contact and gap maps over each macro-segment I_r,
//   K(w)_r v = int_{I_r} k(w; v) psi_r,   g(w)_r = int_{I_r} g(w) psi_r,   psi_r = 1 on I_r,
// in the spirit of the LAC of Drouot & Hild, instead of the paper's Simpson rule (62) on the
// three slave nodes (Discretization::LACSimpson), which is not consistent for P1 fields.
//
// For each slave edge (s_a, s_b), parametrized by t in [0, 1] (reference X(t) and deformed
// x(t) = X(t) + w(t) linear in t), the master curvilinear abscissa S (deformed arc length
// along the master chain) of the pointwise projections of s_a and s_b is interpolated
// linearly in t. [0, 1] is split where S crosses a master vertex; on each piece the master
// segment k is fixed, xi = (S - L_k) / |y_k+1 - y_k| is linear in t, and so are the slave
// and master P1 fields, so 2-point Gauss integrates k(w; v) exactly on a flat master (and
// accurately on a curved one, where the continuous normal n2 of projection.hpp varies
// smoothly). At each Gauss point (weight c = |e| dt):
//   K += c n2 . ( (1 - xi) v_a^m + xi v_b^m - (1 - t) v_a^s - t v_b^s ),
//   g += c (X(t) - rho) . n2,   rho = (1 - xi) X_a^m + xi X_b^m.
// Interpolating the arc length (not the segment index + xi) keeps this exact for masters
// with non-uniform segments: on a flat master the projection abscissa is linear in t.
// A non-candidate end node (beyond an end of an open master) gets the abscissa extrapolated
// along the end segment (< 0 or > L); pieces of an edge lying beyond the master's ends are
// non-candidate: no K contribution, and g += c * (distance of x(t) to the end vertex) > 0,
// as in the pointwise rule. Slave and master chains may run in either direction (S may
// decrease along the edge). On a closed master S is taken modulo the master length.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

// Rows of the LAC macro-segments of `quadrature` (edges 2r and 2r + 1, a single last edge
// when their number is odd). `pointwise` must be project_slave_nodes(mesh, pair, w).
// Throws contactrb::Error on size mismatch.
ConstraintRows integrate_lac_rows(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                                  const PointwiseContact& pointwise, const Eigen::VectorXd& w);

// Rows `rows` only (a restricted evaluation: the EIM magic rows online); the other rows are
// zero. `pointwise` needs the projections of the slave nodes of those macro-segments only
// (lac_slave_positions). Throws contactrb::Error for a row outside [0, R).
ConstraintRows integrate_lac_rows(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                                  const PointwiseContact& pointwise, const Eigen::VectorXd& w,
                                  std::span<const int> rows);

// The slave chain positions that the macro-segments `rows` integrate over (sorted, unique):
// 2r, 2r + 1, 2r + 2 (fewer for a single-edge last row), for a chain of num_slave nodes.
std::vector<int> lac_slave_positions(std::span<const int> rows, int num_slave);

}  // namespace contactrb::contact
