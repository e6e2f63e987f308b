#include <gtest/gtest.h>

#include "contactrb/common/error.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb::mesh;

TEST(Structured, RectangleAreaAndOrientation) {
  Mesh m = rectangle(0.0, 0.0, 2.0, 1.0, 4, 3);
  ASSERT_NO_THROW(validate(m));
  double area = 0.0;
  for (int t = 0; t < m.num_triangles(); ++t) area += signed_area(m, t);
  EXPECT_NEAR(area, 2.0, 1e-14);
  EXPECT_EQ(m.num_nodes(), 20);
  EXPECT_EQ(ordered_chain(m, "top").size(), 5u);
  // "top" runs right to left (counter-clockwise around the body).
  EXPECT_DOUBLE_EQ(m.nodes[static_cast<std::size_t>(ordered_chain(m, "top").front())].x(), 2.0);
}

TEST(Structured, MergeAndValidateErrors) {
  Mesh a = rectangle(0, 0, 1, 1, 2, 2, kSlaveBody);
  Mesh b = rectangle(0, -1, 1, 0, 3, 3, kMasterBody);
  EXPECT_THROW(merge(a, b), contactrb::Error);  // same group names
  for (const char* g : {"bottom", "right", "top", "left"}) rename_boundary(b, g, std::string("b_") + g);
  Mesh m = merge(a, b);
  ASSERT_NO_THROW(validate(m));
  EXPECT_EQ(m.num_bodies(), 2);
  std::swap(m.triangles[0][1], m.triangles[0][2]);
  EXPECT_THROW(validate(m), contactrb::Error);
}

TEST(Structured, PerturbKeepsValidity) {
  Mesh m = rectangle(0, 0, 1, 1, 8, 8);
  perturb_interior(m, 0.25, 7);
  ASSERT_NO_THROW(validate(m));
  double area = 0.0;
  for (int t = 0; t < m.num_triangles(); ++t) area += signed_area(m, t);
  EXPECT_NEAR(area, 1.0, 1e-13);
}

// mirror: the unit box joined with its image about x = 0 is the box [-1, 1] x [0, 1]^2, a valid
// mesh (positive cells, outward facets), the nodes on the plane shared, the plane's group gone.
TEST(Structured, MirrorJoinsTheImageAboutAPlane) {
  const Mesh3 box3 = box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 2, 2, 2);
  const Mesh3 m = mirror(box3, 0, "left");
  ASSERT_NO_THROW(validate(m));
  double volume = 0.0;
  for (int c = 0; c < m.num_cells(); ++c) {
    EXPECT_GT(signed_volume(m, c), 0.0);
    volume += signed_volume(m, c);
  }
  EXPECT_NEAR(volume, 2.0, 1e-14);
  EXPECT_EQ(m.num_nodes(), 27 + 18);
  EXPECT_FALSE(m.has_boundary("left"));
  EXPECT_EQ(m.boundary("right").size(), 2 * box3.boundary("right").size());
  EXPECT_EQ(m.boundary("front").size(), 2 * box3.boundary("front").size());
  EXPECT_THROW(mirror(box3, 0, "missing"), contactrb::Error);
  EXPECT_THROW(mirror(box3, 0, "right"), contactrb::Error);  // not on the plane x = 0
}
