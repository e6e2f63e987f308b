// Output sets written as a whole (`offline`, `offline --greedy`, `report`): a failure half way
// leaves the files of the run before and no temporary; `offline --case` keeps its complete,
// sealed snapshots when the offline step after them fails. And the level and mesh a file records
// agree: a sealed file whose recorded level or stored mesh is not its case's is refused by every
// command that rebuilds the case from it (cases/recorded_mesh.hpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "support/file_bytes.hpp"
#include "cli_fixtures.hpp"
#include "cli_runner.hpp"
#include "support/temp_dir.hpp"
#include "contactrb/common/file_seal.hpp"
#include "contactrb/model/reconstruction.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/io/snapshot_file.hpp"

namespace fs = std::filesystem;
using contactrb::test::SmallDisk;
using contactrb::test::read_bytes;
using contactrb::test::write_bytes;
using contactrb::test::CliResult;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

namespace {

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

int error_lines(const std::string& err) {
  int n = 0;
  std::istringstream in(err);
  std::string line;
  while (std::getline(in, line)) n += line.rfind("contactrb: error: ", 0) == 0 ? 1 : 0;
  return n;
}

// Exit 1 and one error line holding `words`.
void expect_one_error(const CliResult& r, const std::string& words) {
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(error_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(words), std::string::npos) << "missing '" << words << "' in " << r.err;
}


// A small hertz-a snapshot file (stores its level-0 mesh) and its model, made once.
class CliOutputSets : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<contactrb::test::TempDir>("output_sets");
    snapshots_ = dir_->file("s.h5");
    model_ = dir_->file("model.h5");
    contactrb::test::make_small_hertz_model(snapshots_, model_);
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::unique_ptr<contactrb::test::TempDir> dir_;
  static std::string snapshots_, model_;
};
std::unique_ptr<contactrb::test::TempDir> CliOutputSets::dir_;
std::string CliOutputSets::snapshots_, CliOutputSets::model_;

// `offline --case` whose offline step is refused after the snapshots (an EIM tolerance above
// every value of kappa keeps no function): the snapshots are kept, complete and sealed (a second
// offline runs from them), the model and offline.json of the run before stay, nothing else.
TEST_F(CliOutputSets, OfflineCaseKeepsItsSnapshotsAndNothingElseWhenTheOfflineStepFails) {
  const fs::path d = dir_->path() / "kept";
  fs::create_directories(d);
  write_bytes(d / "model.h5", "the earlier model");
  write_bytes(d / "offline.json", "the earlier report");
  const std::string kept = (d / "snapshots.h5").string();
  const CliResult r = run_cli("offline --case hertz-a --values 0.2,0.3,0.4 -q --dual cpg --eps-eim-k 1e6 --out " +
                              shell_quote((d / "model.h5").string()));
  expect_one_error(r, "; no model written; the snapshots of this run are kept in " + kept);
  EXPECT_NE(r.err.find("eps"), std::string::npos) << r.err;  // the refused setting is named
  EXPECT_EQ(read_bytes(d / "model.h5"), "the earlier model");
  EXPECT_EQ(read_bytes(d / "offline.json"), "the earlier report");
  EXPECT_EQ(entries(d), (std::vector<std::string>{"model.h5", "offline.json", "snapshots.h5"}));
  EXPECT_EQ(contactrb::check_seal(kept), contactrb::SealState::Valid);
  const contactrb::io::SnapshotSet set = contactrb::io::read_snapshot_file(kept);
  ASSERT_EQ(set.snapshots.size(), 3u);
  EXPECT_EQ(set.num_failed(), 0);
  const CliResult resumed = run_cli("offline --snapshots " + shell_quote(kept) + " --out " + shell_quote(dir_->file("resumed.h5")));
  EXPECT_EQ(resumed.exit_code, 0) << resumed.out << resumed.err;
}

// A success writes the whole set, and no temporary stays.
TEST_F(CliOutputSets, OfflineCaseAndGreedyWriteEveryFile) {
  const fs::path d = dir_->path() / "whole";
  fs::create_directories(d / "greedy");
  const CliResult pod = run_cli("offline --case hertz-a --values 0.2,0.3,0.4 -q --out " + shell_quote((d / "m.h5").string()));
  ASSERT_EQ(pod.exit_code, 0) << pod.out << pod.err;
  EXPECT_EQ(entries(d), (std::vector<std::string>{"greedy", "m.h5", "offline.json", "snapshots.h5"}));
  const CliResult greedy = run_cli("offline --case hertz-a --greedy --values 0.2,0.3,0.4 --max-hf 2 -q --out " +
                                   shell_quote((d / "greedy" / "m.h5").string()));
  ASSERT_EQ(greedy.exit_code, 0) << greedy.out << greedy.err;
  EXPECT_EQ(entries(d / "greedy"),
            (std::vector<std::string>{"greedy.csv", "greedy.json", "m.h5", "snapshots.h5"}));
  for (const char* h5 : {"m.h5", "snapshots.h5"}) {
    EXPECT_EQ(contactrb::check_seal((d / "greedy" / h5).string()), contactrb::SealState::Valid) << h5;
  }
}

// A full disk after the snapshots (a tmpfs holding them and little more): the snapshots are
// kept, no model or offline.json appears, no temporary stays. `--greedy` on a disk with room for
// its snapshots only: none of its four files appears.
TEST_F(CliOutputSets, FullDiskAfterTheSnapshotsKeepsThemAlone) {
  const std::uintmax_t snapshot_bytes = [&] {
    const fs::path probe = dir_->path() / "probe";
    fs::create_directories(probe);
    const CliResult s = run_cli("snapshots --case hertz-a --values 0.2,0.3,0.4 -q --out " +
                                shell_quote((probe / "s.h5").string()));
    return s.exit_code == 0 ? fs::file_size(probe / "s.h5") : 0;
  }();
  ASSERT_GT(snapshot_bytes, 0u);
  // Room for the snapshots and 8 KiB: the model (mesh, bases, reconstruction) does not fit.
  const SmallDisk disk(dir_->path() / "after_snapshots", static_cast<long>(snapshot_bytes / 1024 + 12));
  if (!disk.mounted()) GTEST_SKIP() << "needs root to mount a tmpfs";
  const CliResult r = run_cli("offline --case hertz-a --values 0.2,0.3,0.4 -q --out " + shell_quote(disk.file("m.h5")));
  expect_one_error(r, "No space left on device");
  EXPECT_NE(r.err.find("the snapshots of this run are kept in " + disk.file("snapshots.h5")), std::string::npos) << r.err;
  EXPECT_EQ(entries(disk.file("")), std::vector<std::string>{"snapshots.h5"});
  EXPECT_EQ(contactrb::check_seal(disk.file("snapshots.h5")), contactrb::SealState::Valid);

  // --greedy with room for its snapshots (written first) and a little more.
  const std::string greedy = "offline --case hertz-a --greedy --values 0.2,0.3,0.4 --max-hf 2 -q --out ";
  const fs::path probe = dir_->path() / "greedy_probe";
  fs::create_directories(probe);
  ASSERT_EQ(run_cli(greedy + shell_quote((probe / "m.h5").string())).exit_code, 0);
  const SmallDisk full(dir_->path() / "greedy_full", static_cast<long>(fs::file_size(probe / "snapshots.h5") / 1024 + 12));
  ASSERT_TRUE(full.mounted());
  const CliResult g = run_cli(greedy + shell_quote(full.file("m.h5")));
  expect_one_error(g, "No space left on device");
  EXPECT_TRUE(entries(full.file("")).empty()) << g.err;
}

std::string report_args(const std::string& out) {
  return "report --case hertz-a --training-values 0.2,0.4 --max-verification 0 --profiles 0 --deformed 0 "
         "--comparisons 0 --repeats 1 -q --out " +
         shell_quote(out);
}

// A target of the set that cannot be replaced (a directory where a CSV goes): no file of the run
// appears, the earlier report.md stays, the staging directory is removed.
TEST_F(CliOutputSets, ReportWithAnUnwritableTargetLeavesTheEarlierFiles) {
  const fs::path out = dir_->path() / "report_blocked";
  fs::create_directories(out / "sizes.csv");
  write_bytes(out / "report.md", "the earlier report");
  const CliResult r = run_cli(report_args(out.string()) + " --no-plots");
  expect_one_error(r, "sizes.csv' is a directory");
  EXPECT_EQ(read_bytes(out / "report.md"), "the earlier report");
  EXPECT_EQ(entries(out), (std::vector<std::string>{"report.md", "sizes.csv"}));
}

// A failing plotting script: the tables, study.json and report.md of the run are written (the
// message says so), no figure, and the figures of an earlier run are removed.
TEST_F(CliOutputSets, ReportWhosePlotsFailKeepsTheTablesAndDropsEarlierFigures) {
  const fs::path out = dir_->path() / "report_noplot";
  fs::create_directories(out);
  write_bytes(out / "eim_error.png", "an earlier figure");
  write_bytes(out / "eim_error.pdf", "an earlier figure");
  const CliResult r = run_cli(report_args(out.string()), "", "CONTACTRB_PYTHON=/bin/false");
  expect_one_error(r, "the CSV files and report.md (without figures) are in " + out.string());
  const std::vector<std::string> names = entries(out);
  for (const char* f : {"study.json", "report.md", "sizes.csv", "errors_training.csv"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), f), names.end()) << f;
  }
  for (const std::string& f : names) {
    EXPECT_EQ(f.find(".png"), std::string::npos) << f;
    EXPECT_EQ(f.find(".pdf"), std::string::npos) << f;
    EXPECT_EQ(f.find("contactrb-tmp"), std::string::npos) << f;
  }
  const std::string md = read_bytes(out / "report.md");
  EXPECT_NE(md.find("Case `hertz-a`"), std::string::npos) << md;
  EXPECT_EQ(md.find(".png"), std::string::npos) << md;
}

// A full disk while the report is written: none of its files appears. A success (--no-plots)
// writes every file study.json lists, and report.md, and no temporary.
TEST_F(CliOutputSets, ReportIsWrittenWhole) {
  const fs::path out = dir_->path() / "report_ok";
  const CliResult ok = run_cli(report_args(out.string()) + " --no-plots");
  ASSERT_EQ(ok.exit_code, 0) << ok.out << ok.err;
  const std::string study = read_bytes(out / "study.json");
  std::uintmax_t bytes = 0;
  for (const std::string& f : entries(out)) {
    EXPECT_EQ(f.find("contactrb-tmp"), std::string::npos) << f;
    EXPECT_TRUE(f == "report.md" || study.find('"' + f + '"') != std::string::npos) << f << " not in study.json";
    bytes += fs::file_size(out / f);
  }
  EXPECT_GE(entries(out).size(), 9u);

  const SmallDisk disk(dir_->path() / "report_full", static_cast<long>(bytes / 2048));
  if (!disk.mounted()) GTEST_SKIP() << "needs root to mount a tmpfs";
  const CliResult r = run_cli(report_args(disk.file("r")) + " --no-plots");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(error_lines(r.err), 1) << r.err;
  EXPECT_TRUE(entries(disk.file("r")).empty()) << r.err;
}

}  // namespace

// --- Level and mesh: sealed files whose record disagrees with what they hold, written by the
// library's own writers (valid checksums and seal), as a crafted file would be.

namespace {

std::string crafted_snapshots(const std::string& source, const std::string& path, int level, double scale) {
  contactrb::io::SnapshotSet set = contactrb::io::read_snapshot_file(source);
  set.level = level;
  for (Eigen::Vector2d& p : set.mesh.nodes) p *= scale;
  contactrb::io::write_snapshot_file(set, path);
  return path;
}

std::string crafted_model(const std::string& source, const std::string& path, int level, double scale) {
  contactrb::model::ReducedModel model = contactrb::io::read_reduced_model_file(source);
  contactrb::model::ReducedReconstruction rec = contactrb::io::read_reconstruction(source);
  model.level = level;
  for (Eigen::Vector2d& p : rec.mesh.nodes) p *= scale;
  contactrb::io::write_reduced_model_file(model, rec, path);
  return path;
}

}  // namespace

// `offline --snapshots`: a level-3 record over the stored level-0 mesh (700 nodes) is refused
// before a mesh of level 2 or 3 is built; so are the mesh scaled by 2 at its true level and a
// level-2 set recorded as level 0.
TEST_F(CliOutputSets, OfflineRefusesSnapshotsWhoseLevelOrMeshIsNotTheirCase) {
  const std::string level3 = crafted_snapshots(snapshots_, dir_->file("level3.h5"), 3, 1.0);
  ASSERT_EQ(contactrb::check_seal(level3), contactrb::SealState::Valid);
  const CliResult r = run_cli("offline --snapshots " + shell_quote(level3) + " --out " + shell_quote(dir_->file("m3.h5")));
  expect_one_error(r, "file '" + level3 + "' records level 3 but holds a mesh of 700 nodes; case 'hertz-a' at level 1 "
                      "already has ");
  EXPECT_NE(r.err.find(" nodes: the file is inconsistent"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_->file("m3.h5")));

  const std::string scaled = crafted_snapshots(snapshots_, dir_->file("scaled.h5"), 0, 2.0);
  const CliResult s = run_cli("offline --snapshots " + shell_quote(scaled) + " --out " + shell_quote(dir_->file("m2.h5")));
  expect_one_error(s, "file '" + scaled + "' holds a mesh spanning [");
  EXPECT_NE(s.err.find("; case 'hertz-a' at level 0 spans ["), std::string::npos) << s.err;
  EXPECT_FALSE(fs::exists(dir_->file("m2.h5")));

  // Level-2 snapshots (mesh and arrays of 1652 nodes) recorded as level 0.
  const std::string fine = dir_->file("fine.h5");
  const CliResult f = run_cli("snapshots --case hertz-a --values 0.2,0.3 --level 2 -q --out " + shell_quote(fine));
  ASSERT_EQ(f.exit_code, 0) << f.out << f.err;
  const std::string level0 = crafted_snapshots(fine, dir_->file("level0.h5"), 0, 1.0);
  const CliResult z = run_cli("offline --snapshots " + shell_quote(level0) + " --out " + shell_quote(dir_->file("m0.h5")));
  expect_one_error(z, "file '" + level0 + "' records level 0 but holds a mesh of 1652 nodes; case 'hertz-a' at level 0 "
                      "has 700 nodes: the file is inconsistent");
  EXPECT_FALSE(fs::exists(dir_->file("m0.h5")));
}

// `evaluate` and `online --out` rebuild the case from a model's record: the same checks.
TEST_F(CliOutputSets, EvaluateAndOnlineFieldsRefuseAModelWhoseLevelOrMeshIsNotItsCase) {
  const std::string level2 = crafted_model(model_, dir_->file("model_level2.h5"), 2, 1.0);
  const std::string scaled = crafted_model(model_, dir_->file("model_scaled.h5"), 0, 2.0);
  ASSERT_EQ(contactrb::check_seal(level2), contactrb::SealState::Valid);
  const std::string level_words = "file '" + level2 + "' records level 2 but holds a mesh of 700 nodes; case 'hertz-a' at level 1 already has ";
  const std::string box_words = "file '" + scaled + "' holds a mesh spanning [";
  for (const auto& [model, words] : {std::pair{level2, level_words}, std::pair{scaled, box_words}}) {
    SCOPED_TRACE(model);
    const fs::path eval = dir_->path() / ("eval_" + fs::path(model).stem().string());
    const CliResult e = run_cli("evaluate --model " + shell_quote(model) + " --set training -q --out " + shell_quote(eval.string()));
    expect_one_error(e, words);
    EXPECT_FALSE(fs::exists(eval / "evaluation.json"));
    const fs::path fields = dir_->path() / ("fields_" + fs::path(model).stem().string());
    const CliResult o = run_cli("online --model " + shell_quote(model) + " --mu 0.3 --out " + shell_quote(fields.string()));
    expect_one_error(o, words);
    EXPECT_FALSE(fs::exists(fields / "solution.vtu"));
  }
  // The model itself is fine: the same commands accept it.
  const CliResult ok = run_cli("online --model " + shell_quote(model_) + " --mu 0.3 --out " + shell_quote(dir_->file("fields_ok")));
  EXPECT_EQ(ok.exit_code, 0) << ok.out << ok.err;
}
