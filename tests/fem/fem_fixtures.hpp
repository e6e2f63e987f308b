#pragma once
// Small meshes shared by the fem tests.
#include <string>

#include "contactrb/mesh/structured.hpp"

namespace fem_test {

// Two disjoint rectangles: body 0 on [0,1]x[0,1] (groups bottom/right/top/left), body 1 on
// [1.5,2.5]x[0,1.2] (groups b_bottom/b_right/b_top/b_left), interiors perturbed.
inline contactrb::mesh::Mesh two_bodies(int nx0, int ny0, int nx1, int ny1, double perturbation = 0.3) {
  using namespace contactrb::mesh;
  Mesh a = rectangle(0.0, 0.0, 1.0, 1.0, nx0, ny0, kSlaveBody);
  Mesh b = rectangle(1.5, 0.0, 2.5, 1.2, nx1, ny1, kMasterBody);
  for (const char* g : {"bottom", "right", "top", "left"}) rename_boundary(b, g, std::string("b_") + g);
  Mesh m = merge(a, b);
  perturb_interior(m, perturbation, 3);
  return m;
}

}  // namespace fem_test
