// The files of a 3D solution (study/solution_fields_3d.hpp): a uniaxial strain field gives the
// analytic stress and von Mises value; the contact surface and multipliers.csv carry the rows.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "contactrb/common/error.hpp"
#include "contactrb/mesh/structured.hpp"
#include "contactrb/study/solution_fields_3d.hpp"
#include "support/meshio_reader.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
namespace mesh = contactrb::mesh;
namespace study = contactrb::study;

namespace {

// The unit cube (slave) whose bottom face is the slave group.
mesh::Mesh3 cube() {
  mesh::Mesh3 m = mesh::box({0, 0, 0}, {1, 1, 1}, 2, 2, 2, mesh::kSlaveBody);
  mesh::rename_boundary(m, "bottom", mesh::kSlaveBoundary);
  return m;
}

// u = e (nu x, nu y, -z): uniaxial stress szz = -E e, every other component 0.
Eigen::VectorXd uniaxial(const mesh::Mesh3& m, double e, double nu) {
  Eigen::VectorXd u(m.num_dofs());
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Eigen::Vector3d& x = m.nodes[static_cast<std::size_t>(i)];
    u.segment<3>(3 * i) = e * Eigen::Vector3d(nu * x.x(), nu * x.y(), -x.z());
  }
  return u;
}

study::SlaveSurfaceFields rows(const mesh::Mesh3& m) {
  study::SlaveSurfaceFields c;
  c.nodes = mesh::boundary_nodes(m, mesh::kSlaveBoundary);
  const auto n = static_cast<Eigen::Index>(c.nodes.size());
  c.pressure = Eigen::VectorXd::LinSpaced(n, 0.5, 2.0);
  c.gap = Eigen::VectorXd::LinSpaced(n, -1e-3, 1e-3);
  c.weight = Eigen::VectorXd::Constant(n, 1.0 / 16.0);
  return c;
}

}  // namespace

TEST(SolutionFields3d, UniaxialStressAndVonMises) {
  const mesh::Mesh3 m = cube();
  const double E = 10.0, nu = 0.3, e = 0.02;
  const study::CellStress3 s = study::cell_stress(m, {{E, nu}}, uniaxial(m, e, nu));
  ASSERT_EQ(s.tensor.size(), 9 * m.num_cells());
  for (int c = 0; c < m.num_cells(); ++c) {
    for (int k = 0; k < 9; ++k) EXPECT_NEAR(s.tensor[9 * c + k], k == 8 ? -E * e : 0.0, 1e-12) << k;
    EXPECT_NEAR(s.von_mises[c], E * e, 1e-12);
  }
}

TEST(SolutionFields3d, FilesCarryTheFieldsAndTheRows) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("fields3d");
  const mesh::Mesh3 m = cube();
  const Eigen::VectorXd u = uniaxial(m, 0.02, 0.3);
  const study::SlaveSurfaceFields c = rows(m);
  contactrb::cases::ParameterSpec p;
  p.name = "imposed displacement";
  const study::VtuFiles f = study::write_solution_vtus(m, {{10.0, 0.3}}, {p}, contactrb::cases::Mu::Constant(1, 0.02),
                                                       u, c, dir.path().string());
  const nlohmann::json vtu = contactrb::test::read_vtu_with_meshio(f.vtu);
  EXPECT_EQ(vtu["cells"][0]["type"], "tetra");
  EXPECT_EQ(vtu["field_data"]["imposed displacement"], nlohmann::json::array({0.02}));
  for (std::size_t r = 0; r < c.nodes.size(); ++r) {
    EXPECT_EQ(vtu["point_data"]["contact_pressure"][static_cast<std::size_t>(c.nodes[r])].get<double>(),
              c.pressure[static_cast<Eigen::Index>(r)]);
  }
  const nlohmann::json surface = contactrb::test::read_vtu_with_meshio(f.contact_vtu);
  EXPECT_EQ(surface["cells"][0]["type"], "triangle");
  EXPECT_EQ(surface["cells"][0]["data"].size(), m.boundary(mesh::kSlaveBoundary).size());
  ASSERT_EQ(surface["points"].size(), c.nodes.size());
  for (std::size_t r = 0; r < c.nodes.size(); ++r) {
    EXPECT_EQ(surface["points"][r][2].get<double>(), 0.0);  // the bottom face
    EXPECT_EQ(surface["point_data"]["gap"][r].get<double>(), c.gap[static_cast<Eigen::Index>(r)]);
  }

  const fs::path csv = dir.path() / "multipliers.csv";
  study::write_multipliers_csv(m, c, csv.string());
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "r,x,y,z,gap,pressure,weight");
  std::size_t count = 0;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::vector<double> v;
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 7u);
    const Eigen::Vector3d& X = m.nodes[static_cast<std::size_t>(c.nodes[count])];
    EXPECT_EQ(v[1], X.x());
    EXPECT_EQ(v[3], X.z());
    EXPECT_EQ(v[4], c.gap[static_cast<Eigen::Index>(count)]);
    EXPECT_EQ(v[5], c.pressure[static_cast<Eigen::Index>(count)]);
    EXPECT_EQ(v[6], 1.0 / 16.0);
    ++count;
  }
  EXPECT_EQ(count, c.nodes.size());
}

TEST(SolutionFields3d, InconsistentRowsAreRefused) {
  contactrb::test::TempDir dir("fields3d_bad");
  const mesh::Mesh3 m = cube();
  study::SlaveSurfaceFields c = rows(m);
  c.gap.resize(2);
  EXPECT_THROW(study::write_multipliers_csv(m, c, (dir.path() / "m.csv").string()), contactrb::Error);
  c = rows(m);
  c.nodes.pop_back();  // a slave triangle on a node without a row
  c.pressure.conservativeResize(c.pressure.size() - 1);
  c.gap.conservativeResize(c.gap.size() - 1);
  c.weight.conservativeResize(c.weight.size() - 1);
  EXPECT_THROW(study::write_solution_vtus(m, {{10.0, 0.3}}, {}, contactrb::cases::Mu(0), uniaxial(m, 0.01, 0.3), c,
                                         dir.path().string()),
               contactrb::Error);
}
