// contactrb offline --greedy: a short greedy on hertz-a (budget 4) writes the model, the selected
// snapshots, greedy.csv and greedy.json; the model answers `contactrb online`; the snapshot file
// holds exactly the selected points; bad input (budget < 1, tolerance <= 0 or NaN, --greedy with
// --snapshots) is one clear error each and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
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

int count_lines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) ++n;
  return n;
}

TEST(CliOfflineGreedy, WritesTheModelTheSnapshotsAndTheStepTable) {
  const contactrb::test::TempDir dir("offline_greedy");
  const std::string model = dir.file("model.h5");
  const CliResult r = run_cli("offline --greedy --case hertz-a --greedy-tol 1e-6 --max-hf 4 -j 2 -q --out " +
                              shell_quote(model));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(field_value(r.out, "status").rfind("budget after 4 steps, 4 HF solves", 0), 0u) << r.out;
  EXPECT_NE(field_value(r.out, "max relative estimate").find("NOT reached"), std::string::npos) << r.out;
  for (const char* f : {"model.h5", "snapshots.h5", "greedy.csv", "greedy.json"}) {
    EXPECT_TRUE(fs::is_regular_file(dir.path() / f)) << f;
  }
  EXPECT_EQ(count_lines(dir.file("greedy.csv")), 1 + 4);  // header + one line per step
  std::ifstream in(dir.file("greedy.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["status"], "budget");
  EXPECT_EQ(j["hf_solves"], 4);
  ASSERT_EQ(j["selected"].size(), 4u);
  EXPECT_NEAR(j["start"].get<double>(), 0.3, 1e-12);  // hertz-a's training set: the centre value
  ASSERT_EQ(j["steps"].size(), 4u);
  EXPECT_EQ(j["steps"][3]["chosen_mu"], nullptr);  // the last step stops, no HF solve
  EXPECT_GT(j["steps"][0]["max_estimate"].get<double>(), j["steps"][3]["max_estimate"].get<double>());
  // The snapshot file holds the 4 selected points (the same values).
  const CliResult o = run_cli("online --model " + shell_quote(model) + " --mu " +
                              std::to_string(j["selected"][1].get<double>()));
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  const CliResult again = run_cli("offline --snapshots " + shell_quote(dir.file("snapshots.h5")) + " --out " +
                                  shell_quote(dir.file("pod.h5")));
  ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
  EXPECT_NE(again.out.find("4 snapshots (set greedy)"), std::string::npos) << again.out;
}

// --solver reaches the HF solves of the greedy and of `offline --case`: snapshots.h5 records the
// method and its solves took Newton's iteration counts (hertz-a: 4-8; Kacanov 21-25); offline.json
// names it.
TEST(CliOfflineGreedy, SolverOptionReachesTheHFSolves) {
  const contactrb::test::TempDir dir("offline_solver");
  for (const char* d : {"g", "p", "x"}) fs::create_directories(dir.path() / d);
  const CliResult g = run_cli("offline --greedy --case hertz-a --greedy-tol 1e-6 --max-hf 2 --solver newton -q --out " +
                              shell_quote(dir.file("g/model.h5")));
  ASSERT_EQ(g.exit_code, 0) << g.out << g.err;
  const contactrb::io::SnapshotSet greedy = contactrb::io::read_snapshot_file(dir.file("g/snapshots.h5"));
  EXPECT_EQ(greedy.solver, "newton");
  ASSERT_EQ(greedy.snapshots.size(), 2u);
  for (const auto& s : greedy.snapshots) EXPECT_LE(s.iterations, 12);
  const CliResult p = run_cli("offline --case hertz-a --values 0.2,0.3,0.4 --solver newton -q --out " +
                              shell_quote(dir.file("p/model.h5")));
  ASSERT_EQ(p.exit_code, 0) << p.out << p.err;
  const contactrb::io::SnapshotSet pod = contactrb::io::read_snapshot_file(dir.file("p/snapshots.h5"));
  EXPECT_EQ(pod.solver, "newton");
  for (const auto& s : pod.snapshots) EXPECT_LE(s.iterations, 12);
  std::ifstream in(dir.file("p/offline.json"));
  EXPECT_EQ(nlohmann::json::parse(in)["snapshot_solver"], "newton");
  // --solver belongs to the snapshots computed here: with --snapshots it is a usage error.
  const CliResult x = run_cli("offline --snapshots " + shell_quote(dir.file("p/snapshots.h5")) +
                              " --solver newton --out " + shell_quote(dir.file("x/model.h5")));
  EXPECT_NE(x.exit_code, 0);
  EXPECT_NE(x.err.find("--solver excludes --snapshots"), std::string::npos) << x.err;
}

TEST(CliOfflineGreedy, BadInputIsOneClearError) {
  const contactrb::test::TempDir dir("offline_greedy_bad");
  const std::string out = shell_quote(dir.file("model.h5"));
  const auto user_error = [&](const std::string& args, const std::string& words, int code = 1) {
    const CliResult r = run_cli("offline --greedy --case hertz-a -q " + args + " --out " + out);
    EXPECT_EQ(r.exit_code, code) << args << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "model.h5")) << args;
    EXPECT_FALSE(fs::exists(dir.path() / "greedy.csv")) << args;
  };
  user_error("--max-hf 0", "--max-hf must be >= 1");
  user_error("--max-hf -2", "--max-hf must be >= 1");
  user_error("--greedy-tol 0", "--greedy-tol must be a finite number > 0");
  user_error("--greedy-tol nan", "--greedy-tol must be a finite number > 0");
  user_error("--greedy-tol -1e-3", "--greedy-tol must be a finite number > 0");
  user_error("--set nosuchset", "nosuchset");
  user_error("--greedy-batch 0", "--greedy-batch must be >= 1");
  user_error("--solver qr", "--solver: unknown HF solver 'qr' (expected newton or kacanov)");
  // Greedy options without --greedy, and --greedy with a snapshot file: usage errors (CLI11).
  const CliResult a = run_cli("offline --case hertz-a --max-hf 3 --out " + out);
  EXPECT_NE(a.exit_code, 0);
  EXPECT_NE(a.err.find("--max-hf requires --greedy"), std::string::npos) << a.err;
  const CliResult c = run_cli("offline --case hertz-a --greedy-batch 2 --out " + out);
  EXPECT_NE(c.exit_code, 0);
  EXPECT_NE(c.err.find("--greedy-batch requires --greedy"), std::string::npos) << c.err;
  const CliResult b = run_cli("offline --greedy --snapshots x.h5 --out " + out);
  EXPECT_NE(b.exit_code, 0);
  EXPECT_NE(b.err.find("--greedy excludes --snapshots"), std::string::npos) << b.err;
}

}  // namespace
