#pragma once
// Small two-body meshes for the contact tests, built from mesh::rectangle.
#include <cmath>
#include <numbers>
#include <string>

#include "contactrb/mesh/structured.hpp"

namespace contact_test {

using contactrb::mesh::Mesh;

// Gives every group of `m` except `keep` the prefix `prefix` (merge needs distinct names).
inline void prefix_groups(Mesh& m, const std::string& prefix, const std::string& keep) {
  for (const char* g : {"bottom", "right", "top", "left"}) {
    if (g != keep && m.has_boundary(g)) contactrb::mesh::rename_boundary(m, g, prefix + g);
  }
}

// Joins a slave body (body 0) whose "bottom" edge becomes "slave" with a master body
// (body 1) whose "top" edge becomes "master".
inline Mesh join(Mesh slave_body, Mesh master_body) {
  prefix_groups(slave_body, "s_", "bottom");
  prefix_groups(master_body, "m_", "top");
  contactrb::mesh::rename_boundary(slave_body, "bottom", contactrb::mesh::kSlaveBoundary);
  contactrb::mesh::rename_boundary(master_body, "top", contactrb::mesh::kMasterBoundary);
  return contactrb::mesh::merge(slave_body, master_body);
}

// Slave block [sx0, sx1] x [sy0, sy0 + 1] (nxs cells along x) over master block
// [mx0, mx1] x [-1, 0] (nxm cells along x): flat interface at y = 0, gap sy0.
inline Mesh flat_blocks(double sx0, double sx1, double sy0, int nxs, double mx0, double mx1, int nxm) {
  return join(contactrb::mesh::rectangle(sx0, sy0, sx1, sy0 + 1.0, nxs, 2, contactrb::mesh::kSlaveBody),
              contactrb::mesh::rectangle(mx0, -1.0, mx1, 0.0, nxm, 2, contactrb::mesh::kMasterBody));
}

// Half annulus r in [r_in, r_out], theta in [0, pi] (body 1), nx cells along the arc: the
// structured rectangle mapped by (x, y) -> r (cos t, sin t), r = r_in + (r_out - r_in) y,
// t = pi (1 - x), which keeps triangles counter-clockwise. Its "top" is the outer arc,
// traversed from theta = 0 to theta = pi.
inline Mesh half_annulus(double r_in, double r_out, int nx, int ny) {
  Mesh m = contactrb::mesh::rectangle(0.0, 0.0, 1.0, 1.0, nx, ny, contactrb::mesh::kMasterBody);
  for (auto& p : m.nodes) {
    const double r = r_in + (r_out - r_in) * p.y();
    const double t = std::numbers::pi * (1.0 - p.x());
    p = Eigen::Vector2d(r * std::cos(t), r * std::sin(t));
  }
  return m;
}

}  // namespace contact_test
