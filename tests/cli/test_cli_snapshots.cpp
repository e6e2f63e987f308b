// contactrb snapshots: the summary, the exit codes of failed solves (with and without
// --allow-failures), progress lines when stderr is not a terminal, and usage errors.
// Small sets (hertz-a at level 0, a few values) keep it fast.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.hpp"
#include "contactrb/io/snapshot_file.hpp"
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
  expect_user_error(run_cli("snapshots --case hertz-a --solver gauss-seidel" + out),
                    "--solver: unknown HF solver 'gauss-seidel' (expected newton or kacanov)");
  expect_user_error(run_cli("snapshots --case hertz-a --solver ''" + out), "--solver: unknown HF solver ''");
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

// --solver picks the HF method of every solve; the summary names it and the file records it.
// The two methods' answers agree to Kacanov's tolerance eps_KA = 1e-3 (Newton: KKT 1e-10).
TEST(CliSnapshots, SolverOptionChoosesAndRecordsTheMethod) {
  contactrb::test::TempDir dir("snapshots_solver");
  const std::string values = " --values 0.2,0.3,0.4 -q --out ";
  const std::string newton = (dir.path() / "n.h5").string();
  const std::string kacanov = (dir.path() / "k.h5").string();
  const CliResult n = run_cli("snapshots --case hertz-a --solver newton" + values + shell_quote(newton));
  ASSERT_EQ(n.exit_code, 0) << n.out << n.err;
  EXPECT_EQ(field_value(n.out, "solver"), "newton") << n.out;
  const CliResult k = run_cli("snapshots --case hertz-a" + values + shell_quote(kacanov));  // 2D default
  ASSERT_EQ(k.exit_code, 0) << k.out << k.err;
  EXPECT_EQ(field_value(k.out, "solver"), "kacanov") << k.out;
  const contactrb::io::SnapshotSet a = contactrb::io::read_snapshot_file(newton);
  const contactrb::io::SnapshotSet b = contactrb::io::read_snapshot_file(kacanov);
  EXPECT_EQ(a.solver, "newton");
  EXPECT_EQ(b.solver, "kacanov");
  ASSERT_EQ(a.snapshots.size(), 3u);
  ASSERT_EQ(b.snapshots.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LE(a.snapshots[i].iterations, 12);
    EXPECT_GE(b.snapshots[i].iterations, 13);  // Kacanov: 21-25 on hertz-a
    const double du = (a.snapshots[i].u - b.snapshots[i].u).lpNorm<Eigen::Infinity>() /
                      a.snapshots[i].u.lpNorm<Eigen::Infinity>();
    const double dl = (a.snapshots[i].lambda - b.snapshots[i].lambda).lpNorm<Eigen::Infinity>() /
                      a.snapshots[i].lambda.lpNorm<Eigen::Infinity>();
    EXPECT_LT(du, 1e-2) << i;
    EXPECT_LT(dl, 1e-2) << i;
  }
}

// A bad --solver is one clear error, the same words, in every command that solves HF; nothing
// is written.
TEST(CliSnapshots, BadSolverValuesAreOneClearErrorInEveryCommand) {
  contactrb::test::TempDir dir("solver_bad");
  const std::string out = shell_quote((dir.path() / "o").string());
  for (const std::string& command :
       {"snapshots --case hertz-a --out " + out + ".h5", "offline --case hertz-a --out " + out + ".h5",
        "offline --greedy --case hertz-a --out " + out + ".h5", "report --case hertz-a --no-plots --out " + out,
        "solve --case hertz-a --mu 0.3 --out " + out}) {
    const CliResult r = run_cli(command + " --solver Newton");
    expect_user_error(r, "--solver: unknown HF solver 'Newton' (expected newton or kacanov)");
    EXPECT_EQ(count(r.err, "\n"), 1) << command << "\n" << r.err;
  }
  EXPECT_EQ(entries(dir.path()), 0);
}
