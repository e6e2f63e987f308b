#pragma once
// Surface (Neumann) loads on a boundary group of P1 triangles: int_Gamma t . w ds.
#include <Eigen/Core>
#include <string>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::fem {

// A load per unit length of the current mesh: a fixed vector t, or a normal pressure p
// (t = -p n with n the outward normal of the edge, so p > 0 pushes into the body).
struct TractionLoad {
  std::string group;
  bool is_pressure = false;
  Eigen::Vector2d vector = Eigen::Vector2d::Zero();
  double pressure = 0.0;
};

// int_Gamma t . w over the edges of `load.group`; t is constant on each edge, so each end
// node of an edge of length |e| receives t |e| / 2 (exact for P1). Throws contactrb::Error
// naming the group for a missing group or a node index out of range.
Eigen::VectorXd traction_load(const mesh::Mesh& mesh, const TractionLoad& load);

// The body (0 or 1) whose triangles hold the edges of `group`. Throws contactrb::Error
// naming the group when it is missing, empty, or touches both bodies.
int traction_body(const mesh::Mesh& mesh, const std::string& group);

}  // namespace contactrb::fem
