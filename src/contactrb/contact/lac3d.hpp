#pragma once
// The exactly integrated LAC in 3D (Discretization::LAC on a Mesh3; docs/contact.md, "LAC in
// three dimensions"): one row per slave node r, psi_r = 1 on its median dual cell I_r (in each
// adjacent slave triangle the quadrilateral of the vertex, the two edge midpoints and the
// centroid, i.e. where the vertex's barycentric coordinate is the largest), and
//   K(w)_r v = int_{I_r} k(w; v),   g(w)_r = int_{I_r} g(w)   (paper (10)-(11)),
// integrated on the reference slave surface, so that the multipliers are contact pressures
// and |I_r| is the nodal area of collocation.
//
// Each slave triangle T is seen along one direction d_T, the normalized sum of the continuous
// master normals n2 at the projections of its three vertices. T and the candidate master
// triangles (a box query on the facet tree around the feet of T's vertices) are projected
// along d_T on a plane; in that plane each cell of T is clipped by each master triangle
// (polygon_clip.hpp), and on every piece the pointwise maps (27)-(28) are evaluated with the
// master point on the line through the slave point along d_T:
//   K_r += c n2 . (sum_j mu_j v_j^m - sum_i lambda_i v_i^s),   g_r += c (X - rho) . n2,
// lambda the slave and mu the master barycentric coordinates, rho = sum_j mu_j X_j^m, n2 the
// continuous master normal at mu, c the quadrature weight on the reference slave triangle
// (three points per triangle of the piece's fan, exact for quadratic integrands). On a flat
// master d_T is the master normal, the line is the closest-point projection, the integrand
// is affine on each piece, and the rows are the exact integrals of the pointwise maps.
// Partial coverage: the part of a cell whose projection meets no master triangle (beyond the
// rim) adds nothing to K and adds (its area) x (the distance of the deformed slave point at
// its centroid to the master surface) to g, the 2D rule for slave edges beyond a master end.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

// Rows of the 3D LAC quadrature (make_quadrature(Mesh3, pair, LAC)). `pointwise` must be
// project_slave_nodes(mesh, pair, w). Throws contactrb::Error on size mismatch.
ConstraintRows integrate_lac_rows(const mesh::Mesh3& mesh, const ContactPair3& pair,
                                  const ContactQuadrature& quadrature, const PointwiseContact3& pointwise,
                                  const Eigen::VectorXd& w);

// Rows `rows` only (a restricted evaluation); the other rows are zero. `pointwise` needs the
// projections of lac_slave_positions(pair, rows) only. Throws for a row outside [0, R).
ConstraintRows integrate_lac_rows(const mesh::Mesh3& mesh, const ContactPair3& pair,
                                  const ContactQuadrature& quadrature, const PointwiseContact3& pointwise,
                                  const Eigen::VectorXd& w, std::span<const int> rows);

// The slave positions (indices in pair.slave) whose projections rows `rows` need: the vertices
// of the slave triangles around their nodes (sorted, unique).
std::vector<int> lac_slave_positions(const ContactPair3& pair, std::span<const int> rows);

// How much of the slave surface the master covers along the directions d_T (reference areas).
struct LacCoverage3 {
  Eigen::VectorXd triangle_area;  // per slave triangle (pair.slave_faces)
  Eigen::VectorXd covered_area;   // per slave triangle: the sum of its pieces over the master triangles
  Eigen::VectorXd row_covered;    // per row: the covered part of |I_r|
};
LacCoverage3 lac_coverage(const mesh::Mesh3& mesh, const ContactPair3& pair, const PointwiseContact3& pointwise,
                          const Eigen::VectorXd& w);

}  // namespace contactrb::contact
