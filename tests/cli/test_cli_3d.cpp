// Three-dimensional cases in the CLI: `cases` gives each case's dimension, `mesh` writes the 3D
// built-in meshes (read back by read_msh3), `solve` and `snapshots` solve them, and the commands
// without a 3D path refuse a 3D case or 3D snapshots in one line naming the dimension.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "csv_text.hpp"
#include "contactrb/mesh/msh_io.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::expect_user_error;
using contactrb::test::field_value;
using contactrb::test::lines_of;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

namespace {

// A one-line error: the whole of stderr is one line.
void expect_one_line(const contactrb::test::CliResult& r) { EXPECT_EQ(lines_of(r.err).size(), 1u) << r.err; }

}  // namespace

TEST(Cli3d, CasesGiveTheirDimension) {
  const auto r = run_cli("cases");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& line : lines_of(r.out)) {
    const std::string name = line.substr(0, line.find(' '));
    const bool three_d = name == "hertz-3d" || name == "patch-3d" || name == "cattaneo-3d";
    EXPECT_NE(line.find(three_d ? " 3D " : " 2D "), std::string::npos) << line;
  }
  EXPECT_NE(r.out.find("hertz-3d"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("patch-3d"), std::string::npos) << r.out;
}

TEST(Cli3d, MeshWritesTheHertz3dMeshAndItReadsBack) {
  contactrb::test::TempDir dir("cli3d_mesh");
  const auto r = run_cli("mesh --case hertz-3d --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(field_value(r.out, "dimension"), "3") << r.out;
  EXPECT_EQ(field_value(r.out, "bodies"), "2") << r.out;
  const contactrb::mesh::Mesh3 m = contactrb::mesh::read_msh3((dir.path() / "mesh.msh").string());
  EXPECT_EQ(std::to_string(m.num_nodes()), field_value(r.out, "nodes"));
  EXPECT_EQ(std::to_string(m.num_tetrahedra()), field_value(r.out, "elements"));
  EXPECT_EQ(std::to_string(contactrb::mesh::boundary_nodes(m, "slave").size()), field_value(r.out, "slave contact nodes"));
  for (const char* group : {"top", "bottom", "symmetry_x", "symmetry_y"}) EXPECT_TRUE(m.has_boundary(group)) << group;
  std::ifstream vtu(dir.path() / "mesh.vtu");
  const std::string text((std::istreambuf_iterator<char>(vtu)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("NumberOfCells=\"" + field_value(r.out, "elements") + "\""), std::string::npos);

  // The written .msh is itself a valid input of `mesh --msh`.
  const fs::path again = dir.path() / "again";
  const auto r2 = run_cli("mesh --msh " + shell_quote((dir.path() / "mesh.msh").string()) + " --out " +
                          shell_quote(again.string()));
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_EQ(field_value(r2.out, "nodes"), field_value(r.out, "nodes"));
  EXPECT_EQ(field_value(r2.out, "dimension"), "3");
}

TEST(Cli3d, PatchMeshGrowsWithTheLevel) {
  contactrb::test::TempDir dir("cli3d_patch");
  const auto r0 = run_cli("mesh --case patch-3d --out " + shell_quote((dir.path() / "0").string()));
  const auto r1 = run_cli("mesh --case patch-3d --level 1 --out " + shell_quote((dir.path() / "1").string()));
  ASSERT_EQ(r0.exit_code, 0) << r0.err;
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  EXPECT_GT(std::stoi(field_value(r1.out, "nodes")), 4 * std::stoi(field_value(r0.out, "nodes")));
  EXPECT_NE(r0.out.find("symmetry_x"), std::string::npos) << r0.out;
  const auto bad = run_cli("mesh --case patch-3d --level 9 --out " + shell_quote((dir.path() / "9").string()));
  expect_user_error(bad, "stacked-blocks mesh level must be in [0, 4] (got 9)");
  expect_one_line(bad);
}

TEST(Cli3d, CommandsWithoutA3dPathRefuseA3dCaseInOneLine) {
  contactrb::test::TempDir dir("cli3d_refuse");
  const std::string out = shell_quote(dir.path().string());
  for (const std::string& command :
       {"offline --case patch-3d --out " + out + "/m.h5", "offline --greedy --case patch-3d --out " + out + "/m.h5",
        "report --case hertz-3d --out " + out}) {
    const auto r = run_cli(command);
    expect_user_error(r, "is 3D");
    expect_one_line(r);
    EXPECT_NE(r.err.find("2D cases only"), std::string::npos) << command << ": " << r.err;
  }
}

// solve --sequence in 3D: the coarse stage runs and the patch test's answer stays uniform.
TEST(Cli3d, SolveWithGridSequencingKeepsThePatchAnswer) {
  contactrb::test::TempDir dir("cli3d_sequence");
  const auto r = run_cli("solve --case patch-3d --level 2 --solver newton --sequence 1 --mu 0.02 --out " +
                         shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("grid sequencing: level 0 "), std::string::npos) << r.out;
  const auto csv = contactrb::test::read_csv((dir.path() / "multipliers.csv").string());
  for (const std::string& p : csv.at("pressure")) EXPECT_NEAR(std::stod(p), 0.2, 1e-9) << r.out;
}

// `snapshots` in 3D writes a file of dimension 3 (its contents: io_snapshots_3d_h5py); the
// commands that build or answer reduced models refuse it in one line, and no model appears.
TEST(Cli3d, SnapshotsOfA3dCaseAreWrittenAndTheModelCommandsRefuseThem) {
  contactrb::test::TempDir dir("cli3d_snapshots");
  const std::string snapshots = (dir.path() / "s.h5").string();
  const auto r = run_cli("snapshots --case patch-3d --values 0.01,0.02 -q --out " + shell_quote(snapshots));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("case patch-3d (3D)"), std::string::npos) << r.out;
  EXPECT_EQ(field_value(r.out, "failures"), "0") << r.out;
  const std::string model = (dir.path() / "m.h5").string();
  const auto offline = run_cli("offline --snapshots " + shell_quote(snapshots) + " --out " + shell_quote(model));
  expect_user_error(offline, "supports 2D snapshots only in this build");
  EXPECT_NE(offline.err.find("is 3D"), std::string::npos) << offline.err;
  expect_one_line(offline);
  for (const std::string& command : {"online --model " + shell_quote(snapshots) + " --mu 0.02",
                                     "evaluate --model " + shell_quote(snapshots) + " --set training --out " +
                                         shell_quote((dir.path() / "e").string())}) {
    const auto e = run_cli(command);
    expect_user_error(e, "a contactrb snapshot file, not a reduced model");
    expect_one_line(e);
  }
  EXPECT_FALSE(fs::exists(model));
}

// Array-job parts of a 3D case merge into the file a single run writes (the same solves).
TEST(Cli3d, SnapshotPartsOfA3dCaseMergeIntoTheSingleRunsFile) {
  contactrb::test::TempDir dir("cli3d_parts");
  const auto file = [&](const std::string& name) { return shell_quote((dir.path() / name).string()); };
  const std::string common = "snapshots --case patch-3d --values 0.01,0.015,0.02 -q --warm-start off ";
  for (const std::string part : {"1/2", "2/2"}) {
    const auto r = run_cli(common + "--part " + part + " --out " + file("p" + part.substr(0, 1) + ".h5"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto whole = run_cli(common + "--out " + file("whole.h5"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto merged = run_cli("merge " + file("p1.h5") + " " + file("p2.h5") + " --out " + file("merged.h5"));
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  // Both read back (the reader checks every index against the 3D layout); offline names the dimension.
  for (const char* name : {"merged.h5", "whole.h5"}) {
    const auto r = run_cli("offline --snapshots " + file(name) + " --out " + file("m.h5"));
    expect_user_error(r, "is 3D");
  }
}

namespace {

double solution_force(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in).at("contact_force").get<double>();
}

}  // namespace

// `solve` on the 3D patch test (two blocks, non-matching meshes, LAC): the uniform pressure
// E mu / 0.5 ... of the confined compression at every row to round-off, and the five files.
TEST(Cli3d, SolveGivesTheUniformPressureOfThePatchTest) {
  contactrb::test::TempDir dir("cli3d_patch");
  const auto r = run_cli("solve --case patch-3d --mu 0.02 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(3D)"), std::string::npos) << r.out;
  for (const char* f : {"solution.json", "multipliers.csv", "solution.vtu", "solution_deformed.vtu", "contact.vtu"}) {
    EXPECT_TRUE(fs::is_regular_file(dir.path() / f)) << f;
  }
  const auto csv = contactrb::test::read_csv((dir.path() / "multipliers.csv").string());
  const std::size_t n = csv.at("pressure").size();
  ASSERT_GT(n, 10u);
  double area = 0.0, force = 0.0, pmin = 1e300, pmax = -1e300;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = std::stod(csv.at("weight")[i]), p = std::stod(csv.at("pressure")[i]);
    area += w;
    force += w * p;
    pmin = std::min(pmin, p);
    pmax = std::max(pmax, p);
    EXPECT_LT(std::abs(std::stod(csv.at("gap")[i])), 1e-12);
  }
  EXPECT_NEAR(area, 1.0, 1e-12);  // the unit square interface
  EXPECT_GT(pmin, 0.0);
  EXPECT_LT((pmax - pmin) / pmax, 1e-10) << pmin << " " << pmax;
  EXPECT_NEAR(solution_force(dir.path() / "solution.json"), force, 1e-12 * force);
}

// `solve --linear-solver amg` (docs/solvers.md, "AMG-preconditioned Krylov solve"): the patch
// test's uniform pressure E mu = 10 x 0.02 on every row, as with the direct solve; a bad value of
// the option is one error line. Skipped in a build without hypre.
TEST(Cli3d, SolveWithTheAmgLinearSolverKeepsThePatchPressure) {
  contactrb::test::TempDir dir("cli3d_patch_amg");
  const std::string out = " --out " + shell_quote(dir.path().string());
  expect_user_error(run_cli("solve --case patch-3d --mu 0.02 --linear-solver cg" + out),
                    "unknown --linear-solver 'cg' (expected direct, amg or auto)");
  const auto r = run_cli("solve --case patch-3d --mu 0.02 --solver newton --linear-solver amg" + out);
  if (r.exit_code != 0 && r.err.find("unavailable") != std::string::npos) GTEST_SKIP() << "this build has no hypre";
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto csv = contactrb::test::read_csv((dir.path() / "multipliers.csv").string());
  ASSERT_GT(csv.at("pressure").size(), 10u);
  for (const std::string& p : csv.at("pressure")) EXPECT_NEAR(std::stod(p), 0.2, 1e-8) << p;
}

TEST(Cli3d, TomlCaseOnA3dMeshIsThreeDimensional) {
  contactrb::test::TempDir dir("cli3d_toml");
  ASSERT_EQ(run_cli("mesh --case patch-3d --out " + shell_quote(dir.path().string())).exit_code, 0);
  std::ofstream(dir.path() / "case.toml") << R"(name = "patch-file-3d"
description = "the patch-3d mesh read from a file"
[mesh]
file = "mesh.msh"
[slave]
body = "body1"
boundary = "slave"
E = 10.0
nu = 0.3
[master]
body = "body2"
boundary = "master"
E = 10.0
nu = 0.3
[[dirichlet]]
group = "top"
uz = { a = 0.0, b = -1.0 }
[[dirichlet]]
group = "bottom"
uz = 0.0
[[dirichlet]]
group = "symmetry_x"
ux = 0.0
[[dirichlet]]
group = "symmetry_y"
uy = 0.0
[parameter]
name = "imposed displacement"
kind = "dirichlet-scale"
domain = [0.01, 0.03]
reference = 0.02
training = [0.01, 0.02, 0.03]
)";
  const auto r = run_cli("solve --case-file " + shell_quote((dir.path() / "case.toml").string()) + " --mu 0.02 --out " +
                         shell_quote((dir.path() / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("case patch-file-3d (3D)"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::is_regular_file(dir.path() / "out" / "contact.vtu"));
}

namespace {

// Two tetrahedra (body1 above z = 1, body2 below z = 0) with the contact faces as groups, and
// node 9 under the slave face; `elements` is the $Elements section.
std::string two_tetrahedra(const std::string& elements) {
  return "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
         "$PhysicalNames\n4\n2 1 \"slave\"\n2 2 \"master\"\n3 3 \"body1\"\n3 4 \"body2\"\n$EndPhysicalNames\n"
         "$Entities\n0 0 2 2\n1 0 0 1 1 1 1 1 1 0\n2 0 0 0 1 1 0 1 2 0\n"
         "1 0 0 1 1 1 2 1 3 0\n2 0 0 -1 1 1 0 1 4 0\n$EndEntities\n"
         "$Nodes\n3 9 1 9\n3 1 0 4\n1\n2\n3\n4\n0 0 1\n1 0 1\n0 1 1\n0 0 2\n"
         "3 2 0 4\n5\n6\n7\n8\n0 0 0\n1 0 0\n0 1 0\n0 0 -1\n3 1 0 1\n9\n0.25 0.25 0.5\n$EndNodes\n" +
         elements;
}

}  // namespace

TEST(Cli3d, BadThreeDimensionalMeshesGiveOneLine) {
  contactrb::test::TempDir dir("cli3d_bad_msh");
  const std::vector<std::pair<std::string, std::string>> cases{
      // one of body1's two tetrahedra inverted
      {"$Elements\n4 5 1 5\n2 1 2 1\n1 1 2 3\n2 2 2 1\n2 5 6 7\n3 1 4 2\n3 1 2 3 4\n4 1 2 3 9\n"
       "3 2 4 1\n5 5 6 7 8\n$EndElements\n",
       "inverted tetrahedra"},
      // the slave group on the face shared by body1's two tetrahedra
      {"$Elements\n4 5 1 5\n2 1 2 1\n1 1 2 3\n2 2 2 1\n2 5 6 7\n3 1 4 2\n3 1 2 3 4\n4 1 3 2 9\n"
       "3 2 4 1\n5 5 6 7 8\n$EndElements\n",
       "is an interior face, not on the boundary"}};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const fs::path msh = dir.path() / ("bad" + std::to_string(k) + ".msh");
    std::ofstream(msh) << two_tetrahedra(cases[k].first);
    const auto r = run_cli("mesh --msh " + shell_quote(msh.string()) + " --out " + shell_quote((dir.path() / "out").string()));
    expect_user_error(r, cases[k].second);
    expect_one_line(r);
  }
}
