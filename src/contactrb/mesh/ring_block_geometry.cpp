// generate_ring_block (geometries.hpp): paper Section 6.3, Fig. 17.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "contactrb/common/error.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "contactrb/mesh/gmsh_session.hpp"
#include "contactrb/mesh/structured.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::mesh {

namespace {

// Size grading, calibrated so that the defaults of RingBlockGeometry give about the 1590
// nodes of the paper's Fig. 17 (measured count in docs/meshes.md). The size caps are relative
// to the outer-arc node spacing (ring) and to the block height (block).
constexpr double kRingSlope = 0.3;            // size growth per unit distance from the outer arc
constexpr double kRingMaxSizeFactor = 1.5;    // ring size cap / outer-arc spacing
constexpr double kBlockSlope = 0.2;           // size growth per unit distance from the contact zone
constexpr double kBlockMaxSizeFactor = 0.072;  // block size cap / block height
// The fine, uniform part of the block's top edge covers [-R_out, R_out] shifted right by
// this fraction of its spacing, so that no master node sits below a slave node at the
// reference configuration (non-matching meshes, paper Section 6.3).
constexpr double kMasterShiftFraction = 0.25;
// Share of the top-edge segments given to the fine part, relative to its share of the width.
constexpr double kMasterZoneDensity = 1.1;

std::string format(double v) {
  std::ostringstream os;
  os.precision(17);
  os << "(" << v << ")";
  return os.str();
}

Mesh mesh_half_ring(const RingBlockGeometry& g) {
  const double R = g.R_out;
  const double r = g.R_out - g.thickness;
  const Eigen::Vector2d c(0.0, g.gap + R);
  const double spacing = std::numbers::pi * R / (g.slave_arc_nodes - 1);
  const double max_size = kRingMaxSizeFactor * spacing;
  const double inner_size = std::min(max_size, spacing + kRingSlope * g.thickness);
  const int inner_nodes = std::max(3, static_cast<int>(std::lround(std::numbers::pi * r / inner_size)) + 1);

  detail::GmshSession session("half_ring");
  try {
    const int lo = detail::add_point(c + Eigen::Vector2d(-R, 0.0));
    const int ro = detail::add_point(c + Eigen::Vector2d(R, 0.0));
    const int ri = detail::add_point(c + Eigen::Vector2d(r, 0.0));
    const int li = detail::add_point(c + Eigen::Vector2d(-r, 0.0));
    // Counter-clockwise: outer arc left -> bottom -> right, right end, inner arc back, left end.
    const auto outer = detail::add_arc(lo, ro, c, R, std::numbers::pi, 2.0 * std::numbers::pi, g.slave_arc_nodes);
    const int right_end = detail::add_segment(ro, ri);
    const auto inner = detail::add_arc(ri, li, c, r, 2.0 * std::numbers::pi, std::numbers::pi, inner_nodes);
    const int left_end = detail::add_segment(li, lo);
    std::vector<int> loop = outer;
    loop.push_back(right_end);
    loop.insert(loop.end(), inner.begin(), inner.end());
    loop.push_back(left_end);
    const int surface = detail::add_plane_surface(loop);
    detail::SizeRamp ramp{format(R) + " - Sqrt(x^2 + (y - " + format(c.y()) + ")^2)", spacing, max_size,
                          (max_size - spacing) / kRingSlope};
    detail::mesh_2d({ramp});
    return detail::extract_mesh({{surface, kSlaveBody}},
                                {{kSlaveBoundary, outer}, {"ring_ends", {right_end, left_end}}});
  } catch (...) {
    detail::rethrow_as_error("meshing the half-ring of the ring-block geometry");
  }
}

Mesh mesh_block(const RingBlockGeometry& g) {
  const double W = g.block_width;
  const double H = g.block_height;
  const double a = g.R_out;  // half-width of the fine part of the top edge
  const int segments = g.master_edge_nodes - 1;
  // Fine part: m segments, same parity as `segments` so both side parts get the same count.
  int m = static_cast<int>(std::lround(segments * (2.0 * a / W) * kMasterZoneDensity));
  m = std::clamp(m, 1, segments - 2);
  if ((segments - m) % 2 != 0) --m;
  const int side = (segments - m) / 2;
  const double h = 2.0 * a / m;
  const double shift = kMasterShiftFraction * h;
  const double xl = -a + shift;
  const double xr = a + shift;
  const double max_size = kBlockMaxSizeFactor * H;

  detail::GmshSession session("block");
  try {
    const int bl = detail::add_point({-0.5 * W, -H});
    const int br = detail::add_point({0.5 * W, -H});
    const int tr = detail::add_point({0.5 * W, 0.0});
    const int tl = detail::add_point({-0.5 * W, 0.0});
    const int pr = detail::add_point({xr, 0.0});
    const int pl = detail::add_point({xl, 0.0});
    const int bottom = detail::add_segment(bl, br);
    const int right = detail::add_segment(br, tr);
    // Side parts run outwards from the fine part so their progression grows away from it.
    const int top_right = detail::add_segment(
        pr, tr, side + 1, detail::progression_ratio(0.5 * W - xr, side, h));
    const int top_middle = detail::add_segment(pr, pl, m + 1);
    const int top_left = detail::add_segment(
        pl, tl, side + 1, detail::progression_ratio(0.5 * W + xl, side, h));
    const int left = detail::add_segment(tl, bl);
    const int surface = detail::add_plane_surface({bottom, right, -top_right, top_middle, top_left, left});
    // Distance to the fine part of the top edge.
    const std::string t = "(Sqrt((x - " + format(shift) + ")^2) - " + format(a) + ")";
    const std::string distance = "Sqrt(((" + t + " + Sqrt(" + t + "^2)) / 2)^2 + y^2)";
    detail::SizeRamp ramp{distance, h, std::max(h, max_size), std::max(h, max_size - h) / kBlockSlope};
    detail::mesh_2d({ramp});
    return detail::extract_mesh({{surface, kMasterBody}},
                                {{kMasterBoundary, {top_right, top_middle, top_left}}, {"block_bottom", {bottom}}});
  } catch (...) {
    detail::rethrow_as_error("meshing the block of the ring-block geometry");
  }
}

}  // namespace

Mesh generate_ring_block(const RingBlockGeometry& g) {
  require(g.R_out > 0.0, "ring-block R_out must be positive (got " + number_text(g.R_out) + ")");
  require(g.thickness > 0.0 && g.thickness < g.R_out,
          "ring-block thickness must be in (0, R_out) (got " + number_text(g.thickness) + ")");
  require(g.gap >= 0.0, "ring-block gap must be >= 0 (got " + number_text(g.gap) + ")");
  require(g.block_width > 2.0 * g.R_out,
          "ring-block block_width must exceed the ring's outer diameter 2 R_out (got " +
              number_text(g.block_width) + ")");
  require(g.block_height > 0.0, "ring-block block_height must be positive (got " + number_text(g.block_height) + ")");
  require(g.slave_arc_nodes >= 3, "ring-block slave_arc_nodes must be >= 3 (got " +
                                      std::to_string(g.slave_arc_nodes) + ")");
  require(g.master_edge_nodes >= 6, "ring-block master_edge_nodes must be >= 6 (got " +
                                        std::to_string(g.master_edge_nodes) + ")");
  Mesh mesh = merge(mesh_half_ring(g), mesh_block(g));
  validate(mesh);
  return mesh;
}

}  // namespace contactrb::mesh
