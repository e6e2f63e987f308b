// contactrb snapshots: the summary, the exit codes of failed solves (with and without
// --allow-failures), progress lines when stderr is not a terminal, and usage errors.
// Small sets (hertz-a at level 0, a few values) keep it fast.
#include <gtest/gtest.h>

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
int count(const std::string& text, const std::string& word) {
  int n = 0;
  for (auto p = text.find(word); p != std::string::npos; p = text.find(word, p + 1)) ++n;
  return n;
}
int entries(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}
}  // namespace

TEST(CliSnapshots, HertzAWritesTheFileAndASummary) {
  contactrb::test::TempDir dir("snapshots_ok");
  const std::string out = (dir.path() / "s.h5").string();
  const CliResult r = run_cli("snapshots --case hertz-a --values 0.2,0.3,0.4 --jobs 2 --out " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(field_value(r.out, "solves"), "3");
  EXPECT_EQ(field_value(r.out, "failures"), "0");
  EXPECT_EQ(field_value(r.out, "iterations").rfind("min ", 0), 0u) << r.out;
  EXPECT_FALSE(field_value(r.out, "total time").empty()) << r.out;
  EXPECT_FALSE(field_value(r.out, "time per solve").empty()) << r.out;
  EXPECT_GT(fs::file_size(out), 10000u);
  EXPECT_EQ(entries(dir.path()), 1);  // no temporary file left behind
  // stderr is a file here, not a terminal: one progress line per value, no '\r'.
  EXPECT_EQ(count(r.err, "snapshot "), 3) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
}

TEST(CliSnapshots, QuietPrintsNoProgress) {
  contactrb::test::TempDir dir("snapshots_quiet");
  const CliResult r = run_cli("snapshots --case hertz-a --values 0.2 -q --out " + shell_quote((dir.path() / "s.h5").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(CliSnapshots, FailedSolvesExitNonZeroUnlessAllowed) {
  contactrb::test::TempDir dir("snapshots_fail");
  const std::string out = (dir.path() / "s.h5").string();
  const std::string args = "snapshots --case hertz-a --values 0.2,0.3 --max-iterations 1 -q --out " + shell_quote(out);
  const CliResult r = run_cli(args);
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_EQ(field_value(r.out, "failures"), "2");
  EXPECT_NE(r.err.find("contactrb: error: 2 of 2 solves failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("mu = 0.3: max_iterations"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(out));  // failures are recorded, not dropped

  fs::remove(out);
  const CliResult allowed = run_cli(args + " --allow-failures");
  EXPECT_EQ(allowed.exit_code, 0) << allowed.out << allowed.err;
  EXPECT_NE(allowed.err.find("contactrb: warning: 2 of 2 solves failed"), std::string::npos) << allowed.err;
  EXPECT_TRUE(fs::exists(out));
}

TEST(CliSnapshots, TomlCaseFileOverItsVerificationSet) {
  contactrb::test::TempDir dir("snapshots_toml");
  const std::string file = std::string(CONTACTRB_SOURCE_DIR) + "/examples/two-block-patch/case.toml";
  const CliResult r = run_cli("snapshots --case-file " + shell_quote(file) + " --set verification -q --out " +
                              shell_quote((dir.path() / "s.h5").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(field_value(r.out, "solves"), "4");
  EXPECT_EQ(field_value(r.out, "failures"), "0");
}

TEST(CliSnapshots, BadInputsGiveOneClearError) {
  contactrb::test::TempDir dir("snapshots_bad");
  const std::string out = " --out " + shell_quote((dir.path() / "s.h5").string());
  expect_user_error(run_cli("snapshots --case hertz-z" + out), "unknown case 'hertz-z'");
  expect_user_error(run_cli("snapshots --case hertz-a --jobs 0" + out), "--jobs");
  expect_user_error(run_cli("snapshots --case hertz-a --set nope" + out), "nope");
  expect_user_error(run_cli("snapshots --case hertz-a --values 0.1" + out), "outside");
  // A file where the directory of --out should be.
  { std::ofstream((dir.path() / "plain").string()) << "x"; }
  expect_user_error(run_cli("snapshots --case hertz-a --out " + shell_quote((dir.path() / "plain/dir/s.h5").string())),
                    "cannot create the directory of --out");
  std::filesystem::remove(dir.path() / "plain");
  expect_user_error(run_cli("snapshots --case-file " + shell_quote((dir.path() / "none.toml").string()) + out),
                    "none.toml");
  // Usage errors (CLI11): no case, two cases.
  EXPECT_NE(run_cli("snapshots" + out).exit_code, 0);
  EXPECT_NE(run_cli("snapshots --case hertz-a --case-file x.toml" + out).exit_code, 0);
  EXPECT_EQ(entries(dir.path()), 0);
}

// Progress lines print mu with at most six significant digits: hertz-b's training value
// 0.905 + 0.01 * 10.5 is 1.0100000000000002 in double precision and reads "mu = 1.01".
TEST(CliSnapshots, ProgressLinesPrintMuWithSixSignificantDigits) {
  contactrb::test::TempDir dir("snapshots_digits");
  const CliResult r = run_cli("snapshots --case hertz-b --values 1.0100000000000002 --out " +
                              shell_quote((dir.path() / "s.h5").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("mu = 1.01 "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("1.0100000000000002"), std::string::npos) << r.err;
}
