// Gmsh-generated geometries (geometries.hpp): node counts, areas, orientation, groups.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <thread>

#include "contactrb/common/error.hpp"
#include "contactrb/mesh/geometries.hpp"

using namespace contactrb::mesh;

namespace {

double body_area(const Mesh& m, int body) {
  double a = 0.0;
  for (int t = 0; t < m.num_triangles(); ++t) {
    if (m.body[static_cast<std::size_t>(t)] == body) a += signed_area(m, t);
  }
  return a;
}

// Body of each node (-1 if none).
std::vector<int> node_bodies(const Mesh& m) {
  std::vector<int> owner(m.nodes.size(), -1);
  for (int t = 0; t < m.num_triangles(); ++t) {
    for (int v : m.triangles[static_cast<std::size_t>(t)]) owner[static_cast<std::size_t>(v)] = m.body[static_cast<std::size_t>(t)];
  }
  return owner;
}

void expect_group_on_body(const Mesh& m, const std::string& group, int body) {
  ASSERT_TRUE(m.has_boundary(group)) << group;
  EXPECT_FALSE(m.boundary(group).empty()) << group;
  const auto owner = node_bodies(m);
  for (int v : boundary_nodes(m, group)) EXPECT_EQ(owner[static_cast<std::size_t>(v)], body) << group;
}

const Eigen::Vector2d& node(const Mesh& m, int v) { return m.nodes[static_cast<std::size_t>(v)]; }

}  // namespace

TEST(HertzGeometry, LevelsArcNodes) {
  EXPECT_EQ(hertz_arc_nodes_for_level(0), 51);
  EXPECT_EQ(hertz_arc_nodes_for_level(1), 61);
  EXPECT_EQ(hertz_arc_nodes_for_level(2), 121);
  EXPECT_EQ(hertz_arc_nodes_for_level(3), 241);
  EXPECT_EQ(hertz_arc_nodes_for_level(4), 481);
  EXPECT_THROW(hertz_arc_nodes_for_level(-1), contactrb::Error);
}

TEST(HertzGeometry, NodeCountsNearPaper) {
  // Paper Fig. 2 and Tables 1-2: 675, 802 and 1682 nodes.
  const int paper[] = {675, 802, 1682};
  for (int level = 0; level < 3; ++level) {
    HertzGeometry g;
    g.slave_arc_nodes = hertz_arc_nodes_for_level(level);
    const Mesh m = generate_hertz(g);
    EXPECT_EQ(boundary_nodes(m, kSlaveBoundary).size(), static_cast<std::size_t>(g.slave_arc_nodes));
    EXPECT_EQ(ordered_chain(m, kSlaveBoundary).size(), static_cast<std::size_t>(g.slave_arc_nodes));
    EXPECT_NEAR(m.num_nodes(), paper[level], 0.15 * paper[level]) << "level " << level;
    std::cout << "[ info     ] Hertz level " << level << ": " << g.slave_arc_nodes << " slave-arc nodes, "
              << m.num_nodes() << " nodes, " << m.num_triangles() << " triangles\n";
  }
}

TEST(HertzGeometry, GroupsBodiesAndOrientation) {
  HertzGeometry g;
  const Mesh m = generate_hertz(g);
  ASSERT_NO_THROW(validate(m));  // includes: every triangle counter-clockwise
  for (int t = 0; t < m.num_triangles(); ++t) ASSERT_GT(signed_area(m, t), 0.0);
  EXPECT_EQ(m.num_bodies(), 2);
  EXPECT_EQ(m.boundaries.size(), 4u);
  expect_group_on_body(m, kSlaveBoundary, kSlaveBody);
  expect_group_on_body(m, "top", kSlaveBody);
  expect_group_on_body(m, kMasterBoundary, kMasterBody);
  expect_group_on_body(m, "bottom", kMasterBody);
  const double c1 = 0.5 * g.gap + g.R1;
  const double c2 = -0.5 * g.gap - g.R2;
  for (int v : boundary_nodes(m, kSlaveBoundary)) {
    EXPECT_NEAR((node(m, v) - Eigen::Vector2d(0, c1)).norm(), g.R1, 1e-12);
    EXPECT_LE(node(m, v).y(), c1 + 1e-12);
  }
  for (int v : boundary_nodes(m, "top")) EXPECT_NEAR(node(m, v).y(), c1, 1e-12);
  for (int v : boundary_nodes(m, "bottom")) EXPECT_NEAR(node(m, v).y(), c2, 1e-12);
  // Counter-clockwise around each body: the slave arc runs left to right, the master arc
  // right to left; "top" right to left, "bottom" left to right.
  auto first_x = [&](const std::string& group) { return node(m, ordered_chain(m, group).front()).x(); };
  EXPECT_DOUBLE_EQ(first_x(kSlaveBoundary), -g.R1);
  EXPECT_DOUBLE_EQ(first_x("top"), g.R1);
  EXPECT_DOUBLE_EQ(first_x(kMasterBoundary), g.R2);
  EXPECT_DOUBLE_EQ(first_x("bottom"), -g.R2);
  // Arc nodes equally spaced.
  const auto chain = ordered_chain(m, kSlaveBoundary);
  const double spacing = 2.0 * g.R1 * std::sin(0.5 * std::numbers::pi / (g.slave_arc_nodes - 1));
  for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
    EXPECT_NEAR((node(m, chain[k + 1]) - node(m, chain[k])).norm(), spacing, 1e-8);  // Gmsh: ~1e-10
  }
}

TEST(HertzGeometry, MirrorMeshesMatch) {
  HertzGeometry g;
  const Mesh m = generate_hertz(g);
  EXPECT_EQ(m.num_nodes() % 2, 0);
  const auto master = boundary_nodes(m, kMasterBoundary);
  ASSERT_EQ(master.size(), boundary_nodes(m, kSlaveBoundary).size());
  for (int s : boundary_nodes(m, kSlaveBoundary)) {
    const Eigen::Vector2d mirror(node(m, s).x(), -node(m, s).y());
    double best = 1e9;
    for (int q : master) best = std::min(best, (node(m, q) - mirror).norm());
    EXPECT_LT(best, 1e-12);
  }
  // Whole bodies are mirror images: same triangle count and area.
  EXPECT_NEAR(body_area(m, kSlaveBody), body_area(m, kMasterBody), 1e-12);
}

TEST(HertzGeometry, IndependentLowerBody) {
  HertzGeometry g;
  g.R2 = 0.9;
  const Mesh m = generate_hertz(g);
  EXPECT_EQ(boundary_nodes(m, kSlaveBoundary).size(), 51u);
  EXPECT_EQ(boundary_nodes(m, kMasterBoundary).size(), static_cast<std::size_t>(std::lround(51 * 0.9)));
  for (int v : boundary_nodes(m, kMasterBoundary)) {
    EXPECT_NEAR((node(m, v) - Eigen::Vector2d(0, -0.5 * g.gap - g.R2)).norm(), g.R2, 1e-12);
  }
  HertzGeometry h;
  h.mirror = false;
  const Mesh n = generate_hertz(h);
  EXPECT_EQ(boundary_nodes(n, kMasterBoundary).size(), 51u);
  ASSERT_NO_THROW(validate(n));
}

TEST(HertzGeometry, Deterministic) {
  HertzGeometry g;
  g.R2 = 1.05;
  const Mesh a = generate_hertz(g);
  const Mesh b = generate_hertz(g);
  ASSERT_EQ(a.num_nodes(), b.num_nodes());
  ASSERT_EQ(a.triangles, b.triangles);
  for (int v = 0; v < a.num_nodes(); ++v) EXPECT_EQ(node(a, v), node(b, v));
}

TEST(HertzGeometry, ConcurrentCallsAreSerialized) {
  // Gmsh is a process-wide singleton; generators lock it internally.
  Mesh a, b;
  std::thread t1([&] { a = generate_hertz({}); });
  std::thread t2([&] { b = generate_ring_block({}); });
  t1.join();
  t2.join();
  EXPECT_EQ(a.triangles, generate_hertz({}).triangles);
  EXPECT_EQ(b.num_nodes(), generate_ring_block({}).num_nodes());
}

TEST(HertzGeometry, InvalidArguments) {
  HertzGeometry g;
  g.slave_arc_nodes = 2;
  EXPECT_THROW(generate_hertz(g), contactrb::Error);
  g = HertzGeometry{};
  g.R1 = -1.0;
  EXPECT_THROW(generate_hertz(g), contactrb::Error);
}

TEST(HalfDisk, AreaConvergesQuadratically) {
  // Area error of the inscribed polygon: (R^2 / 2) (pi - n sin(pi / n)) ~ pi^3 R^2 / (12 n^2)
  // for n arc segments, i.e. O(h^2).
  const double R = 1.0;
  double previous_error = 0.0;
  double previous_h = 0.0;
  for (int level = 0; level < 4; ++level) {
    const int n = hertz_arc_nodes_for_level(level);
    const Mesh m = generate_half_disk(R, n);
    ASSERT_NO_THROW(validate(m));
    EXPECT_EQ(boundary_nodes(m, "arc").size(), static_cast<std::size_t>(n));
    expect_group_on_body(m, "flat", kSlaveBody);
    const double h = std::numbers::pi * R / (n - 1);
    const double error = 0.5 * std::numbers::pi * R * R - body_area(m, kSlaveBody);
    EXPECT_GT(error, 0.0);
    EXPECT_LT(error, 0.5 * h * h) << "level " << level;
    if (level > 0) {
      const double rate = std::log(previous_error / error) / std::log(previous_h / h);
      EXPECT_NEAR(rate, 2.0, 0.05) << "level " << level;
    }
    previous_error = error;
    previous_h = h;
  }
}

TEST(RingBlockGeometry, DefaultMesh) {
  const RingBlockGeometry g;
  const Mesh m = generate_ring_block(g);
  ASSERT_NO_THROW(validate(m));
  std::cout << "[ info     ] ring-block: " << m.num_nodes() << " nodes, " << m.num_triangles() << " triangles\n";
  EXPECT_NEAR(m.num_nodes(), 1590, 0.15 * 1590);  // paper Fig. 17
  EXPECT_EQ(boundary_nodes(m, kSlaveBoundary).size(), 121u);
  EXPECT_EQ(boundary_nodes(m, kMasterBoundary).size(), 91u);
  EXPECT_EQ(m.boundaries.size(), 4u);
  expect_group_on_body(m, kSlaveBoundary, kSlaveBody);
  expect_group_on_body(m, "ring_ends", kSlaveBody);
  expect_group_on_body(m, kMasterBoundary, kMasterBody);
  expect_group_on_body(m, "block_bottom", kMasterBody);
  EXPECT_EQ(m.boundary("ring_ends").size() > 2u, true);

  // Areas: the polygonal half-annulus is inscribed (outer arc exact up to O(h^2)).
  const double R = g.R_out, r = g.R_out - g.thickness;
  EXPECT_NEAR(body_area(m, kSlaveBody), 0.5 * std::numbers::pi * (R * R - r * r), 5e-3);
  EXPECT_NEAR(body_area(m, kMasterBody), g.block_width * g.block_height, 1e-12);
  for (int v : boundary_nodes(m, kMasterBoundary)) EXPECT_NEAR(node(m, v).y(), 0.0, 1e-14);
  for (int v : boundary_nodes(m, kSlaveBoundary)) {
    EXPECT_NEAR((node(m, v) - Eigen::Vector2d(0, g.gap + R)).norm(), R, 1e-12);
  }
  // "master" runs right to left (counter-clockwise around the block).
  EXPECT_DOUBLE_EQ(node(m, ordered_chain(m, kMasterBoundary).front()).x(), 0.5 * g.block_width);
  EXPECT_DOUBLE_EQ(node(m, ordered_chain(m, kSlaveBoundary).front()).x(), -R);
}

TEST(RingBlockGeometry, NonMatchingContactMeshes) {
  const Mesh m = generate_ring_block({});
  const auto master = ordered_chain(m, kMasterBoundary);
  double master_spacing = 1e9;
  for (std::size_t k = 0; k + 1 < master.size(); ++k) {
    master_spacing = std::min(master_spacing, (node(m, master[k + 1]) - node(m, master[k])).norm());
  }
  double closest = 1e9;
  for (int s : boundary_nodes(m, kSlaveBoundary)) {
    for (int q : master) closest = std::min(closest, std::abs(node(m, s).x() - node(m, q).x()));
  }
  std::cout << "[ info     ] ring-block: closest slave/master abscissas " << closest
            << ", finest master spacing " << master_spacing << "\n";
  EXPECT_GT(closest, 1e-3 * master_spacing);
}

TEST(RingBlockGeometry, InvalidArguments) {
  RingBlockGeometry g;
  g.thickness = 1.5;
  EXPECT_THROW(generate_ring_block(g), contactrb::Error);
  g = RingBlockGeometry{};
  g.block_width = 1.0;
  EXPECT_THROW(generate_ring_block(g), contactrb::Error);
}
