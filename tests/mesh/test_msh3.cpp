// .msh 4.1 import of 3D meshes (read_msh3): a small file written here by hand and a file written
// by Gmsh, their groups, orientations, volumes and areas checked against values computed by hand,
// and one test per bad file.
#include <gtest/gtest.h>

#include <gmsh.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/mesh/msh_io.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb::mesh;

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("contactrb_test_msh3_" + name)).string();
}

// Two unit tetrahedra: body1 (slave) above z = 1, body2 (master) below z = 0, groups "slave"
// (the face of body1 at z = 1) and "master" (the face of body2 at z = 0). As written, the slave
// face is inward (reoriented on reading) and body2's tetrahedron has negative volume (the whole
// body reoriented). `elements` replaces the $Elements section when given.
std::string two_tetrahedra(const std::string& elements = "") {
  std::string s =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      "$PhysicalNames\n4\n2 1 \"slave\"\n2 2 \"master\"\n3 3 \"body1\"\n3 4 \"body2\"\n$EndPhysicalNames\n"
      "$Entities\n0 0 2 2\n"
      "1 0 0 1 1 1 1 1 1 0\n"
      "2 0 0 0 1 1 0 1 2 0\n"
      "1 0 0 1 1 1 2 1 3 0\n"
      "2 0 0 -1 1 1 0 1 4 0\n"
      "$EndEntities\n"
      "$Nodes\n2 8 1 8\n"
      "3 1 0 4\n1\n2\n3\n4\n0 0 1\n1 0 1\n0 1 1\n0 0 2\n"
      "3 2 0 4\n5\n6\n7\n8\n0 0 0\n1 0 0\n0 1 0\n0 0 -1\n"
      "$EndNodes\n";
  s += elements.empty() ? "$Elements\n4 4 1 4\n"
                          "2 1 2 1\n1 1 2 3\n"
                          "2 2 2 1\n2 5 6 7\n"
                          "3 1 4 1\n3 1 2 3 4\n"
                          "3 2 4 1\n4 5 6 7 8\n"
                          "$EndElements\n"
                        : elements;
  return s;
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

std::string read3_error(const std::string& path, const MshGroups& groups = {}) {
  try {
    read_msh3(path, groups);
  } catch (const contactrb::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "read_msh3('" << path << "') did not throw";
  return {};
}

}  // namespace

TEST(Msh3, ReadsTwoBodiesGroupsAndOrientations) {
  const std::string path = write("good.msh", two_tetrahedra());
  EXPECT_EQ(msh_dimension(path), 3);
  const Mesh3 m = read_msh3(path);
  ASSERT_EQ(m.num_nodes(), 8);
  ASSERT_EQ(m.num_tetrahedra(), 2);
  EXPECT_EQ(m.body, (std::vector<int>{kSlaveBody, kMasterBody}));
  for (int t = 0; t < 2; ++t) EXPECT_DOUBLE_EQ(signed_volume(m, t), 1.0 / 6.0) << t;
  // Node coordinates in file order, z kept.
  EXPECT_EQ(m.nodes[3], Eigen::Vector3d(0, 0, 2));
  EXPECT_EQ(m.nodes[7], Eigen::Vector3d(0, 0, -1));
  ASSERT_EQ(m.boundary("slave").size(), 1u);
  ASSERT_EQ(m.boundary("master").size(), 1u);
  // Outward normals times the area 1/2: down for the slave face, up for the master face.
  EXPECT_EQ(facet_area_normal(m, m.boundary("slave").front()), Eigen::Vector3d(0, 0, -0.5));
  EXPECT_EQ(facet_area_normal(m, m.boundary("master").front()), Eigen::Vector3d(0, 0, 0.5));
  EXPECT_EQ(boundary_nodes(m, "slave"), (std::vector<int>{0, 1, 2}));
  std::filesystem::remove(path);
}

TEST(Msh3, TwoDimensionalReaderRefusesA3DFile) {
  const std::string path = write("for_2d.msh", two_tetrahedra());
  try {
    read_msh(path);
    ADD_FAILURE() << "read_msh read a 3D mesh";
  } catch (const contactrb::Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("is a 4-node tetrahedron: this is a 3D mesh"), std::string::npos) << msg;
  }
  std::filesystem::remove(path);
}

TEST(Msh3, TwoDimensionalMeshHasNoVolumeGroups) {
  const std::string path = std::string(CONTACTRB_SOURCE_DIR) + "/tests/data/msh/two_squares.msh";
  EXPECT_EQ(msh_dimension(path), 2);
  const std::string msg = read3_error(path);
  EXPECT_NE(msg.find("no 3D physical group 'body1' (the slave body)"), std::string::npos) << msg;
}

TEST(Msh3, UnsupportedElementType) {
  const std::string path = write("hexahedron.msh", two_tetrahedra("$Elements\n1 1 1 1\n3 1 5 1\n1 1 2 3 4 5 6 7 8\n$EndElements\n"));
  const std::string msg = read3_error(path);
  EXPECT_NE(msg.find("element 8-node hexahedron is not supported"), std::string::npos) << msg;
  std::filesystem::remove(path);
}

TEST(Msh3, MixedOrientationInOneBody) {
  // body1 holds the positive tetrahedron and the negative one (nodes 5 6 7 8 moved into it).
  const std::string path = write("mixed.msh", two_tetrahedra("$Elements\n2 2 1 2\n"
                                                             "3 1 4 1\n1 1 2 3 4\n"
                                                             "3 1 4 1\n2 5 6 7 8\n$EndElements\n"));
  MshGroups one_body;
  one_body.body_groups = {"body1"};
  one_body.required_boundaries = {};
  const std::string msg = read3_error(path, one_body);
  EXPECT_NE(msg.find("body 'body1' has inverted tetrahedra: 1 negative-volume and 1 positive-volume"),
            std::string::npos) << msg;
  std::filesystem::remove(path);
}

TEST(Msh3, ZeroVolumeTetrahedron) {
  const std::string path = write("flat.msh", two_tetrahedra("$Elements\n2 3 1 3\n"
                                                            "3 1 4 1\n1 1 2 3 4\n"
                                                            "3 2 4 2\n2 5 6 7 8\n3 5 6 7 5\n$EndElements\n"));
  const std::string msg = read3_error(path);
  EXPECT_NE(msg.find("tetrahedron 3 has zero volume"), std::string::npos) << msg;
  std::filesystem::remove(path);
}

TEST(Msh3, BoundaryTriangleNotOnAFace) {
  // "slave" names the triangle (1, 2, 5), across the two bodies.
  const std::string path = write("not_a_face.msh", two_tetrahedra("$Elements\n3 3 1 3\n"
                                                                  "2 1 2 1\n1 1 2 5\n"
                                                                  "3 1 4 1\n3 1 2 3 4\n"
                                                                  "3 2 4 1\n4 5 6 7 8\n$EndElements\n"));
  const std::string msg = read3_error(path);
  EXPECT_NE(msg.find("boundary group 'slave' triangle 1 (nodes 1, 2, 5) is not a face of any tetrahedron"),
            std::string::npos) << msg;
  std::filesystem::remove(path);
}

namespace {

// Two boxes meshed by Gmsh (OpenCASCADE kernel), written as .msh 4.1: the master [0, 1]^2 x
// [0, 0.5] and the slave [0, 1]^2 x [0.6, 1.1], with different mesh sizes (non-matching), groups
// body1 / body2 (3D) and slave / master (2D: the slave bottom face, the master top face).
void write_gmsh_blocks(const std::string& path) {
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("blocks");
  const int master = gmsh::model::occ::addBox(0, 0, 0, 1, 1, 0.5);
  const int slave = gmsh::model::occ::addBox(0, 0, 0.6, 1, 1, 0.5);
  gmsh::model::occ::synchronize();
  auto face_at = [](double z) {
    gmsh::vectorpair faces;
    gmsh::model::getEntitiesInBoundingBox(-0.1, -0.1, z - 1e-6, 1.1, 1.1, z + 1e-6, faces, 2);
    return faces.at(0).second;
  };
  auto group = [](int dim, int entity, const std::string& name) {
    gmsh::model::setPhysicalName(dim, gmsh::model::addPhysicalGroup(dim, {entity}), name);
  };
  group(3, slave, "body1");
  group(3, master, "body2");
  group(2, face_at(0.6), "slave");
  group(2, face_at(0.5), "master");
  gmsh::vectorpair slave_points, master_points;
  gmsh::model::getEntitiesInBoundingBox(-0.1, -0.1, 0.55, 1.1, 1.1, 1.2, slave_points, 0);
  gmsh::model::getEntitiesInBoundingBox(-0.1, -0.1, -0.1, 1.1, 1.1, 0.55, master_points, 0);
  gmsh::model::mesh::setSize(slave_points, 0.2);
  gmsh::model::mesh::setSize(master_points, 0.3);
  gmsh::model::mesh::generate(3);
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::write(path);
  gmsh::finalize();
}

double total_volume(const Mesh3& m, int body) {
  double v = 0.0;
  for (int t = 0; t < m.num_cells(); ++t) {
    if (m.body[static_cast<std::size_t>(t)] == body) v += signed_volume(m, t);
  }
  return v;
}

}  // namespace

TEST(Msh3, ReadsAGmshFile) {
  const std::string path = temp_path("gmsh_blocks.msh");
  write_gmsh_blocks(path);
  EXPECT_EQ(msh_dimension(path), 3);
  const Mesh3 m = read_msh3(path);
  ASSERT_NO_THROW(validate(m));
  EXPECT_EQ(m.num_bodies(), 2);
  for (int t = 0; t < m.num_cells(); ++t) ASSERT_GT(signed_volume(m, t), 0.0) << t;
  EXPECT_NEAR(total_volume(m, kSlaveBody), 0.5, 1e-12);
  EXPECT_NEAR(total_volume(m, kMasterBody), 0.5, 1e-12);
  Eigen::Vector3d slave = Eigen::Vector3d::Zero(), master = Eigen::Vector3d::Zero();
  for (const Face& f : m.boundary("slave")) {
    const Eigen::Vector3d n = facet_area_normal(m, f);
    EXPECT_LT(n.z(), 0.0);  // every slave triangle faces down, out of the slave block
    slave += n;
  }
  for (const Face& f : m.boundary("master")) master += facet_area_normal(m, f);
  EXPECT_LT((slave - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  EXPECT_LT((master - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
  for (int v : boundary_nodes(m, "slave")) EXPECT_NEAR(m.nodes[static_cast<std::size_t>(v)].z(), 0.6, 1e-12);
  EXPECT_NE(m.boundary("slave").size(), m.boundary("master").size());  // different sizes: non-matching
  std::filesystem::remove(path);
}

TEST(Msh3, RoundTripStackedBlocks) {
  const Mesh3 m = stacked_blocks(1, 0.05);
  const std::string path = temp_path("stacked.msh");
  write_msh(m, path);
  EXPECT_EQ(msh_dimension(path), 3);
  MshGroups groups;
  groups.required_boundaries = {"slave", "master", "top", "bottom", "slave_sides", "master_sides"};
  const Mesh3 r = read_msh3(path, groups);
  ASSERT_EQ(r.num_nodes(), m.num_nodes());
  for (int v = 0; v < m.num_nodes(); ++v) ASSERT_EQ(r.nodes[static_cast<std::size_t>(v)], m.nodes[static_cast<std::size_t>(v)]) << v;
  EXPECT_EQ(r.tetrahedra, m.tetrahedra);
  EXPECT_EQ(r.body, m.body);
  ASSERT_EQ(r.boundaries.size(), m.boundaries.size());
  for (const auto& [name, faces] : m.boundaries) {
    const auto& other = r.boundary(name);
    ASSERT_EQ(other.size(), faces.size()) << name;
    for (std::size_t k = 0; k < faces.size(); ++k) {
      EXPECT_EQ(other[k].vertices(), faces[k].vertices()) << name << " " << k;
    }
  }
  std::filesystem::remove(path);
}


namespace {

// two_tetrahedra() with a third node block: node 9 at (0.25, 0.25, 0.5), under the slave face
// (1, 2, 3), in entity `block` (a volume entity of tag 1, or a surface entity of tag 1).
std::string with_node_9(const std::string& elements, const std::string& block = "3 1 0 1\n9\n0.25 0.25 0.5\n") {
  std::string s = two_tetrahedra(elements);
  const std::string head = "$Nodes\n2 8 1 8\n";
  s.replace(s.find(head), head.size(), "$Nodes\n3 9 1 9\n");
  const std::string end = "$EndNodes\n";
  s.insert(s.find(end), block);
  return s;
}

}  // namespace

TEST(Msh3, TetrahedraWithoutVolumeGroups) {
  // The tetrahedra are in volume entities that carry no physical tag.
  std::string text = two_tetrahedra();
  for (const std::string tagged : {"1 0 0 1 1 1 2 1 3 0\n", "2 0 0 -1 1 1 0 1 4 0\n"}) {
    const std::string untagged = tagged.substr(0, tagged.size() - 7) + " 0 0\n";
    text.replace(text.find(tagged), tagged.size(), untagged);
  }
  const std::string path = write("no_volume_groups.msh", text);
  EXPECT_EQ(msh_dimension(path), 3);
  const std::string msg = read3_error(path);
  EXPECT_NE(msg.find("tetrahedron 3 (volume 1) is in no body group 'body1' or 'body2'"), std::string::npos) << msg;
  std::filesystem::remove(path);
}

TEST(Msh3, SurfaceGroupInsideABody) {
  // body1 is two tetrahedra sharing the face (1, 2, 3); "slave" names that interior face.
  const std::string path = write("interior_face.msh", with_node_9("$Elements\n4 5 1 5\n"
                                                                  "2 1 2 1\n1 1 2 3\n"
                                                                  "2 2 2 1\n2 5 6 7\n"
                                                                  "3 1 4 2\n3 1 2 3 4\n4 1 3 2 9\n"
                                                                  "3 2 4 1\n5 5 6 7 8\n$EndElements\n"));
  const std::string msg = read3_error(path);
  EXPECT_NE(msg.find("boundary group 'slave'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(nodes 1, 2, 3) is an interior face, not on the boundary"), std::string::npos) << msg;
  std::filesystem::remove(path);
}

TEST(Msh3, MixedTwoAndThreeDimensionalBodies) {
  // body1 is a triangle of a surface group, body2 a tetrahedron: no mesh of one dimension.
  std::string text = two_tetrahedra("$Elements\n2 2 1 2\n"
                                    "2 1 2 1\n1 1 2 3\n"
                                    "3 2 4 1\n2 5 6 7 8\n$EndElements\n");
  text.replace(text.find("2 1 \"slave\""), 11, "2 3 \"body1\"");  // surface entity 1 carries body1
  text.replace(text.find("3 3 \"body1\""), 11, "3 1 \"slave\"");
  const std::string path = write("mixed_dimension.msh", text);
  EXPECT_EQ(msh_dimension(path), 3);
  const std::string msg = read3_error(path);
  EXPECT_NE(msg.find("has no 3D physical group 'body1' (the slave body); groups present:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'body1' (2D)"), std::string::npos) << msg;
  std::filesystem::remove(path);
}

TEST(Msh3, AllTetrahedraOfABodyInvertedAreReorientedOneInvertedIsRefused) {
  // two_tetrahedra() writes body2 negative: read as positive (a mirrored file).
  const std::string good = write("negative_body.msh", two_tetrahedra());
  const Mesh3 m = read_msh3(good);
  for (int c = 0; c < m.num_cells(); ++c) EXPECT_GT(signed_volume(m, c), 0.0);
  std::filesystem::remove(good);
  // body1 of two tetrahedra, one of them inverted: refused.
  const std::string bad = write("one_inverted.msh", with_node_9("$Elements\n2 3 1 3\n"
                                                                "3 1 4 2\n3 1 2 3 4\n4 1 2 3 9\n"
                                                                "3 2 4 1\n5 5 6 7 8\n$EndElements\n"));
  MshGroups no_boundaries;
  no_boundaries.required_boundaries = {};
  const std::string msg = read3_error(bad, no_boundaries);
  EXPECT_NE(msg.find("inverted tetrahedra"), std::string::npos) << msg;
  std::filesystem::remove(bad);
}
