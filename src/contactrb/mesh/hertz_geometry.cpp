// generate_hertz, hertz_arc_nodes_for_level, generate_half_disk (geometries.hpp).
#include <cmath>
#include <utility>

#include "contactrb/common/error.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "contactrb/mesh/half_disk_mesher.hpp"
#include "contactrb/mesh/structured.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::mesh {

namespace {

// Mirror image y -> -y of a one-body mesh, as body `body`, with group names mapped by
// `rename`. Mirroring reverses orientation, so triangles and edges are reversed to stay
// counter-clockwise with the body on the left.
Mesh mirrored(const Mesh& m, int body, const std::map<std::string, std::string>& rename) {
  Mesh out;
  out.nodes.reserve(m.nodes.size());
  for (const auto& p : m.nodes) out.nodes.emplace_back(p.x(), -p.y());
  for (const auto& t : m.triangles) out.triangles.push_back({t[0], t[2], t[1]});
  out.body.assign(m.triangles.size(), body);
  for (const auto& [name, edges] : m.boundaries) {
    auto& dst = out.boundaries[rename.at(name)];
    for (auto it = edges.rbegin(); it != edges.rend(); ++it) dst.push_back({it->b, it->a});
  }
  return out;
}

// Up to 121 slave-arc nodes (levels 0-2, the paper's meshes) the interior size is capped at
// 0.082 R; beyond, the cap shrinks with the arc spacing, so every refinement level halves
// the element size everywhere (about 4x the DOFs per level) instead of refining only the
// band along the arc, whose capped interior kept levels 4 and 5 0.1-0.3% above the
// converged force and energy (docs/meshes.md).
detail::HalfDiskSizing whole_mesh_sizing(int slave_arc_nodes) {
  constexpr int kCappedSegments = 120;  // level 2
  detail::HalfDiskSizing sizing;
  const int segments = slave_arc_nodes - 1;
  if (segments > kCappedSegments) sizing.max_size_factor *= static_cast<double>(kCappedSegments) / segments;
  return sizing;
}

}  // namespace

int hertz_arc_nodes_for_level(int level) {
  require(level >= 0, "Hertz mesh level must be >= 0 (got " + std::to_string(level) + ")");
  require(level <= kMaxMeshLevel,
          "Hertz mesh level must be <= " + std::to_string(kMaxMeshLevel) + " (got " + std::to_string(level) + ")");
  if (level == 0) return 51;
  if (level == 1) return 61;
  return 120 * (1 << (level - 2)) + 1;
}

Mesh generate_hertz(const HertzGeometry& g) {
  require(g.R1 > 0.0 && g.R2 > 0.0, "Hertz radii must be positive (R1 = " + number_text(g.R1) +
                                        ", R2 = " + number_text(g.R2) + ")");
  require(g.gap >= 0.0, "Hertz gap must be >= 0 (got " + number_text(g.gap) + ")");
  require(g.slave_arc_nodes >= 3,
          "Hertz slave_arc_nodes must be >= 3 (got " + std::to_string(g.slave_arc_nodes) + ")");
  detail::HalfDiskSpec upper;
  upper.center = {0.0, 0.5 * g.gap + g.R1};
  upper.radius = g.R1;
  upper.arc_nodes = g.slave_arc_nodes;
  upper.arc_below = true;
  upper.body = kSlaveBody;
  upper.arc_group = kSlaveBoundary;
  upper.flat_group = "top";
  upper.sizing = whole_mesh_sizing(g.slave_arc_nodes);
  const Mesh slave = detail::mesh_half_disk(upper);

  Mesh master;
  if (g.mirror && g.R1 == g.R2) {
    master = mirrored(slave, kMasterBody, {{kSlaveBoundary, kMasterBoundary}, {"top", "bottom"}});
  } else {
    detail::HalfDiskSpec lower;
    lower.center = {0.0, -0.5 * g.gap - g.R2};
    lower.radius = g.R2;
    lower.arc_nodes = std::max(3, static_cast<int>(std::lround(g.slave_arc_nodes * g.R2 / g.R1)));
    lower.arc_below = false;
    lower.body = kMasterBody;
    lower.arc_group = kMasterBoundary;
    lower.flat_group = "bottom";
    lower.sizing = whole_mesh_sizing(g.slave_arc_nodes);
    master = detail::mesh_half_disk(lower);
  }
  Mesh mesh = merge(slave, master);
  validate(mesh);
  return mesh;
}

Mesh generate_half_disk(double radius, int arc_nodes) {
  detail::HalfDiskSpec spec;
  spec.radius = radius;
  spec.arc_nodes = arc_nodes;
  Mesh mesh = detail::mesh_half_disk(spec);
  validate(mesh);
  return mesh;
}

}  // namespace contactrb::mesh
