// .msh import/export (msh_io.hpp): round trips and one test per bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "contactrb/mesh/msh_io.hpp"

using namespace contactrb::mesh;

namespace {

std::string fixture(const std::string& name) { return std::string(CONTACTRB_SOURCE_DIR) + "/tests/data/msh/" + name; }

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("contactrb_test_mesh_" + name)).string();
}

// The message of the contactrb::Error thrown by read_msh (fails the test if none is).
std::string read_error(const std::string& path, const MshGroups& groups = {}) {
  try {
    read_msh(path, groups);
  } catch (const contactrb::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "read_msh('" << path << "') did not throw";
  return {};
}

void expect_same(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.num_nodes(), b.num_nodes());
  for (int v = 0; v < a.num_nodes(); ++v) {
    EXPECT_EQ(a.nodes[static_cast<std::size_t>(v)], b.nodes[static_cast<std::size_t>(v)]) << "node " << v;
  }
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.body, b.body);
  ASSERT_EQ(a.boundaries.size(), b.boundaries.size());
  for (const auto& [name, edges] : a.boundaries) {
    ASSERT_TRUE(b.has_boundary(name)) << name;
    const auto& other = b.boundary(name);
    ASSERT_EQ(edges.size(), other.size()) << name;
    for (std::size_t k = 0; k < edges.size(); ++k) {
      EXPECT_EQ(edges[k].a, other[k].a) << name;
      EXPECT_EQ(edges[k].b, other[k].b) << name;
    }
  }
}

}  // namespace

TEST(MshIo, RoundTripHertz) {
  const Mesh m = generate_hertz({});
  const std::string path = temp_path("hertz.msh");
  write_msh(m, path);
  MshGroups groups;
  groups.required_boundaries = {"slave", "master", "top", "bottom"};
  expect_same(m, read_msh(path, groups));
  std::filesystem::remove(path);
}

TEST(MshIo, RoundTripRingBlockAndHalfDisk) {
  const Mesh ring = generate_ring_block({});
  const std::string path = temp_path("ring_block.msh");
  write_msh(ring, path);
  expect_same(ring, read_msh(path));
  const Mesh disk = generate_half_disk(2.0, 21);
  write_msh(disk, path);
  MshGroups one_body;
  one_body.body_groups = {"body1"};
  one_body.required_boundaries = {"arc", "flat"};
  expect_same(disk, read_msh(path, one_body));
  std::filesystem::remove(path);
}

TEST(MshIo, ReadsHandWrittenFile) {
  const Mesh m = read_msh(fixture("two_squares.msh"));
  EXPECT_EQ(m.num_nodes(), 8);  // the geometry point node 9 is dropped
  EXPECT_EQ(m.num_triangles(), 4);
  EXPECT_EQ(m.num_bodies(), 2);
  ASSERT_EQ(m.boundary("master").size(), 1u);
  // Written (8, 7) in the file, reoriented with the master body on the left: (1, 0) -> (0, 0).
  const Edge e = m.boundary("master").front();
  EXPECT_EQ(m.nodes[static_cast<std::size_t>(e.a)], Eigen::Vector2d(1, 0));
  EXPECT_EQ(m.nodes[static_cast<std::size_t>(e.b)], Eigen::Vector2d(0, 0));
}

TEST(MshIo, ReorientsConsistentlyClockwiseBody) {
  const Mesh m = read_msh(fixture("clockwise_body.msh"));
  for (int t = 0; t < m.num_triangles(); ++t) EXPECT_GT(signed_area(m, t), 0.0);
}

TEST(MshIo, MissingFile) {
  const std::string msg = read_error(fixture("no_such_file.msh"));
  EXPECT_NE(msg.find("no_such_file.msh"), std::string::npos) << msg;
  EXPECT_NE(msg.find("does not exist"), std::string::npos) << msg;
}

TEST(MshIo, NotAMesh) {
  const std::string msg = read_error(fixture("not_a_mesh.msh"));
  EXPECT_NE(msg.find("not_a_mesh.msh"), std::string::npos) << msg;
  EXPECT_NE(msg.find("is not a Gmsh mesh"), std::string::npos) << msg;
}

TEST(MshIo, Version2) {
  const std::string msg = read_error(fixture("version2.msh"));
  EXPECT_NE(msg.find("version2.msh"), std::string::npos) << msg;
  EXPECT_NE(msg.find("legacy Gmsh format version 2.2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("4.1"), std::string::npos) << msg;
}

TEST(MshIo, Binary) {
  const std::string msg = read_error(fixture("binary.msh"));
  EXPECT_NE(msg.find("binary.msh"), std::string::npos) << msg;
  EXPECT_NE(msg.find("binary Gmsh file"), std::string::npos) << msg;
  EXPECT_NE(msg.find("ASCII"), std::string::npos) << msg;
}

TEST(MshIo, MissingPhysicalGroup) {
  const std::string msg = read_error(fixture("missing_group.msh"));
  EXPECT_NE(msg.find("missing_group.msh"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no 1D physical group 'master'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("groups present: 'slave' (1D), 'body1' (2D), 'body2' (2D)"), std::string::npos) << msg;
  MshGroups groups;
  groups.body_groups = {"upper", "lower"};
  const std::string body_msg = read_error(fixture("two_squares.msh"), groups);
  EXPECT_NE(body_msg.find("no 2D physical group 'upper' (the slave body)"), std::string::npos) << body_msg;
}

TEST(MshIo, InvertedTriangle) {
  const std::string msg = read_error(fixture("inverted_triangle.msh"));
  EXPECT_NE(msg.find("inverted_triangle.msh"), std::string::npos) << msg;
  EXPECT_NE(msg.find("body 'body1' has inverted triangles: 1 clockwise and 1 counter-clockwise"),
            std::string::npos) << msg;
}

TEST(MshIo, ZeroAreaTriangle) {
  const std::string msg = read_error(fixture("zero_area.msh"));
  EXPECT_NE(msg.find("zero_area.msh"), std::string::npos) << msg;
  EXPECT_NE(msg.find("triangle 4 has zero area"), std::string::npos) << msg;
}

TEST(MshIo, UnreferencedNode) {
  const std::string msg = read_error(fixture("unreferenced_node.msh"));
  EXPECT_NE(msg.find("unreferenced_node.msh"), std::string::npos) << msg;
  EXPECT_NE(msg.find("node 10"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not referenced by any triangle"), std::string::npos) << msg;
}

TEST(MshIo, TruncatedFile) {
  const std::string path = temp_path("truncated.msh");
  {
    std::ofstream out(path);
    out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n";
  }
  const std::string msg = read_error(path);
  EXPECT_NE(msg.find("truncated.msh"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 9"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unexpected end of file while reading node tag"), std::string::npos) << msg;
  std::filesystem::remove(path);
}
