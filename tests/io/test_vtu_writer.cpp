// VTU output checked by an independent reader: Debian's python3-meshio, run with
// /usr/bin/python3 (the system Python that has it), through tests/io/read_vtu.py.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>

#include "contactrb/common/error.hpp"
#include "contactrb/io/vtu_writer.hpp"
#include "contactrb/mesh/structured.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::Error;
using contactrb::io::VtuWriter;
namespace mesh = contactrb::mesh;

namespace {

constexpr const char* kSystemPython = "/usr/bin/python3";

// Two bodies: a 3x2 rectangle (slave) over a 2x1 rectangle (master).
mesh::Mesh two_body_mesh() {
  mesh::Mesh a = mesh::rectangle(0.0, 0.1, 1.5, 1.1, 3, 2, mesh::kSlaveBody);
  mesh::Mesh b = mesh::rectangle(0.0, -1.0, 1.0, 0.0, 2, 1, mesh::kMasterBody);
  for (const char* g : {"bottom", "right", "top", "left"}) mesh::rename_boundary(b, g, std::string("b_") + g);
  return mesh::merge(a, b);
}

bool meshio_available() {
  if (!fs::exists(kSystemPython)) return false;
  const std::string cmd = std::string(kSystemPython) + " -c 'import meshio' >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

// Runs read_vtu.py on `path`; returns the parsed JSON. Fails the test on a reader error.
nlohmann::json read_back(const fs::path& path) {
  const std::string cmd = std::string(kSystemPython) + " " + CONTACTRB_SOURCE_DIR + "/tests/io/read_vtu.py '" +
                          path.string() + "' 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("popen failed");
  std::string output;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) output.append(buf.data(), n);
  const int status = ::pclose(pipe);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    ADD_FAILURE() << "read_vtu.py failed (status " << status << "): " << output;
    return {};
  }
  return nlohmann::json::parse(output);
}

#define SKIP_WITHOUT_MESHIO()                                                                      \
  if (!meshio_available()) GTEST_SKIP() << "/usr/bin/python3 with meshio (python3-meshio) missing"

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
      .write(path.string());

  const nlohmann::json r = read_back(path);
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
  const nlohmann::json r = read_back(path);
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
  const nlohmann::json r = read_back(path);
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
  EXPECT_EQ(read_back(path)["points"].size(), static_cast<std::size_t>(m.num_nodes()));
}
