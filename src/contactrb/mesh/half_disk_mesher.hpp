#pragma once
// Internal to contactrb_mesh: Gmsh mesh of one half-disk with a prescribed number of
// equally spaced arc nodes and a size graded from the arc towards the flat edge.
#include <Eigen/Core>
#include <string>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::mesh::detail {

// Element size h(d) = min(h_arc + slope * d, max_size_factor * R), d = distance to the arc,
// h_arc = arc node spacing. Defaults calibrated so that two Hertz half-disks with 51, 61
// and 121 slave-arc nodes have about 675, 802 and 1682 nodes (paper Fig. 2, Tables 1-2;
// measured counts in docs/meshes.md).
struct HalfDiskSizing {
  double slope = 0.14;
  double max_size_factor = 0.082;
};

struct HalfDiskSpec {
  Eigen::Vector2d center{0.0, 0.0};
  double radius = 1.0;
  int arc_nodes = 51;
  bool arc_below = false;  // false: {y > center.y} (arc above), true: arc below
  int body = kSlaveBody;
  std::string arc_group = "arc";
  std::string flat_group = "flat";
  HalfDiskSizing sizing;
};

// Throws contactrb::Error for radius <= 0 or arc_nodes < 3.
Mesh mesh_half_disk(const HalfDiskSpec& spec);

}  // namespace contactrb::mesh::detail
