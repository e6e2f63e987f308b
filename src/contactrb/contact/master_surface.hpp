#pragma once
// The deformed master surface in 3D, the counterpart of master_polyline.hpp: vertices,
// triangle normals, the continuous vertex-normal field and the rim conormals. Internal to
// the contact module (no stable API).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::contact {

struct MasterSurface {
  std::vector<Eigen::Vector3d> y;              // deformed vertices y_j = X_j + w_j, one per pair.master entry
  std::vector<std::array<int, 3>> face;        // positions in y (pair.master_faces)
  std::vector<Eigen::Vector3d> normal;         // unit outward normal of each triangle
  std::vector<Eigen::Vector3d> vertex_normal;  // n_j: angle-weighted average of the adjacent triangle normals
  // Rim edges (pair.master_rim): the outward conormal (in the triangle's plane, normal to the
  // edge, pointing away from the triangle) and the edge length; per vertex, its rim edges.
  std::vector<Eigen::Vector3d> rim_conormal;
  std::vector<double> rim_length;
  std::vector<std::array<int, 3>> face_rim;    // per triangle and opposite vertex i: rim edge or -1
  std::vector<int> vertex_rim_start, vertex_rim;  // CSR: rim edges at vertex j
  int num_facets() const { return static_cast<int>(face.size()); }
  // The continuous normal field: normalize(sum_i phi_i n_{v_i}) over triangle f; the triangle
  // normal in the degenerate case of a vanishing sum (a folded master).
  Eigen::Vector3d normal_at(int f, const Eigen::Vector3d& phi) const;
};

// Throws contactrb::Error if a deformed master triangle has zero area (its normal is undefined).
// Node indices are not checked here (callers do).
MasterSurface deformed_master(const mesh::Mesh3& mesh, const ContactPair3& pair, const Eigen::VectorXd& w);

}  // namespace contactrb::contact
