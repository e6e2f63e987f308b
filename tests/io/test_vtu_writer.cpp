// VTU output checked by an independent reader: Debian's python3-meshio, run with
// /usr/bin/python3 (the system Python that has it), through tests/io/read_vtu.py
// (support/meshio_reader.hpp). The .pvd collection is checked as text here and opened by
// ParaView in tests/io/paraview_check.py.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/io/pvd_writer.hpp"
#include "contactrb/io/vtu_writer.hpp"
#include "contactrb/mesh/structured.hpp"
#include "support/meshio_reader.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::Error;
using contactrb::io::VtuWriter;
namespace mesh = contactrb::mesh;

namespace {

// Two bodies: a 3x2 rectangle (slave) over a 2x1 rectangle (master).
mesh::Mesh two_body_mesh() {
  mesh::Mesh a = mesh::rectangle(0.0, 0.1, 1.5, 1.1, 3, 2, mesh::kSlaveBody);
  mesh::Mesh b = mesh::rectangle(0.0, -1.0, 1.0, 0.0, 2, 1, mesh::kMasterBody);
  for (const char* g : {"bottom", "right", "top", "left"}) mesh::rename_boundary(b, g, std::string("b_") + g);
  return mesh::merge(a, b);
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(VtuWriter, FieldsReadBackByMeshio) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("vtu_fields");
  const mesh::Mesh m = two_body_mesh();
  Eigen::VectorXd u(m.num_dofs());
  Eigen::VectorXd p(m.num_nodes());
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Eigen::Vector2d& x = m.nodes[static_cast<std::size_t>(i)];
    u[2 * i] = 0.1 * x.y() + 1.0 / 3.0;
    u[2 * i + 1] = -0.2 * x.x() * x.x();
    p[i] = std::exp(x.x()) - 1e-300;
  }
  Eigen::VectorXd area(m.num_triangles());
  for (int t = 0; t < m.num_triangles(); ++t) area[t] = mesh::signed_area(m, t);
  const fs::path path = dir.path() / "fields.vtu";
  VtuWriter(m)
      .add_point_vector("displacement", u)
      .add_point_scalar("contact_pressure", p)
      .add_cell_scalar("area", area)
      .add_field_data("delta", 0.3)
      .add_field_data("E2 & <ratio>", std::vector<double>{1.0 / 7.0, -2.5e-300})
      .write(path.string());

  // Binary: every array in the appended raw block, the header readable XML.
  const std::string text = file_text(path);
  EXPECT_EQ(text.find("format=\"ascii\""), std::string::npos);
  EXPECT_NE(text.find("<AppendedData encoding=\"raw\">"), std::string::npos);
  EXPECT_NE(text.find("format=\"appended\""), std::string::npos);

  const nlohmann::json r = contactrb::test::read_vtu_with_meshio(path);
  ASSERT_FALSE(r.is_null());
  ASSERT_EQ(r["points"].size(), static_cast<std::size_t>(m.num_nodes()));
  ASSERT_EQ(r["cells"].size(), 1u);
  EXPECT_EQ(r["cells"][0]["type"], "triangle");
  ASSERT_EQ(r["cells"][0]["data"].size(), static_cast<std::size_t>(m.num_triangles()));
  for (int i = 0; i < m.num_nodes(); ++i) {
    const auto& pt = r["points"][static_cast<std::size_t>(i)];
    EXPECT_EQ(pt[0].get<double>(), m.nodes[static_cast<std::size_t>(i)].x());
    EXPECT_EQ(pt[1].get<double>(), m.nodes[static_cast<std::size_t>(i)].y());
    EXPECT_EQ(pt[2].get<double>(), 0.0);
    const auto& d = r["point_data"]["displacement"][static_cast<std::size_t>(i)];
    ASSERT_EQ(d.size(), 3u);
    EXPECT_EQ(d[0].get<double>(), u[2 * i]);  // round-trip exact
    EXPECT_EQ(d[1].get<double>(), u[2 * i + 1]);
    EXPECT_EQ(d[2].get<double>(), 0.0);
    EXPECT_EQ(r["point_data"]["contact_pressure"][static_cast<std::size_t>(i)].get<double>(), p[i]);
  }
  for (int t = 0; t < m.num_triangles(); ++t) {
    const auto ts = static_cast<std::size_t>(t);
    for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(r["cells"][0]["data"][ts][k].get<int>(), m.triangles[ts][k]);
    EXPECT_EQ(r["cell_data"]["body"][0][ts].get<int>(), m.body[ts]);
    EXPECT_EQ(r["cell_data"]["area"][0][ts].get<double>(), area[t]);
  }
  ASSERT_EQ(r["field_data"].size(), 2u);
  EXPECT_EQ(r["field_data"]["delta"], nlohmann::json::array({0.3}));
  ASSERT_EQ(r["field_data"]["E2 & <ratio>"].size(), 2u);  // the name XML-escaped and read back
  EXPECT_EQ(r["field_data"]["E2 & <ratio>"][0].get<double>(), 1.0 / 7.0);
  EXPECT_EQ(r["field_data"]["E2 & <ratio>"][1].get<double>(), -2.5e-300);
  // Only the target is left in the directory (the temporary file was renamed).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 1);
}

TEST(VtuWriter, DeformedConfiguration) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("vtu_deformed");
  const mesh::Mesh m = two_body_mesh();
  Eigen::VectorXd u(m.num_dofs());
  for (int i = 0; i < m.num_dofs(); ++i) u[i] = 0.01 * (i % 7) - 0.02;
  const fs::path path = dir.path() / "deformed.vtu";
  VtuWriter(m).add_point_vector("displacement", u).deform_by("displacement", 2.0).write(path.string());
  const nlohmann::json r = contactrb::test::read_vtu_with_meshio(path);
  ASSERT_EQ(r["points"].size(), static_cast<std::size_t>(m.num_nodes()));
  for (int i = 0; i < m.num_nodes(); ++i) {
    const auto& pt = r["points"][static_cast<std::size_t>(i)];
    EXPECT_NEAR(pt[0].get<double>(), m.nodes[static_cast<std::size_t>(i)].x() + 2.0 * u[2 * i], 1e-15);
    EXPECT_NEAR(pt[1].get<double>(), m.nodes[static_cast<std::size_t>(i)].y() + 2.0 * u[2 * i + 1], 1e-15);
    EXPECT_EQ(r["point_data"]["displacement"][static_cast<std::size_t>(i)][0].get<double>(), u[2 * i]);
  }
}

TEST(VtuWriter, MeshOnlyHasBodyCellData) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("vtu_mesh_only");
  const mesh::Mesh m = two_body_mesh();
  const fs::path path = dir.path() / "mesh.vtu";
  contactrb::io::write_vtu(m, path.string());
  const nlohmann::json r = contactrb::test::read_vtu_with_meshio(path);
  EXPECT_EQ(r["points"].size(), static_cast<std::size_t>(m.num_nodes()));
  EXPECT_TRUE(r["point_data"].empty());
  ASSERT_EQ(r["cell_data"].size(), 1u);
  int slave = 0, master = 0;
  for (const auto& b : r["cell_data"]["body"][0]) (b.get<int>() == 0 ? slave : master)++;
  EXPECT_EQ(slave, 12);
  EXPECT_EQ(master, 4);
}

TEST(VtuWriter, WrongSizeFieldNamesTheField) {
  const mesh::Mesh m = two_body_mesh();
  VtuWriter w(m);
  try {
    w.add_point_vector("displacement", Eigen::VectorXd::Zero(m.num_nodes()));
    FAIL() << "expected contactrb::Error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("'displacement'"), std::string::npos) << msg;
    EXPECT_NE(msg.find(std::to_string(m.num_nodes())), std::string::npos) << msg;
    EXPECT_NE(msg.find(std::to_string(m.num_dofs())), std::string::npos) << msg;
  }
  EXPECT_THROW(w.add_point_scalar("p", Eigen::VectorXd::Zero(m.num_nodes() + 1)), Error);
  EXPECT_THROW(w.add_cell_scalar("c", Eigen::VectorXd::Zero(m.num_nodes())), Error);
  EXPECT_THROW(w.add_cell_vector("c", Eigen::VectorXd::Zero(m.num_triangles())), Error);
  EXPECT_TRUE(w.point_data().empty());
  EXPECT_TRUE(w.cell_data().empty());
}

TEST(VtuWriter, RejectsBadNamesAndValues) {
  const mesh::Mesh m = two_body_mesh();
  VtuWriter w(m);
  w.add_point_scalar("p", Eigen::VectorXd::Zero(m.num_nodes()));
  EXPECT_THROW(w.add_point_scalar("p", Eigen::VectorXd::Zero(m.num_nodes())), Error);
  EXPECT_THROW(w.add_point_scalar("", Eigen::VectorXd::Zero(m.num_nodes())), Error);
  EXPECT_THROW(w.add_cell_scalar("body", Eigen::VectorXd::Zero(m.num_triangles())), Error);
  Eigen::VectorXd bad = Eigen::VectorXd::Zero(m.num_nodes());
  bad[3] = std::numeric_limits<double>::quiet_NaN();
  try {
    w.add_point_scalar("q", bad);
    FAIL() << "expected contactrb::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'q'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("index 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(w.deform_by("p"), Error);             // a scalar
  EXPECT_THROW(w.deform_by("displacement"), Error);  // not added
}

TEST(VtuWriter, UnwritablePathNamesThePath) {
  contactrb::test::TempDir dir("vtu_unwritable");
  const mesh::Mesh m = two_body_mesh();
  const std::string path = (dir.path() / "no_such_dir" / "mesh.vtu").string();
  try {
    contactrb::io::write_vtu(m, path);
    FAIL() << "expected contactrb::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(contactrb::io::write_vtu(m, dir.path().string()), Error);  // a directory
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 0);
}

TEST(VtuWriter, OverwritesAnExistingFile) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("vtu_overwrite");
  const fs::path path = dir.path() / "mesh.vtu";
  { std::ofstream(path) << "old content"; }
  const mesh::Mesh m = two_body_mesh();
  contactrb::io::write_vtu(m, path.string());
  EXPECT_EQ(contactrb::test::read_vtu_with_meshio(path)["points"].size(), static_cast<std::size_t>(m.num_nodes()));
}

TEST(VtuWriter, LineCellsReadBackByMeshio) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("vtu_lines");
  const std::vector<Eigen::Vector2d> points = {{0.0, 1.0}, {0.25, 0.9}, {0.5, 0.85}, {1.0, 0.8}};
  const std::vector<std::array<int, 2>> segments = {{0, 1}, {1, 2}, {2, 3}};
  Eigen::VectorXd u(8), gap(4), length(3);
  u << 0.1, -0.2, 0.3, -0.4, 0.5, -0.6, 0.7, -0.8;
  gap << 1e-3, 0.0, -2e-12, 0.25;
  length << 0.1, 0.2, 0.3;
  VtuWriter w = VtuWriter::lines(points, segments);
  EXPECT_EQ(w.num_points(), 4);
  EXPECT_EQ(w.num_cells(), 3);
  w.add_point_vector("displacement", u).add_point_scalar("gap", gap).add_cell_scalar("length", length);
  EXPECT_THROW(w.add_point_scalar("p", Eigen::VectorXd::Zero(3)), Error);  // 4 points
  EXPECT_THROW(w.add_cell_scalar("c", Eigen::VectorXd::Zero(4)), Error);   // 3 cells
  const fs::path path = dir.path() / "contact.vtu";
  w.write(path.string());
  const nlohmann::json r = contactrb::test::read_vtu_with_meshio(path);
  ASSERT_EQ(r["points"].size(), 4u);
  ASSERT_EQ(r["cells"].size(), 1u);
  EXPECT_EQ(r["cells"][0]["type"], "line");
  EXPECT_EQ(r["cells"][0]["data"], nlohmann::json::parse("[[0,1],[1,2],[2,3]]"));
  EXPECT_FALSE(r["cell_data"].contains("body"));  // no bodies on a polyline
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(r["points"][i][0].get<double>(), points[i].x());
    EXPECT_EQ(r["points"][i][1].get<double>(), points[i].y());
    EXPECT_EQ(r["point_data"]["gap"][i].get<double>(), gap[static_cast<Eigen::Index>(i)]);
    EXPECT_EQ(r["point_data"]["displacement"][i][1].get<double>(), u[2 * static_cast<Eigen::Index>(i) + 1]);
  }
  EXPECT_EQ(r["cell_data"]["length"][0][2].get<double>(), 0.3);

  // A segment that names a missing point is refused at write time, naming the path.
  const std::string bad = (dir.path() / "bad.vtu").string();
  try {
    VtuWriter::lines(points, {{0, 4}}).write(bad);
    FAIL() << "expected contactrb::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("node 4 of 4"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(bad));
}

TEST(VtuWriter, FieldDataRejectsEmptyRepeatedAndNonFinite) {
  const mesh::Mesh m = two_body_mesh();
  VtuWriter w(m);
  w.add_field_data("mu", 0.3);
  EXPECT_THROW(w.add_field_data("mu", 0.4), Error);
  EXPECT_THROW(w.add_field_data("", 0.4), Error);
  EXPECT_THROW(w.add_field_data("none", std::vector<double>{}), Error);
  try {
    w.add_field_data("E2", std::numeric_limits<double>::infinity());
    FAIL() << "expected contactrb::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'E2'"), std::string::npos) << e.what();
  }
  EXPECT_EQ(w.field_data().size(), 1u);
  // A point field may share a field data name (different sections).
  EXPECT_NO_THROW(w.add_point_scalar("mu", Eigen::VectorXd::Zero(m.num_nodes())));
}

TEST(PvdWriter, ListsTheDataSetsWithRoundTripTimeSteps) {
  contactrb::test::TempDir dir("pvd");
  const fs::path path = dir.path() / "solutions.pvd";
  contactrb::io::write_pvd(path.string(), {{0.1, "000001/solution.vtu"}, {1.0 / 3.0, "a&b/\"q\".vtu"}});
  const std::string text = file_text(path);
  EXPECT_EQ(text.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\"", 0), 0u) << text;
  EXPECT_NE(text.find("<DataSet timestep=\"0.1\" group=\"\" part=\"0\" file=\"000001/solution.vtu\"/>"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("timestep=\"0.3333333333333333\""), std::string::npos) << text;
  EXPECT_NE(text.find("file=\"a&amp;b/&quot;q&quot;.vtu\""), std::string::npos) << text;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 1);

  contactrb::io::write_pvd(path.string(), {});  // an empty collection replaces the old one
  EXPECT_EQ(file_text(path).find("<DataSet"), std::string::npos);
  EXPECT_THROW(contactrb::io::write_pvd(path.string(), {{std::numeric_limits<double>::quiet_NaN(), "x.vtu"}}), Error);
  EXPECT_THROW(contactrb::io::write_pvd(path.string(), {{0.0, ""}}), Error);
  EXPECT_THROW(contactrb::io::write_pvd((dir.path() / "missing" / "x.pvd").string(), {}), Error);
}
