// contactrb mesh: built-in cases, .msh import, and the errors a user can cause.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::field_value;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

namespace {

std::string first_line(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  return line;
}

// A user error: exit code 1 and exactly one line "contactrb: error: ..." on stderr.
void expect_one_line_error(const CliResult& r) {
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind("contactrb: error: ", 0), 0u) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
}

}  // namespace

TEST(CliMesh, HertzALevel0WritesBothFilesAndCounts) {
  contactrb::test::TempDir dir("cli_mesh_hertz_a");
  const fs::path out = dir.path() / "new" / "sub";  // created if missing
  const auto r = run_cli("mesh --case hertz-a --out " + shell_quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(field_value(r.out, "slave contact nodes"), "51") << r.out;
  EXPECT_EQ(field_value(r.out, "master contact nodes"), "51") << r.out;  // matching meshes
  EXPECT_EQ(field_value(r.out, "bodies"), "2") << r.out;
  const int nodes = std::stoi(field_value(r.out, "nodes"));
  const int elements = std::stoi(field_value(r.out, "elements"));
  EXPECT_GT(nodes, 500) << r.out;  // paper Fig. 2: about 675 nodes
  EXPECT_LT(nodes, 900) << r.out;
  EXPECT_GT(elements, nodes) << r.out;  // triangles ~ 2 x nodes in 2D
  EXPECT_EQ(first_line(out / "mesh.vtu"), "<?xml version=\"1.0\"?>");
  EXPECT_EQ(first_line(out / "mesh.msh"), "$MeshFormat");

  // mesh.vtu read by an independent reader (meshio), when the system Python has it.
  if (std::system("/usr/bin/python3 -c 'import meshio' >/dev/null 2>&1") == 0) {
    const std::string check = "/usr/bin/python3 -c \"import meshio, sys; m = meshio.read(sys.argv[1]); "
                              "print(len(m.points), sum(len(c.data) for c in m.cells), int(m.point_data['slave'].sum()), "
                              "int(m.point_data['master'].sum()), int(m.cell_data['body'][0].sum()))\" " +
                              shell_quote((out / "mesh.vtu").string());
    FILE* pipe = ::popen(check.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    int points = 0, cells = 0, slave = 0, master = 0, master_cells = 0;
    const int scanned = std::fscanf(pipe, "%d %d %d %d %d", &points, &cells, &slave, &master, &master_cells);
    EXPECT_EQ(::pclose(pipe), 0);
    ASSERT_EQ(scanned, 5);
    EXPECT_EQ(points, nodes);
    EXPECT_EQ(cells, elements);
    EXPECT_EQ(slave, 51);
    EXPECT_EQ(master, 51);
    EXPECT_GT(master_cells, 0);  // body 1 triangles
    EXPECT_LT(master_cells, elements);
  }

  // The written .msh imports back with the same counts.
  const fs::path again = dir.path() / "again";
  const auto r2 = run_cli("mesh --msh " + shell_quote((out / "mesh.msh").string()) + " --out " +
                          shell_quote(again.string()));
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  for (const char* key : {"nodes", "elements", "bodies", "slave contact nodes", "master contact nodes"}) {
    EXPECT_EQ(field_value(r2.out, key), field_value(r.out, key)) << key;
  }
  EXPECT_TRUE(fs::exists(again / "mesh.vtu"));
  EXPECT_TRUE(fs::exists(again / "mesh.msh"));
}

TEST(CliMesh, UnknownCaseNamesTheCase) {
  contactrb::test::TempDir dir("cli_mesh_unknown");
  const auto r = run_cli("mesh --case hertz-z --out " + shell_quote(dir.path().string()));
  expect_one_line_error(r);
  EXPECT_NE(r.err.find("hertz-z"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("hertz-a"), std::string::npos) << "should list the known cases: " << r.err;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(CliMesh, OutputPathThatIsAFileIsAnError) {
  contactrb::test::TempDir dir("cli_mesh_outfile");
  const fs::path file = dir.path() / "occupied";
  { std::ofstream(file) << "x"; }
  const auto r = run_cli("mesh --case hertz-a --out " + shell_quote(file.string()));
  expect_one_line_error(r);
  EXPECT_NE(r.err.find(file.string()), std::string::npos) << r.err;
}

TEST(CliMesh, MissingMshFileNamesTheFile) {
  contactrb::test::TempDir dir("cli_mesh_missing");
  const std::string missing = (dir.path() / "does_not_exist.msh").string();
  const auto r = run_cli("mesh --msh " + shell_quote(missing) + " --out " + shell_quote((dir.path() / "o").string()));
  expect_one_line_error(r);
  EXPECT_NE(r.err.find("does_not_exist.msh"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "o" / "mesh.vtu"));
}

// The README's demo job (scripts/demo.sh), and every built-in case: exit 0, both files.
class CliMeshCase : public ::testing::TestWithParam<const char*> {};

TEST_P(CliMeshCase, WritesBothFiles) {
  const std::string name = GetParam();
  contactrb::test::TempDir dir("cli_mesh_case_" + name);
  const auto r = run_cli("mesh --case " + name + " --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(field_value(r.out, "mesh"), "case " + name + ", level 0") << r.out;
  EXPECT_EQ(field_value(r.out, "bodies"), "2") << r.out;
  EXPECT_GT(std::stoi(field_value(r.out, "slave contact nodes")), 10) << r.out;
  EXPECT_GT(std::stoi(field_value(r.out, "master contact nodes")), 10) << r.out;
  EXPECT_EQ(first_line(dir.path() / "mesh.vtu"), "<?xml version=\"1.0\"?>");
  EXPECT_EQ(first_line(dir.path() / "mesh.msh"), "$MeshFormat");
}

INSTANTIATE_TEST_SUITE_P(BuiltinCases, CliMeshCase, ::testing::Values("hertz-a", "hertz-b", "ring-block"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string s = info.param;
                           for (char& c : s) {
                             if (c == '-') c = '_';
                           }
                           return s;
                         });
