#include "contactrb/mesh/half_disk_mesher.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "contactrb/common/error.hpp"
#include "contactrb/mesh/gmsh_session.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::mesh::detail {

Mesh mesh_half_disk(const HalfDiskSpec& spec) {
  require(spec.radius > 0.0, "half-disk radius must be positive (got " + number_text(spec.radius) + ")");
  require(spec.arc_nodes >= 3, "half-disk arc needs at least 3 nodes (got " + std::to_string(spec.arc_nodes) + ")");
  const double R = spec.radius;
  const Eigen::Vector2d& c = spec.center;
  const double arc_spacing = std::numbers::pi * R / (spec.arc_nodes - 1);
  const double max_size = std::max(arc_spacing, spec.sizing.max_size_factor * R);

  GmshSession session("half_disk");
  try {
    const int left = add_point(c + Eigen::Vector2d(-R, 0.0));
    const int right = add_point(c + Eigen::Vector2d(R, 0.0));
    std::vector<int> loop;
    std::vector<int> arc;
    int flat = 0;
    if (spec.arc_below) {  // left -> bottom -> right, then back along the top
      arc = add_arc(left, right, c, R, std::numbers::pi, 2.0 * std::numbers::pi, spec.arc_nodes);
      flat = add_segment(right, left);
    } else {  // right -> top -> left, then back along the bottom
      arc = add_arc(right, left, c, R, 0.0, std::numbers::pi, spec.arc_nodes);
      flat = add_segment(left, right);
    }
    loop = arc;
    loop.push_back(flat);
    const int surface = add_plane_surface(loop);

    std::ostringstream distance;
    distance.precision(17);
    distance << R << " - Sqrt((x - (" << c.x() << "))^2 + (y - (" << c.y() << "))^2)";
    SizeRamp ramp{distance.str(), arc_spacing, max_size,
                  (max_size - arc_spacing) / spec.sizing.slope};
    mesh_2d({ramp});
    return extract_mesh({{surface, spec.body}}, {{spec.arc_group, arc}, {spec.flat_group, {flat}}});
  } catch (...) {
    rethrow_as_error("meshing a half-disk of radius " + number_text(R));
  }
}

}  // namespace contactrb::mesh::detail
