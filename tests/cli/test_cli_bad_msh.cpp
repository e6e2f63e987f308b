// `contactrb mesh --msh FILE`: every bad input (docs/meshes.md, "Importing a Gmsh .msh file") ends in one clear line on
// stderr naming the file and the problem, exit code 1, and no output files.
// Fixtures: tests/data/msh/ (shared with tests/mesh/test_msh_io.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::field_value;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

namespace {

std::string fixture(const std::string& name) { return std::string(CONTACTRB_SOURCE_DIR) + "/tests/data/msh/" + name; }

// Runs `mesh --msh path` into a fresh directory and checks the failure contract: exit code
// 1, one line "contactrb: error: ..." naming the file and containing every key phrase,
// nothing written.
void expect_rejected(const std::string& path, const std::vector<std::string>& key_phrases) {
  contactrb::test::TempDir dir("cli_bad_msh");
  const fs::path out = dir.path() / "out";
  const CliResult r = run_cli("mesh --msh " + shell_quote(path) + " --out " + shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(r.err.rfind("contactrb: error: ", 0), 0u) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
  EXPECT_NE(r.err.find(fs::path(path).filename().string()), std::string::npos) << "file not named: " << r.err;
  for (const std::string& phrase : key_phrases) {
    EXPECT_NE(r.err.find(phrase), std::string::npos) << "missing '" << phrase << "' in: " << r.err;
  }
  EXPECT_FALSE(fs::exists(out / "mesh.vtu"));
  EXPECT_FALSE(fs::exists(out / "mesh.msh"));
}

}  // namespace

TEST(CliBadMsh, MissingFile) { expect_rejected(fixture("no_such_file.msh"), {"does not exist"}); }

TEST(CliBadMsh, NotAMesh) { expect_rejected(fixture("not_a_mesh.msh"), {"not a Gmsh mesh"}); }

TEST(CliBadMsh, LegacyFormatVersion2) { expect_rejected(fixture("version2.msh"), {"version 2.2", "4.1"}); }

TEST(CliBadMsh, BinaryFile) { expect_rejected(fixture("binary.msh"), {"binary", "ASCII"}); }

TEST(CliBadMsh, MissingGroup) {
  expect_rejected(fixture("missing_group.msh"), {"physical group 'master'", "groups present"});
}

TEST(CliBadMsh, InvertedTriangle) { expect_rejected(fixture("inverted_triangle.msh"), {"inverted"}); }

TEST(CliBadMsh, ZeroAreaTriangle) { expect_rejected(fixture("zero_area.msh"), {"triangle 4", "zero area"}); }

TEST(CliBadMsh, UnreferencedNode) {
  expect_rejected(fixture("unreferenced_node.msh"), {"node 10", "not referenced"});
}

TEST(CliBadMsh, TruncatedFile) {
  contactrb::test::TempDir dir("cli_truncated");
  const fs::path path = dir.path() / "truncated.msh";
  { std::ofstream(path) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n"; }
  expect_rejected(path.string(), {"unexpected end of file"});
}

TEST(CliBadMsh, DirectoryInsteadOfFile) {
  contactrb::test::TempDir dir("cli_msh_dir");
  const fs::path path = dir.path() / "folder.msh";
  fs::create_directories(path);
  expect_rejected(path.string(), {});
}

// The good fixture next to the bad ones imports (the failures above are about the files).
TEST(CliBadMsh, HandWrittenTwoSquaresImports) {
  contactrb::test::TempDir dir("cli_two_squares");
  const CliResult r = run_cli("mesh --msh " + shell_quote(fixture("two_squares.msh")) + " --out " +
                              shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(field_value(r.out, "nodes"), "8") << r.out;
  EXPECT_EQ(field_value(r.out, "elements"), "4") << r.out;
  EXPECT_EQ(field_value(r.out, "bodies"), "2") << r.out;
  EXPECT_EQ(field_value(r.out, "slave contact nodes"), "2") << r.out;
  EXPECT_EQ(field_value(r.out, "master contact nodes"), "2") << r.out;
  EXPECT_TRUE(fs::exists(dir.path() / "mesh.vtu"));
  EXPECT_TRUE(fs::exists(dir.path() / "mesh.msh"));
}
