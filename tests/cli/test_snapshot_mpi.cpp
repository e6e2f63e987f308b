// mpirun -np K contactrb snapshots (apps/contactrb/mpi_snapshots.cpp): the gathered file holds
// the serial file's data bit for bit (all but the timings), rank 0 reports the progress, and a
// value that does not converge is reported with its mu (exit 3), not a hang. Skipped, with the
// reason, in a build without MPI (CONTACTRB_MPIEXEC empty).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_runner.hpp"
#include "cli/mpi_runner.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "support/snapshot_fixtures.hpp"

using contactrb::test::CliResult;
using contactrb::test::count;
using contactrb::test::mpirun;
using contactrb::test::shell_quote;

namespace {

const std::string kValues = "--case hertz-a --values 0.2,0.25,0.3,0.35,0.4";

}  // namespace

TEST(SnapshotMpi, RanksGatherTheSerialFile) {
  SKIP_WITHOUT_MPI();
  contactrb::test::TempDir dir("mpi_snapshots");
  const CliResult serial = contactrb::test::run_cli("snapshots " + kValues + " -q --out " + shell_quote(dir.file("serial.h5")));
  ASSERT_EQ(serial.exit_code, 0) << serial.out << serial.err;
  const auto reference = contactrb::io::read_snapshot_file(dir.file("serial.h5"));
  for (int ranks : {1, 2, 3}) {
    SCOPED_TRACE(std::to_string(ranks) + " ranks");
    const std::string out = dir.file("mpi" + std::to_string(ranks) + ".h5");
    const CliResult r = mpirun(ranks, "snapshots " + kValues + " --out " + shell_quote(out));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    // One process has nothing to share: `mpirun -np 1` runs as a plain start.
    EXPECT_NE(r.out.find(ranks == 1 ? std::string(" 1 job\n") : std::to_string(ranks) + " MPI ranks"), std::string::npos)
        << r.out;
    EXPECT_EQ(count(r.out, "wrote "), 1) << r.out;  // rank 0 alone reports
    EXPECT_EQ(count(r.err, "snapshot "), 5) << r.err;  // one progress line per value
    const auto gathered = contactrb::io::read_snapshot_file(out);
    contactrb::test::expect_same_data(reference, gathered, false);
  }
  // Without the work during MPI_Init (CONTACTRB_MPI_INIT_OVERLAP=0) each rank solves its first
  // value after it: the same file.
  const CliResult r = mpirun(2, "snapshots " + kValues + " -q --out " + shell_quote(dir.file("plain.h5")),
                             "CONTACTRB_MPI_INIT_OVERLAP=0");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  contactrb::test::expect_same_data(reference, contactrb::io::read_snapshot_file(dir.file("plain.h5")), false);
}

// A 3D case takes the same path: the gathered patch-3d file is the serial one.
TEST(SnapshotMpi, RanksGatherTheSerialFileOfA3dCase) {
  SKIP_WITHOUT_MPI();
  contactrb::test::TempDir dir("mpi_snapshots_3d");
  const std::string values = "--case patch-3d --values 0.01,0.015,0.02 -q";
  const CliResult serial = contactrb::test::run_cli("snapshots " + values + " --out " + shell_quote(dir.file("serial.h5")));
  ASSERT_EQ(serial.exit_code, 0) << serial.out << serial.err;
  const auto reference = contactrb::io::read_snapshot_file(dir.file("serial.h5"));
  EXPECT_EQ(reference.dimension, 3);
  const CliResult r = mpirun(2, "snapshots " + values + " --out " + shell_quote(dir.file("mpi.h5")));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("case patch-3d (3D)"), std::string::npos) << r.out;
  contactrb::test::expect_same_data(reference, contactrb::io::read_snapshot_file(dir.file("mpi.h5")), false);
}

// The warm-start schedule (--warm-start on): rank 0 hands out each wave's values with the
// snapshot each starts from; the gathered file is the serial warm-started file. The warm start
// is checked to be taken: the iteration counts differ from the cold run's.
TEST(SnapshotMpi, WarmStartedRanksGatherTheSerialFile) {
  SKIP_WITHOUT_MPI();
  contactrb::test::TempDir dir("mpi_warm");
  const std::string values = "--case hertz-a --values 0.2,0.22,0.25,0.28,0.3,0.33,0.35,0.4";
  const CliResult cold = contactrb::test::run_cli("snapshots " + values + " -q --out " + shell_quote(dir.file("cold.h5")));
  ASSERT_EQ(cold.exit_code, 0) << cold.out << cold.err;
  const CliResult serial = contactrb::test::run_cli("snapshots " + values + " --warm-start on -q --out " +
                                                    shell_quote(dir.file("serial.h5")));
  ASSERT_EQ(serial.exit_code, 0) << serial.out << serial.err;
  const auto cold_set = contactrb::io::read_snapshot_file(dir.file("cold.h5"));
  const auto reference = contactrb::io::read_snapshot_file(dir.file("serial.h5"));
  int fewer = 0;
  for (std::size_t i = 0; i < reference.snapshots.size(); ++i) {
    fewer += reference.snapshots[i].iterations < cold_set.snapshots[i].iterations ? 1 : 0;
  }
  EXPECT_GT(fewer, 0) << "no value took fewer iterations warm-started: the warm start was not taken";
  for (int ranks : {2, 3}) {
    SCOPED_TRACE(std::to_string(ranks) + " ranks");
    const std::string out = dir.file("mpi" + std::to_string(ranks) + ".h5");
    const CliResult r = mpirun(ranks, "snapshots " + values + " --warm-start on -q --out " + shell_quote(out));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    contactrb::test::expect_same_data(reference, contactrb::io::read_snapshot_file(out), false);
  }
  // A part has not the other parts' values to start from.
  const CliResult part = contactrb::test::run_cli("snapshots " + values + " --warm-start on --part 1/2 -q --out " +
                                                  shell_quote(dir.file("part.h5")));
  EXPECT_EQ(part.exit_code, 1) << part.out << part.err;
  EXPECT_NE(part.err.find("--warm-start on: a part (--part) is solved cold"), std::string::npos) << part.err;
}

// Each rank solves its first value (the rank-th of the set) while MPI_Init waits, before any
// message (mpi_snapshots.hpp, first_task): with more ranks than values, the ranks without one
// ask the coordinator and get none; the file is still the serial one.
// Grid sequencing (--sequence 1 on hertz-a level 2, Newton): every rank builds the same coarse
// mesh before its solves; the gathered file is the serial one, warm-started (the first wave
// sequenced) or cold (every value sequenced).
TEST(SnapshotMpi, SequencedRanksGatherTheSerialFile) {
  SKIP_WITHOUT_MPI();
  contactrb::test::TempDir dir("mpi_sequence");
  const std::string values = "--case hertz-a --level 2 --solver newton --values 0.2,0.25,0.3,0.35,0.4 --sequence 1 -q";
  for (const std::string warm : {"on", "off"}) {
    SCOPED_TRACE("--warm-start " + warm);
    const std::string run = "snapshots " + values + " --warm-start " + warm;
    const CliResult serial = contactrb::test::run_cli(run + " --out " + shell_quote(dir.file("serial.h5")));
    ASSERT_EQ(serial.exit_code, 0) << serial.out << serial.err;
    EXPECT_NE(serial.out.find("grid sequencing: levels 0"), std::string::npos) << serial.out;
    const CliResult r = mpirun(2, run + " --out " + shell_quote(dir.file("mpi.h5")));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    contactrb::test::expect_same_data(contactrb::io::read_snapshot_file(dir.file("serial.h5")),
                                      contactrb::io::read_snapshot_file(dir.file("mpi.h5")), false);
  }
}

TEST(SnapshotMpi, MoreRanksThanValuesGatherTheSerialFile) {
  SKIP_WITHOUT_MPI();
  contactrb::test::TempDir dir("mpi_few");
  const std::string values = "--case hertz-a --values 0.2,0.3";
  const CliResult serial = contactrb::test::run_cli("snapshots " + values + " -q --out " + shell_quote(dir.file("serial.h5")));
  ASSERT_EQ(serial.exit_code, 0) << serial.out << serial.err;
  const CliResult r = mpirun(3, "snapshots " + values + " --out " + shell_quote(dir.file("mpi.h5")));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("3 MPI ranks"), std::string::npos) << r.out;
  EXPECT_EQ(count(r.err, "snapshot "), 2) << r.err;  // each value reported once, by rank 0
  contactrb::test::expect_same_data(contactrb::io::read_snapshot_file(dir.file("serial.h5")),
                                    contactrb::io::read_snapshot_file(dir.file("mpi.h5")), false);
}

TEST(SnapshotMpi, ValueThatDoesNotConvergeIsNamed) {
  SKIP_WITHOUT_MPI();
  contactrb::test::TempDir dir("mpi_fail");
  const CliResult r = mpirun(2, "snapshots " + kValues + " --max-iterations 1 -q --out " + shell_quote(dir.file("s.h5")));
  EXPECT_NE(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.exit_code, 124) << "timed out: a hang";
  EXPECT_NE(r.err.find("5 of 5 solves failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("mu = 0.35: max_iterations"), std::string::npos) << r.err;
  const auto set = contactrb::io::read_snapshot_file(dir.file("s.h5"));  // recorded, not dropped
  EXPECT_EQ(set.num_failed(), 5);
}

TEST(SnapshotMpi, SetupErrorEndsEveryRank) {
  SKIP_WITHOUT_MPI();
  contactrb::test::TempDir dir("mpi_setup");
  const CliResult r = mpirun(2, "snapshots " + kValues + " --jobs 2 -q --out " + shell_quote(dir.file("s.h5")));
  EXPECT_NE(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.exit_code, 124) << "timed out: a hang";
  EXPECT_NE(r.err.find("under mpirun each rank solves one value at a time"), std::string::npos) << r.err;
  // An error of the setup, which runs on a thread while MPI_Init waits, is reported by the
  // ranks (each has the same setup), and no file is written.
  const CliResult domain = mpirun(2, "snapshots --case hertz-a --values 0.2,5 -q --out " + shell_quote(dir.file("d.h5")));
  EXPECT_EQ(domain.exit_code, 1) << domain.out << domain.err;
  EXPECT_NE(domain.err.find("mu = 5 (imposed displacement) is outside the domain [0.15, 0.45]"), std::string::npos)
      << domain.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("d.h5")));
  // A command that does not split its work is refused, not run once per process.
  const CliResult other = mpirun(2, "offline --case hertz-a --out " + shell_quote(dir.file("m.h5")));
  EXPECT_EQ(other.exit_code, 1) << other.out << other.err;
  EXPECT_NE(other.err.find("`contactrb offline` does not run under mpirun with several processes"), std::string::npos)
      << other.err;
}
