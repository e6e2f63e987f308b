#pragma once
// Closest-point projection of deformed slave nodes onto the deformed master polyline and
// the pointwise contact and gap maps (paper (22)-(28), DESIGN.md "Numerical choices").
//
// For slave node s with position X_s in Omega(mu) and deformed position x_s = X_s + w_s,
// the closest point of the deformed master polyline lies on segment k = (a, b) at parameter
// xi in [0, 1]; rho = (1 - xi) X_a + xi X_b. Then
//   k(w; v)_s = ((1 - xi) v_a + xi v_b - v_s) . n2   (27)
//   g(w)_s    = (X_s - rho) . n2                     (28)
// and non-penetration reads k(w; u) <= g(w).
// n2 is a continuous normal field on the master polyline, not the segment normal: with the
// vertex normals n_j = normalized average of the two adjacent (deformed) segment normals
// (an end vertex of an open chain: its only segment's normal; a closed chain wraps),
//   n2 = normalize((1 - xi) n_k + xi n_{k+1}).
// Reason: continuity of the fixed-point map w -> (K(w), g(w)) iterated by Kacanov. With the
// segment normal, a slave node sitting on a master vertex (e.g. Hertz with matching meshes)
// jumps between "closest point = vertex" (averaged normal) and "closest point = segment
// interior" (segment normal) under round-off, and the iteration stalls at ~1e-6. With the
// interpolated normal, (segment k, xi = 1) and (segment k + 1, xi = 0) give the same K row
// and gap, so K and g are continuous in w where the closest segment switches at a vertex
// (as long as the closest point itself moves continuously, e.g. on convex masters).
// On a flat master every n_j equals the segment normal: nothing changes there.
// Ties (a slave node equidistant from several segments, e.g. from the two segments at a
// vertex) go to the lowest segment index, so a vertex between segments k and k+1 is reported
// as (k, xi = 1).
// A slave node is a candidate when its closest point is not an end point of the master
// chain approached from outside (no master facing it). Non-candidates get a zero K row
// and g = their distance to the master polyline (> 0), so the constraint is inactive;
// their projection record (segment, xi, normal, rho, distance) is still filled.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <span>
#include <string>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

// Where a slave node projects: in 2D a segment and xi, in 3D a triangle and its barycentric
// coordinates (docs/contact.md, "Three dimensions").
template <int Dim>
struct NodeProjection;

template <>
struct NodeProjection<2> {
  int segment = -1;         // index k of master segment (master[k], master[k+1])
  double xi = 0.0;          // in [0, 1]
  Eigen::Vector2d normal{0.0, 0.0};  // n2, unit, outward of the master body (interpolated)
  Eigen::Vector2d rho{0.0, 0.0};     // (1 - xi) X_a + xi X_b (undeformed)
  double distance = 0.0;    // |x_s - closest deformed master point|
  bool candidate = false;
};

template <>
struct NodeProjection<3> {
  int facet = -1;                         // index f of master triangle pair.master_faces[f]
  Eigen::Vector3d phi{0.0, 0.0, 0.0};     // barycentric coordinates of the closest point
  Eigen::Vector3d normal{0.0, 0.0, 0.0};  // n2, unit, outward of the master body (interpolated)
  Eigen::Vector3d rho{0.0, 0.0, 0.0};     // sum_i phi_i X_{t_i} (undeformed)
  double distance = 0.0;                  // |x_s - closest deformed master point|
  bool candidate = false;
};

using SlaveProjection = NodeProjection<2>;
using SlaveProjection3 = NodeProjection<3>;

template <int Dim>
struct PointwiseContactOf {
  std::vector<NodeProjection<Dim>> projection;     // one per slave node
  Eigen::SparseMatrix<double, Eigen::RowMajor> K;  // S x num_dofs, rows k(w; .)_s
  Eigen::VectorXd g;                               // S, g(w)_s
};
using PointwiseContact = PointwiseContactOf<2>;
using PointwiseContact3 = PointwiseContactOf<3>;

// How the closest master segment is found. Both methods return exactly the same result:
// the segment minimizing (squared distance, segment index) lexicographically.
enum class SearchMethod {
  Automatic,  // AllPairs below ProjectionOptions::tree_min_segments segments, Tree from there
  AllPairs,   // O(S M): every slave node against every master segment
  Tree,       // bounding-volume tree over the master facets (O(M log M) build, ~O(log M) per node)
};
const char* to_string(SearchMethod value);  // "automatic" | "all-pairs" | "tree"
SearchMethod search_method_from_string(const std::string& name);  // throws contactrb::Error

struct ProjectionOptions {
  SearchMethod search = SearchMethod::Automatic;
  // Master facet count (segments in 2D, triangles in 3D) from which Automatic uses the tree
  // (bench_contact: the tree already wins at 100 segments; below 32, all-pairs is as fast
  // and simplest).
  int tree_min_segments = 32;
  // A slave node is "beyond" an end of an open master chain when its projection parameter on
  // the end segment is < -end_tolerance or > 1 + end_tolerance (relative to the segment
  // length). The tolerance keeps a slave node aligned with the master end (same-width
  // bodies) a candidate despite round-off. 3D: beyond a rim edge of the master surface when
  // (x_s - p) . m > end_tolerance |e| + rim_angle_tolerance |x_s - p|, with p the closest point
  // on the edge, m the edge's outward conormal (in the plane of its deformed triangle) and |e|
  // its length.
  double end_tolerance = 1e-10;
  // 3D only: how far (radians) the direction from the rim to x_s may lean outwards before x_s is
  // beyond it. A slave node above a rim edge on a symmetry plane (both bodies on rollers there)
  // leans by the tilt of the deformed master triangle, O(strain), times its gap; without this
  // angle such nodes near the contact zone switch between candidate and not from one iterate to
  // the next, and Kacanov and the Newton cycle on hertz-3d (docs/contact.md, "Three dimensions").
  // Measured there (level 1, mu 0.03): 0.005 still cycles, 0.01 converges; 0.05 keeps a margin.
  double rim_angle_tolerance = 0.05;
};

// w: global displacement (num_dofs). A closed master chain (master.front() == master.back(),
// see make_contact_pair) has no end, so every slave node is a candidate.
// Throws contactrb::Error on size mismatch, non-finite w, a node index out of range, or a
// deformed master segment of zero length (its normal is undefined).
PointwiseContact project_slave_nodes(const mesh::Mesh& mesh, const ContactPair& pair,
                                     const Eigen::VectorXd& w, const ProjectionOptions& options = {});

// The same, for the slave chain positions `positions` only (a restricted evaluation: the EIM
// magic rows online need a few slave nodes). The entries of the other slave nodes keep their
// defaults: segment -1, empty K row, g = 0. Positions must lie in [0, S); repeats are harmless.
PointwiseContact project_slave_nodes(const mesh::Mesh& mesh, const ContactPair& pair, const Eigen::VectorXd& w,
                                     std::span<const int> positions, const ProjectionOptions& options = {});

// 3D: the same maps over the master triangles (docs/contact.md, "Three dimensions"): the
// closest point of x_s on the deformed master surface lies on triangle f = (t_0, t_1, t_2)
// with barycentric coordinates phi, rho = sum_i phi_i X_{t_i}, and
//   k(w; v)_s = (sum_i phi_i v_{t_i} - v_s) . n2   (27),    g(w)_s = (X_s - rho) . n2   (28),
// n2 = normalize(sum_i phi_i n_{t_i}) with n_j the angle-weighted vertex normals. Ties go to
// the lowest triangle index. A slave node whose closest point lies on the rim of the master
// surface with x_s beyond it (ProjectionOptions::end_tolerance) is no candidate. DOF 3i + c.
// Throws as the 2D version, and on a deformed master triangle of zero area.
PointwiseContact3 project_slave_nodes(const mesh::Mesh3& mesh, const ContactPair3& pair, const Eigen::VectorXd& w,
                                      const ProjectionOptions& options = {});
PointwiseContact3 project_slave_nodes(const mesh::Mesh3& mesh, const ContactPair3& pair, const Eigen::VectorXd& w,
                                      std::span<const int> positions, const ProjectionOptions& options = {});

// The constraint rows of a discretization (paper (10)-(11)): row r = int_{I_r} k(w; .) psi_r
// and int_{I_r} g(w) psi_r.
//  Collocation and LACSimpson: K = W K_pt, g = W g_pt (the quadrature on the slave nodes).
//  LAC: exact segment-to-segment integration over each macro-segment (lac_integration.hpp);
//    it needs the geometry: `pointwise` must be project_slave_nodes(mesh, pair, w).
struct ConstraintRows {
  Eigen::SparseMatrix<double, Eigen::RowMajor> K;  // R x num_dofs
  Eigen::VectorXd g;                               // R
};
ConstraintRows constraint_rows(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                               const PointwiseContact& pointwise, const Eigen::VectorXd& w);
// 3D: Collocation, K = W K_pt, g = W g_pt with W the nodal areas (make_quadrature); LAC, exact
// integration over the median dual cells of the slave nodes (lac3d.hpp).
ConstraintRows constraint_rows(const mesh::Mesh3& mesh, const ContactPair3& pair, const ContactQuadrature& quadrature,
                               const PointwiseContact3& pointwise, const Eigen::VectorXd& w);

}  // namespace contactrb::contact
