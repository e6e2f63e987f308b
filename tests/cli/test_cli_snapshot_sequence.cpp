// --sequence K in the commands that solve HF snapshots or references (snapshots, offline --case,
// evaluate; docs/solvers.md, "Grid sequencing"): the cold solves start from the coarse levels'
// solution, with the answers of unsequenced solves to Newton's tolerance (KKT residual 1e-10) and
// fewer iterations; a bad value is one clear error in every command. hertz-a level 2 (coarse
// level 0), three values of mu.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::io::SnapshotSet;
using contactrb::test::CliResult;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;
using nlohmann::json;

namespace {

const std::string kRun = " --case hertz-a --level 2 --solver newton --values 0.2,0.3,0.4 -q";

int total_iterations(const SnapshotSet& s) {
  int n = 0;
  for (const auto& snap : s.snapshots) n += snap.iterations;
  return n;
}

json read_json(const fs::path& path) {
  std::ifstream in(path);
  return json::parse(in);
}

TEST(CliSequence, SnapshotsSequenceTheColdSolvesWithTheSameAnswers) {
  contactrb::test::TempDir dir("cli_sequence");
  const std::string plain = dir.file("plain.h5"), sequenced = dir.file("sequenced.h5");
  const CliResult a = run_cli("snapshots" + kRun + " --warm-start off --sequence 0 --out " + shell_quote(plain));
  ASSERT_EQ(a.exit_code, 0) << a.out << a.err;
  EXPECT_EQ(a.out.find("grid sequencing"), std::string::npos) << a.out;
  const CliResult b = run_cli("snapshots" + kRun + " --warm-start off --sequence 1 --out " + shell_quote(sequenced));
  ASSERT_EQ(b.exit_code, 0) << b.out << b.err;
  EXPECT_NE(b.out.find("grid sequencing: levels 0 (the solves without a warm start)"), std::string::npos) << b.out;
  const SnapshotSet p = contactrb::io::read_snapshot_file(plain);
  const SnapshotSet s = contactrb::io::read_snapshot_file(sequenced);
  ASSERT_EQ(p.snapshots.size(), 3u);
  ASSERT_EQ(s.snapshots.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(p.snapshots[i].converged && s.snapshots[i].converged) << i;
    EXPECT_LT((s.snapshots[i].u - p.snapshots[i].u).lpNorm<Eigen::Infinity>(),
              1e-8 * p.snapshots[i].u.lpNorm<Eigen::Infinity>())
        << i;
    EXPECT_LT((s.snapshots[i].lambda - p.snapshots[i].lambda).lpNorm<Eigen::Infinity>(),
              1e-6 * p.snapshots[i].lambda.lpNorm<Eigen::Infinity>())
        << i;
  }
  EXPECT_LT(total_iterations(s), total_iterations(p));

  // offline --case passes --sequence to its snapshots: the file next to the model is the one of
  // `snapshots` with the same options (warm start automatic: on with Newton), bit for bit.
  const std::string warm = dir.file("warm.h5");
  ASSERT_EQ(run_cli("snapshots" + kRun + " --sequence 1 --out " + shell_quote(warm)).exit_code, 0);
  const CliResult o = run_cli("offline" + kRun + " --sequence 1 --out " + shell_quote(dir.file("m/model.h5")));
  ASSERT_EQ(o.exit_code, 0) << o.out << o.err;
  const SnapshotSet w = contactrb::io::read_snapshot_file(warm);
  const SnapshotSet m = contactrb::io::read_snapshot_file(dir.file("m/snapshots.h5"));
  ASSERT_EQ(w.snapshots.size(), m.snapshots.size());
  for (std::size_t i = 0; i < w.snapshots.size(); ++i) {
    EXPECT_EQ(w.snapshots[i].iterations, m.snapshots[i].iterations) << i;
    EXPECT_EQ(w.snapshots[i].u, m.snapshots[i].u) << i;
  }
  // The first point (the first wave, cold) started from the coarse level, as in the cold run.
  EXPECT_EQ(w.snapshots[0].u, s.snapshots[0].u);

  // evaluate: the sequenced HF reference gives the errors of the unsequenced one (to Newton's
  // tolerance) and says so in evaluation.json and on stdout.
  const std::string model = " --model " + shell_quote(dir.file("m/model.h5")) + " --set training --repeats 1 -q";
  const CliResult e0 = run_cli("evaluate" + model + " --sequence 0 --out " + shell_quote(dir.file("e0")));
  ASSERT_EQ(e0.exit_code, 0) << e0.out << e0.err;
  const CliResult e1 = run_cli("evaluate" + model + " --sequence 1 --out " + shell_quote(dir.file("e1")));
  ASSERT_EQ(e1.exit_code, 0) << e1.out << e1.err;
  EXPECT_NE(e1.out.find("HF reference newton, grid sequencing from levels 0 (speed-ups against it)"), std::string::npos)
      << e1.out;
  const json j0 = read_json(dir.file("e0/evaluation.json"));
  const json j1 = read_json(dir.file("e1/evaluation.json"));
  EXPECT_EQ(j0.at("hf_sequence"), json::array());
  EXPECT_EQ(j1.at("hf_sequence"), json::array({0}));
  EXPECT_EQ(j1.at("summary").at("count"), 31);
  for (const char* key : {"e_displ", "e_press"}) {
    const double x0 = j0.at("summary").at(key).at("max").get<double>();
    const double x1 = j1.at("summary").at(key).at("max").get<double>();
    EXPECT_GT(x0, 0.0) << key;
    EXPECT_NEAR(x1, x0, 1e-6 * x0) << key;
  }
}

// A bad --sequence is one clear error, the same words, in every command that solves HF; nothing
// is written.
TEST(CliSequence, BadValuesAreOneClearErrorInEveryCommand) {
  contactrb::test::TempDir dir("sequence_bad");
  const std::string out = shell_quote((dir.path() / "o").string());
  for (const std::string& command :
       {"snapshots --case hertz-a --out " + out + ".h5", "offline --case hertz-a --out " + out + ".h5",
        "offline --greedy --case hertz-a --out " + out + ".h5", "report --case hertz-a --no-plots --out " + out,
        "evaluate --model " + shell_quote(dir.file("none.h5")) + " --out " + out,
        "solve --case hertz-a --mu 0.3 --out " + out}) {
    const CliResult r = run_cli(command + " --sequence -2");
    contactrb::test::expect_user_error(r, "--sequence must be >= 0, or -1 for automatic (got -2)");
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << command << "\n" << r.err;
  }
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 0);
}

}  // namespace
