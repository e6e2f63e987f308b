// generate_hertz_3d, hertz_3d_fine_size_for_level (geometries.hpp): the Hertz sphere problem
// as a quarter model (docs/cases.md, "hertz-3d").
#include <gmsh.h>

#include <cmath>
#include <sstream>
#include <utility>

#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "contactrb/mesh/gmsh_session.hpp"
#include "contactrb/mesh/structured.hpp"

namespace contactrb::mesh {

namespace {

// Entity bounding boxes are compared with this absolute tolerance (OpenCASCADE pads them by
// about 1e-7 on lengths of order 1).
constexpr double kBoxTolerance = 1e-5;
// The symmetry groups of the master body before merge() joins them to the slave's.
constexpr const char* kMasterPrefix = "master_";
// Level 0 size in the contact zone, relative to the radius (docs/cases.md, "hertz-3d").
constexpr double kLevel0FineSize = 0.04;

struct Box {
  double xmin, ymin, zmin, xmax, ymax, zmax;
};

Box bounding_box(int dim, int tag) {
  Box b{};
  gmsh::model::getBoundingBox(dim, tag, b.xmin, b.ymin, b.zmin, b.xmax, b.ymax, b.zmax);
  return b;
}

std::vector<int> entity_tags(int dim) {
  gmsh::vectorpair entities;
  gmsh::model::getEntities(entities, dim);
  std::vector<int> tags;
  for (const auto& [d, tag] : entities) tags.push_back(tag);
  return tags;
}

// Surfaces bounding no volume (the part of a cutting rectangle outside the body) are removed.
void remove_free_surfaces() {
  gmsh::vectorpair free;
  for (int s : entity_tags(2)) {
    std::vector<int> up;
    std::vector<int> down;
    gmsh::model::getAdjacencies(2, s, up, down);
    if (up.empty()) free.emplace_back(2, s);
  }
  if (free.empty()) return;
  gmsh::model::occ::remove(free, /*recursive=*/true);
  gmsh::model::occ::synchronize();
}

bool is_internal(int surface) {
  std::vector<int> up;
  std::vector<int> down;
  gmsh::model::getAdjacencies(2, surface, up, down);
  return up.size() > 1;
}

// Size h = fine_size within fine_radius of the first contact point, growing linearly to
// coarse_size at coarse_radius.
detail::SizeRamp contact_ramp(const Hertz3dGeometry& g) {
  std::ostringstream distance;
  distance.precision(17);
  distance << "Sqrt(x^2 + y^2 + (z - (" << 0.5 * g.gap << "))^2)";
  detail::SizeRamp ramp{distance.str(), g.fine_size, g.coarse_size, g.coarse_radius};
  ramp.dist_min = g.fine_radius;
  return ramp;
}

// Body 0: the quarter {x, y >= 0} of the lower half of the ball of radius R centred at
// (0, 0, gap/2 + R), cut at the height of the slave cap into two volumes.
Mesh3 mesh_hemisphere(const Hertz3dGeometry& g) {
  detail::GmshSession session("hertz3d_hemisphere");
  try {
    namespace occ = gmsh::model::occ;
    const double zc = 0.5 * g.gap + g.R;
    const double z_cut = 0.5 * g.gap + g.cap_height * g.R;
    gmsh::vectorpair quarter;
    gmsh::vectorpair pieces;
    std::vector<gmsh::vectorpair> map;
    occ::intersect({{3, occ::addSphere(0.0, 0.0, zc, g.R)}}, {{3, occ::addBox(0.0, 0.0, zc - g.R, g.R, g.R, g.R)}},
                   quarter, map);
    occ::fragment(quarter, {{2, occ::addRectangle(0.0, 0.0, z_cut, g.R, g.R)}}, pieces, map);
    occ::synchronize();
    remove_free_surfaces();
    std::map<std::string, std::vector<int>> groups;
    for (int s : entity_tags(2)) {
      const Box b = bounding_box(2, s);
      if (b.xmax < kBoxTolerance) {
        groups["symmetry_x"].push_back(s);
      } else if (b.ymax < kBoxTolerance) {
        groups["symmetry_y"].push_back(s);
      } else if (b.zmin > zc - kBoxTolerance) {
        groups["top"].push_back(s);
      } else if (!is_internal(s)) {  // curved: below or above the cut (bounding boxes of curved faces are loose)
        double x = 0.0, y = 0.0, z = 0.0;
        gmsh::model::occ::getCenterOfMass(2, s, x, y, z);
        groups[z < z_cut ? kSlaveBoundary : "sphere_free"].push_back(s);
      }
    }
    std::map<int, int> bodies;
    for (int v : entity_tags(3)) bodies.emplace(v, kSlaveBody);
    detail::mesh_3d_occ({contact_ramp(g)});
    return detail::extract_mesh3(bodies, groups);
  } catch (...) {
    detail::rethrow_as_error("meshing the hertz-3d hemisphere of radius " + number_text(g.R));
  }
}

// Body 1: the block [0, W]^2 x [-gap/2 - H, -gap/2].
Mesh3 mesh_block(const Hertz3dGeometry& g) {
  detail::GmshSession session("hertz3d_block");
  try {
    const double z_top = -0.5 * g.gap;
    const double W = g.block_width;
    const int volume = gmsh::model::occ::addBox(0.0, 0.0, z_top - g.block_height, W, W, g.block_height);
    gmsh::model::occ::synchronize();
    const std::string prefix = kMasterPrefix;
    std::map<std::string, std::vector<int>> groups;
    for (int s : entity_tags(2)) {
      const Box b = bounding_box(2, s);
      if (b.xmax < kBoxTolerance) {
        groups[prefix + "symmetry_x"].push_back(s);
      } else if (b.ymax < kBoxTolerance) {
        groups[prefix + "symmetry_y"].push_back(s);
      } else if (b.zmin > z_top - kBoxTolerance) {
        groups[kMasterBoundary].push_back(s);
      } else if (b.zmax < z_top - g.block_height + kBoxTolerance) {
        groups["bottom"].push_back(s);
      } else {
        groups["master_sides"].push_back(s);
      }
    }
    detail::mesh_3d_occ({contact_ramp(g)});
    return detail::extract_mesh3({{volume, kMasterBody}}, groups);
  } catch (...) {
    detail::rethrow_as_error("meshing the hertz-3d block");
  }
}

// OpenCASCADE places nodes of a plane face within round-off (1e-16) of the plane: they are put
// on it, so that the symmetry planes and the contact faces are exact.
void snap_to_plane(Mesh3& mesh, const std::string& group, int axis, double value) {
  for (int v : boundary_nodes(mesh, group)) mesh.nodes[static_cast<std::size_t>(v)](axis) = value;
}

void check_geometry(const Hertz3dGeometry& g) {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  require(positive(g.R), "hertz-3d radius must be positive (got " + number_text(g.R) + ")");
  require(std::isfinite(g.gap) && g.gap >= 0.0, "hertz-3d gap must be >= 0 (got " + number_text(g.gap) + ")");
  require(positive(g.block_width) && positive(g.block_height), "hertz-3d block sizes must be positive");
  require(g.cap_height > 0.0 && g.cap_height < 1.0,
          "hertz-3d cap_height must be in (0, 1) (got " + number_text(g.cap_height) + ")");
  require(positive(g.fine_size) && g.fine_size <= g.coarse_size && g.fine_radius < g.coarse_radius,
          "hertz-3d sizes: need 0 < fine_size <= coarse_size and fine_radius < coarse_radius");
}

}  // namespace

double hertz_3d_fine_size_for_level(int level) {
  require(level >= 0 && level <= kMaxHertz3dLevel, "hertz-3d mesh level must be in [0, " +
                                                       std::to_string(kMaxHertz3dLevel) + "] (got " +
                                                       std::to_string(level) + ")");
  return std::ldexp(kLevel0FineSize, -level);
}

Mesh3 generate_hertz_3d(const Hertz3dGeometry& g) {
  check_geometry(g);
  Mesh3 mesh = merge(mesh_hemisphere(g), mesh_block(g));
  for (const char* group : {"symmetry_x", "symmetry_y"}) {
    const std::string master = std::string(kMasterPrefix) + group;
    auto& joined = mesh.boundaries[group];
    const auto& facets = mesh.boundaries.at(master);
    joined.insert(joined.end(), facets.begin(), facets.end());
    mesh.boundaries.erase(master);
  }
  snap_to_plane(mesh, "symmetry_x", 0, 0.0);
  snap_to_plane(mesh, "symmetry_y", 1, 0.0);
  snap_to_plane(mesh, "top", 2, 0.5 * g.gap + g.R);
  snap_to_plane(mesh, kMasterBoundary, 2, -0.5 * g.gap);
  snap_to_plane(mesh, "bottom", 2, -0.5 * g.gap - g.block_height);
  validate(mesh);
  return mesh;
}

}  // namespace contactrb::mesh
