// The hertz-3d quarter model (geometries.hpp, generate_hertz_3d): volumes, groups, orientation,
// determinism and refinement by level.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "contactrb/common/error.hpp"
#include "contactrb/mesh/geometries.hpp"

using namespace contactrb::mesh;

namespace {

Mesh3 hertz3d(int level) {
  Hertz3dGeometry g;
  g.fine_size = hertz_3d_fine_size_for_level(level);
  return generate_hertz_3d(g);
}

const Mesh3& level0() {
  static const Mesh3 m = hertz3d(0);
  return m;
}

double body_volume(const Mesh3& m, int body) {
  double v = 0.0;
  for (int c = 0; c < m.num_cells(); ++c) {
    if (m.body[static_cast<std::size_t>(c)] == body) v += signed_volume(m, c);
  }
  return v;
}

std::vector<int> node_bodies(const Mesh3& m) {
  std::vector<int> owner(m.nodes.size(), -1);
  for (int c = 0; c < m.num_cells(); ++c) {
    for (int v : m.tetrahedra[static_cast<std::size_t>(c)]) owner[static_cast<std::size_t>(v)] = m.body[static_cast<std::size_t>(c)];
  }
  return owner;
}

const Eigen::Vector3d& node(const Mesh3& m, int v) { return m.nodes[static_cast<std::size_t>(v)]; }

// Centroid of a boundary triangle.
Eigen::Vector3d centroid(const Mesh3& m, const Face& f) { return (node(m, f.a) + node(m, f.b) + node(m, f.c)) / 3.0; }

// Slave nodes on the symmetry line y = 0 with 0 <= x <= radius: the nodes across a contact
// radius `radius` (the quarter model's contact zone is a quarter disk centred at the origin).
int slave_nodes_across(const Mesh3& m, double radius) {
  int n = 0;
  for (int v : boundary_nodes(m, kSlaveBoundary)) {
    if (node(m, v).y() == 0.0 && node(m, v).x() <= radius) ++n;
  }
  return n;
}

}  // namespace

TEST(Hertz3dGeometry, BodyVolumesMatchTheQuarterHemisphereAndTheBlock) {
  const Mesh3& m = level0();
  const Hertz3dGeometry g;
  // The block is a box: its tetrahedra fill it exactly.
  EXPECT_NEAR(body_volume(m, kMasterBody), g.block_width * g.block_width * g.block_height, 1e-12);
  // The hemisphere's tetrahedra fill a polyhedron inscribed in the ball: smaller, by a relative
  // deficit of order (3/8) (h / R)^2 for chords h <= coarse_size (the sagitta h^2 / (8 R) over
  // the surface, times 3 / R for the volume).
  const double exact = std::numbers::pi * std::pow(g.R, 3) / 6.0;  // a quarter of the half ball
  const double v = body_volume(m, kSlaveBody);
  EXPECT_LT(v, exact);
  EXPECT_GT(v, exact * (1.0 - 0.375 * std::pow(g.coarse_size / g.R, 2)));
}

TEST(Hertz3dGeometry, GroupsAreOnTheirBodyAndPlane) {
  const Mesh3& m = level0();
  const auto owner = node_bodies(m);
  const std::map<std::string, int> body_of{{"slave", 0},  {"sphere_free", 0}, {"top", 0},
                                           {"master", 1}, {"bottom", 1},      {"master_sides", 1}};
  for (const auto& [group, body] : body_of) {
    ASSERT_TRUE(m.has_boundary(group)) << group;
    EXPECT_FALSE(m.boundary(group).empty()) << group;
    for (int v : boundary_nodes(m, group)) EXPECT_EQ(owner[static_cast<std::size_t>(v)], body) << group;
  }
  EXPECT_EQ(m.boundaries.size(), body_of.size() + 2);  // and the two symmetry groups
  for (const auto& [group, axis] : {std::pair{"symmetry_x", 0}, std::pair{"symmetry_y", 1}}) {
    int on_body[2] = {0, 0};
    for (int v : boundary_nodes(m, group)) {
      EXPECT_EQ(node(m, v)(axis), 0.0) << group;
      ++on_body[owner[static_cast<std::size_t>(v)]];
    }
    EXPECT_GT(on_body[0], 0) << group;
    EXPECT_GT(on_body[1], 0) << group;
  }
  // The slave cap: the curved surface below z = cap_height R, on the sphere.
  const Hertz3dGeometry g;
  for (int v : boundary_nodes(m, kSlaveBoundary)) {
    EXPECT_LE(node(m, v).z(), g.cap_height * g.R + 1e-12);
    EXPECT_NEAR((node(m, v) - Eigen::Vector3d(0.0, 0.0, g.R)).norm(), g.R, 1e-9);
  }
  for (int v : boundary_nodes(m, kMasterBoundary)) EXPECT_EQ(node(m, v).z(), 0.0);
}

TEST(Hertz3dGeometry, BoundaryFacesPointOutward) {
  const Mesh3& m = level0();
  validate(m);  // every group face is a face of one tetrahedron, oriented outward of it
  const Eigen::Vector3d center(0.0, 0.0, Hertz3dGeometry{}.R);
  const std::map<std::string, Eigen::Vector3d> plane_normal{
      {"top", {0, 0, 1}}, {"bottom", {0, 0, -1}}, {"master", {0, 0, 1}}, {"symmetry_x", {-1, 0, 0}}, {"symmetry_y", {0, -1, 0}}};
  for (const auto& [group, n] : plane_normal) {
    for (const Face& f : m.boundary(group)) {
      const Eigen::Vector3d a = facet_area_normal(m, f);
      EXPECT_NEAR(a.normalized().dot(n), 1.0, 1e-9) << group;
    }
  }
  for (const char* group : {"slave", "sphere_free"}) {
    for (const Face& f : m.boundary(group)) {
      EXPECT_GT(facet_area_normal(m, f).normalized().dot((centroid(m, f) - center).normalized()), 0.9) << group;
    }
  }
  // A closed surface has a zero total area vector: the block's faces.
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  const auto owner = node_bodies(m);
  for (const auto& [group, faces] : m.boundaries) {
    for (const Face& f : faces) {
      if (owner[static_cast<std::size_t>(f.a)] == kMasterBody) total += facet_area_normal(m, f);
    }
  }
  EXPECT_LT(total.norm(), 1e-12);
}

TEST(Hertz3dGeometry, SameMeshBitForBitOnEveryRun) {
  const Mesh3& a = level0();
  const Mesh3 b = hertz3d(0);
  ASSERT_EQ(a.num_nodes(), b.num_nodes());
  ASSERT_EQ(a.tetrahedra, b.tetrahedra);
  EXPECT_EQ(a.body, b.body);
  EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(Eigen::Vector3d)), 0);
  for (const auto& [group, faces] : a.boundaries) {
    ASSERT_TRUE(b.has_boundary(group));
    ASSERT_EQ(faces.size(), b.boundary(group).size()) << group;
    for (std::size_t k = 0; k < faces.size(); ++k) EXPECT_EQ(faces[k].vertices(), b.boundary(group)[k].vertices());
  }
}

TEST(Hertz3dGeometry, LevelsRefineTheContactZone) {
  EXPECT_EQ(hertz_3d_fine_size_for_level(0), 0.04);
  EXPECT_EQ(hertz_3d_fine_size_for_level(2), 0.01);
  EXPECT_THROW(hertz_3d_fine_size_for_level(-1), contactrb::Error);
  EXPECT_THROW(hertz_3d_fine_size_for_level(kMaxHertz3dLevel + 1), contactrb::Error);
  const Mesh3 l1 = hertz3d(1);
  const Mesh3 l2 = hertz3d(2);
  // Halving h in the fine zone multiplies its nodes by about 8 (and the coarse part stays).
  EXPECT_GT(l1.num_nodes(), 2 * level0().num_nodes());
  EXPECT_GT(l2.num_nodes(), 3 * l1.num_nodes());
  // Across the contact radius a = 0.1 (about the smallest of the case's domain, docs/cases.md):
  // the node count doubles with the level, at least 10 at level 2 (about 9000 nodes).
  const int n0 = slave_nodes_across(level0(), 0.1);
  const int n2 = slave_nodes_across(l2, 0.1);
  EXPECT_GE(n2, 10);
  EXPECT_GE(n2, 3 * n0);
  EXPECT_LT(l2.num_nodes(), 15000);
}

TEST(Hertz3dGeometry, InvalidGeometryIsRefused) {
  Hertz3dGeometry g;
  g.R = -1.0;
  EXPECT_THROW(generate_hertz_3d(g), contactrb::Error);
  g = Hertz3dGeometry{};
  g.fine_size = 1.0;  // above coarse_size
  EXPECT_THROW(generate_hertz_3d(g), contactrb::Error);
}
