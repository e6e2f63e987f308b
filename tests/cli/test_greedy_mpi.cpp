// mpirun -np 2 contactrb offline --greedy (apps/contactrb/mpi_greedy.cpp): the ranks split the
// estimate sweep and a step's HF solves (rank 0 alone with one solve per step; --greedy-batch 2 on
// two ranks), yet the run selects the serial run's points and
// writes its files: greedy.csv equal but the timing columns, the selected snapshots equal but the
// timings, and every dataset of the model file equal byte for byte. A command that does not split
// its work (offline without --greedy) is refused with a clear message, not a hang. Skipped, with
// the reason, in a build without MPI (CONTACTRB_MPIEXEC empty).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "cli/mpi_runner.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "support/snapshot_fixtures.hpp"

using contactrb::test::CliResult;
using contactrb::test::count;
using contactrb::test::mpirun;
using contactrb::test::shell_quote;

namespace {

const std::string kGreedy = "offline --greedy --case hertz-a --greedy-tol 1e-6 --max-hf 4";


// greedy.csv as rows of cells, the timing columns (*_s) blanked.
std::vector<std::vector<std::string>> csv_without_timings(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> timing;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    if (rows.empty()) {
      for (const std::string& c : cells) timing.push_back(c.size() > 2 && c.compare(c.size() - 2, 2, "_s") == 0);
    } else {
      for (std::size_t k = 0; k < cells.size() && k < timing.size(); ++k) {
        if (timing[k]) cells[k] = "";
      }
    }
    rows.push_back(cells);
  }
  return rows;
}

// Every dataset of an HDF5 file: its path -> its bytes (native type; the files hold no
// variable-length data).
herr_t collect(hid_t obj, const char* name, const H5O_info_t* info, void* data) {
  if (info->type != H5O_TYPE_DATASET) return 0;
  auto& out = *static_cast<std::map<std::string, std::string>*>(data);
  const hid_t d = H5Dopen2(obj, name, H5P_DEFAULT);
  const hid_t type = H5Dget_type(d);
  const hid_t space = H5Dget_space(d);
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
  std::string bytes;
  EXPECT_EQ(H5Tdetect_class(type, H5T_VLEN), 0) << name;
  EXPECT_LE(H5Tis_variable_str(type), 0) << name;
  const hid_t native = H5Tget_native_type(type, H5T_DIR_ASCEND);
  bytes.resize(n * H5Tget_size(native));
  H5Dread(d, native, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data());
  H5Tclose(native);
  H5Sclose(space);
  H5Tclose(type);
  H5Dclose(d);
  out[name] = bytes;
  return 0;
}

std::map<std::string, std::string> datasets(const std::string& path) {
  std::map<std::string, std::string> out;
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << path;
  if (f < 0) return out;
  H5Ovisit2(f, H5_INDEX_NAME, H5_ITER_INC, collect, &out, H5O_INFO_BASIC);
  H5Fclose(f);
  return out;
}

// `command` serially, then under mpirun on 2 and 3 ranks: the same files (`steps` steps,
// `selected` snapshots).
void expect_ranks_write_the_serial_runs_files(const std::string& command, const std::string& name, std::size_t steps,
                                              std::size_t selected) {
  contactrb::test::TempDir dir(name);
  std::filesystem::create_directories(dir.path() / "serial");
  std::filesystem::create_directories(dir.path() / "mpi");
  const std::string serial_model = dir.file("serial/model.h5"), mpi_model = dir.file("mpi/model.h5");
  const CliResult serial = contactrb::test::run_cli(command + " -q --out " + shell_quote(serial_model));
  ASSERT_EQ(serial.exit_code, 0) << serial.out << serial.err;
  // 3 ranks: blocks of unequal size (31 training points: 11, 10, 10).
  for (int ranks : {2, 3}) {
    SCOPED_TRACE(std::to_string(ranks) + " ranks");
    const CliResult r = mpirun(ranks, command + " --out " + shell_quote(mpi_model));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find(std::to_string(ranks) + " MPI ranks"), std::string::npos) << r.out;
    // Rank 0 alone reports: one summary, one start line and one line per step.
    EXPECT_EQ(count(r.out, "wrote " + mpi_model), 1) << r.out;
    EXPECT_EQ(count(r.err, "greedy: start at mu = 0.3"), 1) << r.err;
    EXPECT_EQ(count(r.err, "greedy step "), static_cast<int>(steps)) << r.err;

    // The same steps: sizes, estimates bit for bit (17 digits), argmax, chosen points, true errors.
    const auto a = csv_without_timings(dir.file("serial/greedy.csv"));
    const auto b = csv_without_timings(dir.file("mpi/greedy.csv"));
    ASSERT_EQ(a.size(), steps + 1);  // header + steps
    EXPECT_EQ(a, b);
    // greedy.json the same but its times_s.
    const auto json = [&](const std::string& path) {
      std::ifstream in(path);
      nlohmann::json j = nlohmann::json::parse(in);
      j.erase("times_s");
      for (auto& step : j["steps"]) step.erase("times_s");
      return j;
    };
    const nlohmann::json ja = json(dir.file("serial/greedy.json"));
    EXPECT_EQ(ja["selected"].size(), selected);
    EXPECT_EQ(ja, json(dir.file("mpi/greedy.json")));
    // The same selected snapshots (all data but the timings).
    const auto sa = contactrb::io::read_snapshot_file(dir.file("serial/snapshots.h5"));
    const auto sb = contactrb::io::read_snapshot_file(dir.file("mpi/snapshots.h5"));
    ASSERT_EQ(sa.snapshots.size(), selected);
    contactrb::test::expect_same_data(sa, sb, false);
    // The model: every dataset byte for byte.
    const auto ma = datasets(serial_model), mb = datasets(mpi_model);
    ASSERT_GT(ma.size(), 10u);
    ASSERT_EQ(ma.size(), mb.size());
    for (const auto& [name, bytes] : ma) {
      ASSERT_TRUE(mb.count(name)) << name;
      EXPECT_TRUE(mb.at(name) == bytes) << name;
    }
  }
}

}  // namespace

// One HF solve per step: rank 0 solves, every rank gets the snapshot.
TEST(GreedyMpi, TwoRanksWriteTheSerialRunsFiles) {
  SKIP_WITHOUT_MPI();
  expect_ranks_write_the_serial_runs_files(kGreedy, "mpi_greedy", 4, 4);
}

// --greedy-batch 2: the step's two HF solves on ranks 0 and 1 (on 3 ranks, rank 2 has none),
// the budget of 4 caps the second batch at one solve: steps of 1, 3 then 4 snapshots.
TEST(GreedyMpi, BatchedHfSolvesAreSharedOutAndGiveTheSerialRunsFiles) {
  SKIP_WITHOUT_MPI();
  expect_ranks_write_the_serial_runs_files(kGreedy + " --greedy-batch 2", "mpi_greedy_batch", 3, 4);
}

// The HF solve at the start point fails (rank 0 solves it): every rank stops with the reason,
// no hang, no file.
TEST(GreedyMpi, FailedHfSolveEndsEveryRank) {
  SKIP_WITHOUT_MPI();
  contactrb::test::TempDir dir("mpi_greedy_hf_failed");
  const CliResult r = mpirun(2, kGreedy + " --max-iterations 1 -q --out " + shell_quote(dir.file("m.h5")));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("greedy: the HF solve at the start point mu = 0.3 failed (max_iterations"), std::string::npos)
      << r.err;
  for (const char* f : {"m.h5", "snapshots.h5", "greedy.csv", "greedy.json"}) {
    EXPECT_FALSE(std::filesystem::exists(dir.path() / f)) << f;
  }
}

TEST(GreedyMpi, OfflineWithoutGreedyIsRefused) {
  SKIP_WITHOUT_MPI();
  contactrb::test::TempDir dir("mpi_greedy_refused");
  const CliResult r = mpirun(2, "offline --case hertz-a --out " + shell_quote(dir.file("m.h5")));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("`contactrb offline` does not run under mpirun with several processes"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("offline --greedy"), std::string::npos) << r.err;  // says what does run
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "m.h5"));
}
