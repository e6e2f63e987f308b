#pragma once
// Surface (Neumann) loads on a boundary group: int_Gamma t . w ds over the group's edges
// (2D) or triangles (3D).
#include <Eigen/Core>
#include <string>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::fem {

// A load per unit length (2D) or area (3D) of the current mesh: a fixed vector t, or a normal
// pressure p (t = -p n with n the outward normal of the facet, so p > 0 pushes into the body).
template <int Dim>
struct SurfaceLoad {
  std::string group;
  bool is_pressure = false;
  Eigen::Matrix<double, Dim, 1> vector = Eigen::Matrix<double, Dim, 1>::Zero();
  double pressure = 0.0;
};
using TractionLoad = SurfaceLoad<2>;
using TractionLoad3 = SurfaceLoad<3>;

// int_Gamma t . w over the facets of `load.group`; t is constant on each (flat) facet, so each
// of the Dim nodes of a facet of measure |F| receives t |F| / Dim (exact for P1). Throws
// contactrb::Error naming the group for a missing group, a contact group or a node index out
// of range.
template <int Dim>
Eigen::VectorXd traction_load(const mesh::SimplexMesh<Dim>& mesh, const SurfaceLoad<Dim>& load);

// The body (0 or 1) whose cells hold the facets of `group`. Throws contactrb::Error
// naming the group when it is missing, empty, or touches both bodies.
template <int Dim>
int traction_body(const mesh::SimplexMesh<Dim>& mesh, const std::string& group);

}  // namespace contactrb::fem
