#pragma once
// Closest-point projection of deformed slave nodes onto the deformed master polyline and
// the pointwise contact and gap maps (paper (22)-(28), DESIGN.md "Numerical choices").
//
// For slave node s with position X_s in Omega(mu) and deformed position x_s = X_s + w_s,
// the closest point of the deformed master polyline lies on segment (a, b) at parameter
// xi in [0, 1]; n2 is the master's outward unit normal there (at a vertex: the normalized
// average of the two adjacent segment normals); rho = (1 - xi) X_a + xi X_b. Then
//   k(w; v)_s = ((1 - xi) v_a + xi v_b - v_s) . n2   (27)
//   g(w)_s    = (X_s - rho) . n2                     (28)
// and non-penetration reads k(w; u) <= g(w).
// A slave node is a candidate when its closest point is not an end point of the master
// chain approached from outside (no master facing it). Non-candidates get a zero K row
// and g = their distance to the master polyline (> 0), so the constraint is inactive.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

struct SlaveProjection {
  int segment = -1;         // index k of master segment (master[k], master[k+1])
  double xi = 0.0;          // in [0, 1]
  Eigen::Vector2d normal{0.0, 0.0};  // n2, unit, outward of the master body
  Eigen::Vector2d rho{0.0, 0.0};     // (1 - xi) X_a + xi X_b (undeformed)
  double distance = 0.0;    // |x_s - closest deformed master point|
  bool candidate = false;
};

struct PointwiseContact {
  std::vector<SlaveProjection> projection;         // one per slave node
  Eigen::SparseMatrix<double, Eigen::RowMajor> K;  // S x num_dofs, rows k(w; .)_s
  Eigen::VectorXd g;                               // S, g(w)_s
};

// w: global displacement (num_dofs). Uses a bounding-box grid search beyond about 1000
// master segments; all-pairs below. Throws contactrb::Error on size mismatch or non-finite w.
PointwiseContact project_slave_nodes(const mesh::Mesh& mesh, const ContactPair& pair,
                                     const Eigen::VectorXd& w);

// The constraint rows for a discretization: K = W K_pt, g = W g_pt (paper (10)-(11)).
struct ConstraintRows {
  Eigen::SparseMatrix<double, Eigen::RowMajor> K;  // R x num_dofs
  Eigen::VectorXd g;                               // R
};
ConstraintRows constraint_rows(const ContactQuadrature& quadrature, const PointwiseContact& pointwise);

}  // namespace contactrb::contact
