#pragma once
// The deformed master polyline shared by the pointwise projection (projection.cpp) and the
// exactly integrated LAC rows (lac_integration.cpp): vertices, segment normals, the
// continuous vertex-normal field and the curvilinear abscissa. Internal to the contact
// module (no stable API).
#include <Eigen/Core>
#include <vector>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

struct MasterPolyline {
  std::vector<Eigen::Vector2d> y;               // deformed vertices y_j = X_j + w_j, one per chain entry
  std::vector<Eigen::Vector2d> normal;          // unit outward normal of segment k = (y_k, y_k+1)
  std::vector<Eigen::Vector2d> vertex_normal;   // n_j: normalized average of the adjacent segment normals
  std::vector<double> abscissa;                 // L_j: deformed arc length from y_0 to y_j
  bool closed = false;                          // first chain entry repeated at the end
  int num_segments() const { return static_cast<int>(normal.size()); }
  double length() const { return abscissa.back(); }
  // The continuous normal field: normalize((1 - xi) n_k + xi n_k+1); the segment normal in the
  // degenerate case of opposite vertex normals (a folded master).
  Eigen::Vector2d normal_at(int k, double xi) const;
};

// Throws contactrb::Error if a deformed segment has zero length (its normal is undefined).
// Node indices are not checked here (callers do).
MasterPolyline deformed_master(const mesh::Mesh& mesh, const std::vector<int>& master, const Eigen::VectorXd& w);

}  // namespace contactrb::contact
