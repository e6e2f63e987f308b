// Tetrahedral meshes (SimplexMesh<3>): the structured generators, validate(), map_body() and the
// orientation conventions of mesh.hpp, against volumes, areas and normals computed by hand.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <set>

#include "contactrb/common/error.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb::mesh;

namespace {

double total_volume(const Mesh3& m, int body = -1) {
  double v = 0.0;
  for (int t = 0; t < m.num_cells(); ++t) {
    if (body < 0 || m.body[static_cast<std::size_t>(t)] == body) v += signed_volume(m, t);
  }
  return v;
}

// Sum of the area normals of a group: its area times its (constant) outward normal when flat.
Eigen::Vector3d area_normal(const Mesh3& m, const std::string& group) {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (const Face& f : m.boundary(group)) s += facet_area_normal(m, f);
  return s;
}

std::string validate_error(const Mesh3& m) {
  try {
    validate(m);
  } catch (const contactrb::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "validate() did not throw";
  return {};
}

}  // namespace

TEST(Mesh3, BoxVolumesFacesAndNormals) {
  const Mesh3 m = box({0.0, 0.0, 0.0}, {2.0, 1.0, 0.5}, 4, 3, 2);
  ASSERT_NO_THROW(validate(m));
  EXPECT_EQ(m.num_nodes(), 5 * 4 * 3);
  EXPECT_EQ(m.num_tetrahedra(), 6 * 4 * 3 * 2);
  EXPECT_EQ(m.num_dofs(), 3 * m.num_nodes());
  for (int t = 0; t < m.num_cells(); ++t) ASSERT_GT(signed_volume(m, t), 0.0) << t;
  EXPECT_NEAR(total_volume(m), 1.0, 1e-14);
  // Each face: two triangles per cell face, area times outward unit normal.
  EXPECT_EQ(m.boundary("bottom").size(), 2u * 4 * 3);
  EXPECT_LT((area_normal(m, "bottom") - Eigen::Vector3d(0, 0, -2.0)).norm(), 1e-14);
  EXPECT_LT((area_normal(m, "top") - Eigen::Vector3d(0, 0, 2.0)).norm(), 1e-14);
  EXPECT_LT((area_normal(m, "left") - Eigen::Vector3d(-0.5, 0, 0)).norm(), 1e-14);
  EXPECT_LT((area_normal(m, "right") - Eigen::Vector3d(0.5, 0, 0)).norm(), 1e-14);
  EXPECT_LT((area_normal(m, "front") - Eigen::Vector3d(0, -1.0, 0)).norm(), 1e-14);
  EXPECT_LT((area_normal(m, "back") - Eigen::Vector3d(0, 1.0, 0)).norm(), 1e-14);
  // Every triangle of "top" is outward, not only their sum.
  for (const Face& f : m.boundary("top")) EXPECT_GT(facet_area_normal(m, f).z(), 0.0);
  EXPECT_EQ(boundary_nodes(m, "top").size(), 5u * 4);
}

TEST(Mesh3, StackedBlocksAreNonMatchingAndNamed) {
  const Mesh3 m = stacked_blocks(0, 0.1);
  ASSERT_NO_THROW(validate(m));
  EXPECT_EQ(m.num_bodies(), 2);
  EXPECT_EQ(m.num_dofs(), 3 * (5 * 5 * 3 + 8 * 8 * 5));  // master 4 x 4 x 2 cubes, slave 7 x 7 x 4
  for (const char* g : {"slave", "master", "top", "bottom", "slave_sides", "master_sides"}) {
    EXPECT_TRUE(m.has_boundary(g)) << g;
  }
  EXPECT_NEAR(total_volume(m, kSlaveBody), 0.5, 1e-14);
  EXPECT_NEAR(total_volume(m, kMasterBody), 0.5, 1e-14);
  EXPECT_LT((area_normal(m, "slave") - Eigen::Vector3d(0, 0, -1)).norm(), 1e-14);   // slave faces down
  EXPECT_LT((area_normal(m, "master") - Eigen::Vector3d(0, 0, 1)).norm(), 1e-14);   // master faces up
  // The lateral groups are closed bands: their area normals cancel; each has area 4 h = 2.
  EXPECT_LT(area_normal(m, "slave_sides").norm(), 1e-13);
  double side_area = 0.0;
  for (const Face& f : m.boundary("master_sides")) side_area += facet_area_normal(m, f).norm();
  EXPECT_NEAR(side_area, 2.0, 1e-13);
  // Non-matching: inside the contact plane no slave node lies on a master node.
  std::set<std::pair<double, double>> master_xy;
  for (int v : boundary_nodes(m, "master")) {
    master_xy.insert({m.nodes[static_cast<std::size_t>(v)].x(), m.nodes[static_cast<std::size_t>(v)].y()});
  }
  int shared = 0;
  for (int v : boundary_nodes(m, "slave")) {
    const auto& x = m.nodes[static_cast<std::size_t>(v)];
    EXPECT_DOUBLE_EQ(x.z(), 0.1);
    const bool on_edge = x.x() == 0.0 || x.x() == 1.0 || x.y() == 0.0 || x.y() == 1.0;
    if (!on_edge && master_xy.count({x.x(), x.y()}) != 0) ++shared;
  }
  EXPECT_EQ(shared, 0);
  EXPECT_NE(boundary_nodes(m, "slave").size(), boundary_nodes(m, "master").size());
  EXPECT_THROW(stacked_blocks(5), contactrb::Error);
  EXPECT_THROW(stacked_blocks(-1), contactrb::Error);
}

TEST(Mesh3, MapBodyMovesOneBodyRigidly) {
  Mesh3 m = stacked_blocks(0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d b(0.5, -1.0, 2.0);
  const Mesh3 before = m;
  map_body(m, kMasterBody, R, b);
  ASSERT_NO_THROW(validate(m));  // a rotation keeps the orientation
  EXPECT_NEAR(total_volume(m, kMasterBody), 0.5, 1e-14);
  EXPECT_LT((area_normal(m, "master") - R * Eigen::Vector3d(0, 0, 1)).norm(), 1e-13);
  for (int v : boundary_nodes(m, "slave")) {
    EXPECT_EQ(m.nodes[static_cast<std::size_t>(v)], before.nodes[static_cast<std::size_t>(v)]);
  }
  // A reflection inverts the tetrahedra: validate() says so.
  map_body(m, kSlaveBody, Eigen::Vector3d(1, 1, -1).asDiagonal(), Eigen::Vector3d::Zero());
  EXPECT_NE(validate_error(m).find("is inverted (negative volume)"), std::string::npos);
}

TEST(Mesh3, ValidateNamesTheViolation) {
  const Mesh3 good = box({0, 0, 0}, {1, 1, 1}, 2, 2, 2);
  Mesh3 m = good;
  std::swap(m.tetrahedra[3][1], m.tetrahedra[3][2]);
  EXPECT_NE(validate_error(m).find("tetrahedron 3 is inverted (negative volume)"), std::string::npos);
  m = good;
  m.tetrahedra[0][3] = m.tetrahedra[0][0];
  EXPECT_NE(validate_error(m).find("tetrahedron 0 has zero volume"), std::string::npos);
  m = good;
  Face& f = m.boundaries["top"].front();
  std::swap(f.b, f.c);  // inward
  EXPECT_NE(validate_error(m).find("is not an outward-oriented face of a tetrahedron"), std::string::npos);
  m = good;
  // The same face written from another vertex is the same oriented face.
  Face& g = m.boundaries["top"].front();
  g = Face{g.b, g.c, g.a};
  EXPECT_NO_THROW(validate(m));
  m = good;
  m.body[1] = 2;
  EXPECT_NE(validate_error(m).find("tetrahedron 1 has body id 2"), std::string::npos);
}

TEST(Mesh3, PerturbKeepsVolumeAndBoundary) {
  Mesh3 m = box({0, 0, 0}, {1, 1, 1}, 4, 4, 4);
  const Mesh3 before = m;
  perturb_interior(m, 0.15, 5);
  ASSERT_NO_THROW(validate(m));
  EXPECT_NEAR(total_volume(m), 1.0, 1e-13);
  int moved = 0;
  for (int v = 0; v < m.num_nodes(); ++v) moved += m.nodes[static_cast<std::size_t>(v)] != before.nodes[static_cast<std::size_t>(v)];
  EXPECT_EQ(moved, 3 * 3 * 3);  // the interior nodes, and only them
}
