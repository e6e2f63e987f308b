// Three-dimensional VTU output (tetrahedra, surface triangles) read back by the independent
// reader of the VTU tests, Debian's python3-meshio (support/meshio_reader.hpp).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <filesystem>

#include "contactrb/common/error.hpp"
#include "contactrb/io/vtu_writer.hpp"
#include "contactrb/mesh/structured.hpp"
#include "support/meshio_reader.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::io::VtuWriter;
namespace mesh = contactrb::mesh;

TEST(VtuWriter3d, TetrahedraAndFieldsReadBackByMeshio) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("vtu3d");
  mesh::Mesh3 m = mesh::box({0, 0, 0}, {2, 1, 1}, 2, 1, 1, mesh::kSlaveBody);
  for (std::size_t c = 6; c < m.body.size(); ++c) m.body[c] = mesh::kMasterBody;  // the second cube
  Eigen::VectorXd u(m.num_dofs()), tensor(9 * m.num_cells()), vm(m.num_cells());
  for (int i = 0; i < m.num_dofs(); ++i) u[i] = 1.0 / (i + 3.0) - 0.25;
  for (int i = 0; i < tensor.size(); ++i) tensor[i] = std::sin(i + 0.5);
  for (int c = 0; c < m.num_cells(); ++c) vm[c] = mesh::signed_volume(m, c);
  const fs::path path = dir.path() / "solution.vtu";
  const fs::path deformed = dir.path() / "deformed.vtu";
  VtuWriter w(m);
  w.add_point_vector("displacement", u).add_cell_scalar("von_mises", vm).add_cell_field("stress", 9, tensor);
  EXPECT_THROW(w.add_point_vector("two", Eigen::VectorXd::Zero(2 * m.num_nodes())), contactrb::Error);
  w.write(path.string());
  w.deform_by("displacement", 2.0).write(deformed.string());

  const nlohmann::json r = contactrb::test::read_vtu_with_meshio(path);
  ASSERT_FALSE(r.is_null());
  ASSERT_EQ(r["cells"].size(), 1u);
  EXPECT_EQ(r["cells"][0]["type"], "tetra");  // VTK type 10
  ASSERT_EQ(r["cells"][0]["data"].size(), static_cast<std::size_t>(m.num_cells()));
  ASSERT_EQ(r["points"].size(), static_cast<std::size_t>(m.num_nodes()));
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(r["points"][i][k].get<double>(), m.nodes[i](static_cast<Eigen::Index>(k)));
      EXPECT_EQ(r["point_data"]["displacement"][i][k].get<double>(), u[static_cast<Eigen::Index>(3 * i + k)]);
    }
  }
  for (std::size_t c = 0; c < m.tetrahedra.size(); ++c) {
    for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(r["cells"][0]["data"][c][k].get<int>(), m.tetrahedra[c][k]);
    EXPECT_EQ(r["cell_data"]["body"][0][c].get<int>(), m.body[c]);
    EXPECT_EQ(r["cell_data"]["von_mises"][0][c].get<double>(), vm[static_cast<Eigen::Index>(c)]);
    // meshio gives a 9-component cell array as 3 x 3 (row by row) or as 9 values.
    const nlohmann::json s = r["cell_data"]["stress"][0][c];
    std::vector<double> flat;
    for (const auto& row : s) {
      if (row.is_array()) {
        for (const auto& v : row) flat.push_back(v.get<double>());
      } else {
        flat.push_back(row.get<double>());
      }
    }
    ASSERT_EQ(flat.size(), 9u);
    for (std::size_t k = 0; k < 9; ++k) EXPECT_EQ(flat[k], tensor[static_cast<Eigen::Index>(9 * c + k)]);
  }
  const nlohmann::json d = contactrb::test::read_vtu_with_meshio(deformed);
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(d["points"][i][k].get<double>(),
                m.nodes[i](static_cast<Eigen::Index>(k)) + 2.0 * u[static_cast<Eigen::Index>(3 * i + k)]);
    }
  }
}

TEST(VtuWriter3d, SurfaceTrianglesReadBackByMeshio) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("vtu3d_surface");
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0.5}, {1, 0, 0.25}, {0, 1, 0.125}, {1, 1, 1.0 / 3.0}};
  const std::vector<std::array<int, 3>> triangles = {{0, 1, 2}, {1, 3, 2}};
  Eigen::VectorXd u(12), gap(4);
  for (int i = 0; i < 12; ++i) u[i] = 0.1 * i - 0.35;
  gap << 1e-3, 0.0, -2e-12, 0.25;
  const fs::path path = dir.path() / "contact.vtu";
  VtuWriter w = VtuWriter::triangles(points, triangles);
  w.add_point_vector("displacement", u).add_point_scalar("gap", gap).write(path.string());
  const nlohmann::json r = contactrb::test::read_vtu_with_meshio(path);
  ASSERT_EQ(r["cells"].size(), 1u);
  EXPECT_EQ(r["cells"][0]["type"], "triangle");
  EXPECT_EQ(r["cells"][0]["data"], nlohmann::json::parse("[[0,1,2],[1,3,2]]"));
  EXPECT_FALSE(r["cell_data"].contains("body"));
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(r["points"][i][2].get<double>(), points[i].z());
    EXPECT_EQ(r["point_data"]["gap"][i].get<double>(), gap[static_cast<Eigen::Index>(i)]);
    EXPECT_EQ(r["point_data"]["displacement"][i][2].get<double>(), u[static_cast<Eigen::Index>(3 * i + 2)]);
  }
  EXPECT_THROW(VtuWriter::triangles(points, {{0, 1, 4}}).write((dir.path() / "bad.vtu").string()), contactrb::Error);
}
