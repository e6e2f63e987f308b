// The files of a frictional solve (study/friction_fields.hpp), read back by independent readers:
// multipliers.csv by hand, contact.vtu by meshio.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "contactrb/cases/frictional_cases.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/study/friction_fields.hpp"
#include "support/meshio_reader.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
namespace cases = contactrb::cases;
namespace contact = contactrb::contact;
namespace hf = contactrb::hf;
namespace study = contactrb::study;

namespace {
struct Solved {
  cases::FrictionalCase c = cases::cattaneo_case(0, {0.2, 0.02, 0.3, 1});  // a slip zone on the coarse mesh
  contact::ContactPair pair = contact::make_contact_pair(c.problem.mesh);
  contact::ContactQuadrature quadrature =
      contact::make_quadrature(c.problem.mesh, pair, contact::Discretization::Collocation);
  hf::FrictionalSolution s = hf::solve_load_path(c.problem, c.path, c.friction);
};
}  // namespace

TEST(FrictionFields, MultipliersCsvCarriesTheTractionsAndStates) {
  const Solved x;
  ASSERT_TRUE(x.s.converged) << x.s.message;
  contactrb::test::TempDir dir("friction_fields");
  const study::FrictionFiles f = study::write_friction_fields(x.c.problem.mesh, x.pair, x.quadrature, x.s, dir.path().string());
  for (const std::string& path : {f.vtu, f.deformed_vtu, f.contact_vtu, f.multipliers}) EXPECT_TRUE(fs::exists(path)) << path;
  std::ifstream in(f.multipliers);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "r,abscissa,x,y,gap,pressure,tangential,state,weight");
  Eigen::Index r = 0;
  int stick = 0, slip = 0;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::vector<std::string> cells;
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 9u) << line;
    EXPECT_EQ(std::stoll(cells[0]), r);
    EXPECT_EQ(std::stod(cells[5]), x.s.lambda(r));
    EXPECT_EQ(std::stod(cells[6]), x.s.lambda_t(r));
    EXPECT_EQ(cells[7], hf::to_string(x.s.state[static_cast<std::size_t>(r)]));
    EXPECT_EQ(std::stod(cells[8]), x.quadrature.weight(r));
    if (cells[7] != "open") {
      EXPECT_LT(std::abs(std::stod(cells[4])), 1e-8);  // closed: zero gap
    }
    stick += cells[7] == "stick";
    slip += cells[7] == "slip";
    ++r;
  }
  EXPECT_EQ(r, x.s.lambda.size());
  EXPECT_EQ(stick, x.s.stick_nodes);
  EXPECT_EQ(slip, x.s.slip_nodes);
  EXPECT_GT(slip, 0);
}

TEST(FrictionFields, ContactVtuCarriesTheTractionsAndStates) {
  SKIP_WITHOUT_MESHIO();
  const Solved x;
  ASSERT_TRUE(x.s.converged) << x.s.message;
  contactrb::test::TempDir dir("friction_fields_vtu");
  const study::FrictionFiles f = study::write_friction_fields(x.c.problem.mesh, x.pair, x.quadrature, x.s, dir.path().string());
  const nlohmann::json surface = contactrb::test::read_vtu_with_meshio(f.contact_vtu);
  EXPECT_EQ(surface["cells"][0]["type"], "line");
  ASSERT_EQ(surface["points"].size(), x.pair.slave.size());
  for (std::size_t q = 0; q < x.pair.slave.size(); ++q) {
    const auto r = static_cast<Eigen::Index>(q);
    EXPECT_EQ(surface["point_data"]["tangential_traction"][q].get<double>(), x.s.lambda_t(r));
    EXPECT_EQ(surface["point_data"]["contact_pressure"][q].get<double>(), x.s.lambda(r));
    EXPECT_EQ(surface["point_data"]["state"][q].get<double>(), static_cast<double>(x.s.state[q]));
  }
}

TEST(FrictionFields, MismatchedSolutionIsRefused) {
  Solved x;
  x.s.lambda_t.resize(3);
  contactrb::test::TempDir dir("friction_fields_bad");
  EXPECT_THROW(study::write_friction_fields(x.c.problem.mesh, x.pair, x.quadrature, x.s, dir.path().string()),
               contactrb::Error);
}
