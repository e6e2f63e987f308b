#pragma once
// The slave and master contact boundaries as ordered node chains, and the quadrature that
// turns pointwise constraints at slave nodes into the rows of K(w), g(w) (paper (10)-(11)).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <type_traits>
#include <vector>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

// Collocation: paper 6.1.1. LAC: macro-segments of two slave edges, rows integrated exactly
// (segment to segment, lac_integration.hpp); our default LAC because it passes the contact
// patch test. LACSimpson: the paper's (62), Simpson's rule on the three slave nodes of each
// macro-segment, kept for comparison (not consistent for P1 fields, docs/contact.md).
enum class Discretization { Collocation, LAC, LACSimpson };
const char* to_string(Discretization d);
Discretization discretization_from_string(const std::string& name);  // "collocation" | "lac" | "lac-simpson"

// Slave boundary Gamma_1^c (body 0) and master boundary Gamma_2^c (body 1) as ordered
// chains of node indices (mesh groups "slave" and "master", in edge orientation).
// A closed master loop is stored with its first node repeated at the end
// (master.front() == master.back()), so master segment k is always (master[k], master[k+1]).
struct ContactPair {
  std::vector<int> slave;
  std::vector<int> master;
};
// Throws contactrb::Error if a group is missing, not a single polyline, has fewer than two
// nodes, or lies on the wrong body, or if the slave chain is a closed loop.
ContactPair make_contact_pair(const mesh::Mesh& mesh);

// 3D: the slave surface Gamma_1^c (body 0) and the master surface Gamma_2^c (body 1) as the
// boundary triangles of the groups "slave" and "master" (outward oriented, mesh/mesh.hpp).
struct ContactPair3 {
  std::vector<int> slave;                        // slave nodes, sorted (one constraint each)
  std::vector<mesh::Face> slave_faces;           // group "slave" (mesh node indices)
  std::vector<int> master;                       // master nodes, sorted
  std::vector<std::array<int, 3>> master_faces;  // group "master", as positions in `master`
  // The rim of the master surface: the edges of exactly one master triangle, as (face, i)
  // with i the face vertex opposite the edge. A slave node whose closest point lies on the
  // rim, outside the master surface, is no candidate (docs/contact.md, "Three dimensions").
  std::vector<std::array<int, 2>> master_rim;
};
// Throws contactrb::Error if a group is missing or empty, or a node lies on the wrong body.
ContactPair3 make_contact_pair(const mesh::Mesh3& mesh);

// The contact pair of a dimension: ContactPair (node chains) in 2D, ContactPair3 in 3D.
template <int Dim>
using ContactPairOf = std::conditional_t<Dim == 2, ContactPair, ContactPair3>;

// Row r of K and g is int_{I_r} (pointwise value) psi_r. W (R x S) is a quadrature over
// the slave nodes; multipliers are then contact pressures.
//  Collocation (6.1.1): one row per slave node, W = diag(|I_r|), |I_r| = half the two
//    adjacent slave edges; rows = W * pointwise.
//  LAC and LACSimpson (6.1.2): one row per macro-segment of two slave edges (with an odd
//    number of slave edges the last macro-segment is the single last edge).
//    LAC: W holds the exact slave-side weights int_{I_r} phi_s (h1/2, (h1+h2)/2, h2/2; a
//      single edge h/2, h/2), exact for P1 on the slave side; the rows themselves are
//      integrated exactly segment to segment by constraint_rows (lac_integration.hpp).
//    LACSimpson: Simpson's rule (62), |I|/6, 4|I|/6, |I|/6 on the three nodes (a single
//      edge: trapezoidal rule); rows = W * pointwise.
struct ContactQuadrature {
  Discretization discretization = Discretization::Collocation;
  Eigen::SparseMatrix<double, Eigen::RowMajor> W;  // R x S, S = slave.size()
  Eigen::VectorXd weight;                          // |I_r| (row sums of W)
  std::vector<int> center_node;                    // mesh node index of the slave node at
                                                   // the center of I_r (collocation: z_r;
                                                   // LAC: the middle node; a single-edge
                                                   // last segment: its first node)
};
// Built on the undeformed configuration of `mesh` (i.e. Omega(mu), not Omega(mu) + w).
ContactQuadrature make_quadrature(const mesh::Mesh& mesh, const ContactPair& pair, Discretization d);
// 3D: one row per slave node with |I_r| = its nodal area (one third of the area of each
// adjacent slave triangle); the weights sum to the area of Gamma_1^c. Collocation: W = diag(|I_r|).
// LAC: I_r is the median dual cell of the node and W_rs = int_{I_r} phi_s (exact for P1 on the
// slave side); the rows are integrated exactly by constraint_rows (lac3d.hpp). LACSimpson throws
// contactrb::Error (not available in 3D).
ContactQuadrature make_quadrature(const mesh::Mesh3& mesh, const ContactPair3& pair, Discretization d);

}  // namespace contactrb::contact
