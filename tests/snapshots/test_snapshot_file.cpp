// Snapshot files: bitwise round trip, atomic writing, and every damaged or foreign file
// rejected with a message naming it. The sets here are synthetic (no solve): fast.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "snapshot_fixtures.hpp"

namespace fs = std::filesystem;
using contactrb::Error;
using contactrb::io::read_snapshot_file;
using contactrb::io::Snapshot;
using contactrb::io::SnapshotSet;
using contactrb::io::write_snapshot_file;
using contactrb::test::TempDir;

namespace {

// A set with the shapes of a small real one: 3 values, the second failed with no arrays,
// the third failed with its last iterate; awkward doubles (-0, denormals, extremes).
SnapshotSet synthetic_set() {
  std::mt19937 rng(42);
  std::normal_distribution<double> normal;
  const auto random = [&](Eigen::Index n) {
    Eigen::VectorXd v(n);
    for (Eigen::Index i = 0; i < n; ++i) v(i) = normal(rng);
    return v;
  };
  SnapshotSet s;
  s.case_name = "two-blocks";
  s.case_kind = "toml";
  s.case_spec = "[case]\nname = \"two-blocks\"\n# a comment with \"quotes\" and unicode: \xce\xbc\n";
  s.level = 1;
  s.constraint = "lac";
  s.parameter_name = "ring radius R1";
  s.parameter_min = 0.95;
  s.parameter_max = 1.15;
  s.set_name = "training";
  s.kacanov_alpha = 0.3;
  s.kacanov_tolerance = 1e-3;
  s.kacanov_max_iterations = 500;
  s.num_dofs = 20;
  s.free_dofs = {2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  s.contact_dofs = {4, 5, 6, 7, 12, 13, 14, 15};
  s.slave = {2, 3};
  s.master = {6, 7};
  const Eigen::Index R = 2, nc = 8;
  for (int i = 0; i < 3; ++i) {
    Snapshot snap;
    snap.mu = 0.95 + 0.01 * i;
    snap.iterations = 10 + i;
    snap.time_s = 0.125 * (i + 1);
    snap.cpu_time_s = 0.1 * (i + 1);
    if (i != 1) {
      snap.u0 = random(14);
      snap.u = random(20);
      snap.lambda = random(R).cwiseAbs();
      snap.K = Eigen::MatrixXd::NullaryExpr(R, nc, [&] { return normal(rng); });
      snap.g = random(R);
      snap.weight = random(R).cwiseAbs();
      snap.gap_pointwise = random(2);
    }
    if (i == 0) {
      snap.converged = true;
      snap.status = "converged";
      snap.u(0) = -0.0;
      snap.u(1) = std::numeric_limits<double>::denorm_min();
      snap.u(2) = std::numeric_limits<double>::max();
      snap.u(3) = std::nextafter(1.0, 2.0);
    } else if (i == 1) {
      snap.status = "exception";
      snap.message = "mesh: inverted triangle 12";
    } else {
      snap.status = "max_iterations";
      snap.message = "no convergence after 12 iterations";
    }
    s.snapshots.push_back(snap);
  }
  return s;
}

void expect_error_naming(const std::string& path, const std::string& words) {
  try {
    (void)read_snapshot_file(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

// Modifies a written file through the HDF5 C API (what another program could do).
template <typename F>
void edit_file(const std::string& path, F edit) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  edit(file);
  ASSERT_GE(H5Fclose(file), 0);
}

}  // namespace

TEST(SnapshotFile, RoundTripIsBitwise) {
  TempDir dir("roundtrip");
  const SnapshotSet s = synthetic_set();
  write_snapshot_file(s, dir.file("s.h5"));
  const SnapshotSet r = read_snapshot_file(dir.file("s.h5"));
  contactrb::test::expect_same_data(s, r, /*with_timings=*/true);
  EXPECT_EQ(r.num_failed(), 2);
  EXPECT_EQ(r.snapshots[1].u.size(), 0);  // an exception leaves no arrays
  EXPECT_EQ(r.snapshots[2].K.rows(), 2);  // a non-converged solve keeps its last iterate
  // Nothing but the file itself is left in the directory (the temporary was renamed).
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST(SnapshotFile, OverwritesAnExistingFileAtomically) {
  TempDir dir("overwrite");
  SnapshotSet s = synthetic_set();
  write_snapshot_file(s, dir.file("s.h5"));
  s.set_name = "verification";
  s.snapshots.pop_back();
  write_snapshot_file(s, dir.file("s.h5"));
  const SnapshotSet r = read_snapshot_file(dir.file("s.h5"));
  EXPECT_EQ(r.set_name, "verification");
  EXPECT_EQ(r.snapshots.size(), 2u);
}

TEST(SnapshotFile, WriteErrorsNameTheFileAndLeaveNothing) {
  TempDir dir("write_errors");
  const std::string missing_dir = dir.file("no/such/dir/s.h5");
  try {
    write_snapshot_file(synthetic_set(), missing_dir);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing_dir), std::string::npos) << e.what();
  }
  SnapshotSet bad = synthetic_set();
  bad.snapshots[0].u0.resize(3);
  EXPECT_THROW(write_snapshot_file(bad, dir.file("bad.h5")), Error);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(SnapshotFile, MissingFileIsRejected) {
  TempDir dir("missing");
  expect_error_naming(dir.file("nothing.h5"), "does not exist");
}

TEST(SnapshotFile, NonHdf5FileIsRejected) {
  TempDir dir("non_hdf5");
  std::ofstream(dir.file("text.h5")) << "mu,u\n0.2,1.0\n";
  expect_error_naming(dir.file("text.h5"), "not an HDF5 file");
  std::ofstream(dir.file("empty.h5")).close();
  expect_error_naming(dir.file("empty.h5"), "not an HDF5 file");
}

TEST(SnapshotFile, TruncatedFileIsRejected) {
  TempDir dir("truncated");
  write_snapshot_file(synthetic_set(), dir.file("good.h5"));
  const auto size = fs::file_size(dir.file("good.h5"));
  // Cut at several points: inside the superblock region, halfway, one byte short.
  for (const std::uintmax_t keep : {std::uintmax_t{100}, size / 2, size - 1}) {
    SCOPED_TRACE("kept " + std::to_string(keep) + " of " + std::to_string(size) + " bytes");
    const std::string cut = dir.file("cut_" + std::to_string(keep) + ".h5");
    fs::copy_file(dir.file("good.h5"), cut);
    fs::resize_file(cut, keep);
    expect_error_naming(cut, "truncated");
  }
}

TEST(SnapshotFile, ForeignHdf5FileIsRejected) {
  TempDir dir("foreign");
  const std::string path = dir.file("foreign.h5");
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t group = H5Gcreate2(file, "data", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Gclose(group);
  H5Fclose(file);
  expect_error_naming(path, "not a contactrb snapshot file");

  // Another program's format attribute.
  write_snapshot_file(synthetic_set(), dir.file("other.h5"));
  edit_file(dir.file("other.h5"), [](hid_t f) {
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, 19);
    ASSERT_GE(H5Adelete(f, "format"), 0);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(f, "format", type, space, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(H5Awrite(attr, type, "contactrb-model\0\0\0\0"), 0);
    H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
  });
  expect_error_naming(dir.file("other.h5"), "another format ('contactrb-model'");
}

TEST(SnapshotFile, WrongVersionIsRejected) {
  TempDir dir("version");
  write_snapshot_file(synthetic_set(), dir.file("v.h5"));
  edit_file(dir.file("v.h5"), [](hid_t f) {
    const hid_t attr = H5Aopen(f, "format_version", H5P_DEFAULT);
    const int version = contactrb::io::kSnapshotFormatVersion + 1;
    ASSERT_GE(H5Awrite(attr, H5T_NATIVE_INT, &version), 0);
    H5Aclose(attr);
  });
  expect_error_naming(dir.file("v.h5"), "format version " + std::to_string(contactrb::io::kSnapshotFormatVersion + 1));
}

TEST(SnapshotFile, IncompleteFileIsRejected) {
  TempDir dir("incomplete");
  write_snapshot_file(synthetic_set(), dir.file("i.h5"));
  edit_file(dir.file("i.h5"), [](hid_t f) { ASSERT_GE(H5Adelete(f, "complete"), 0); });
  expect_error_naming(dir.file("i.h5"), "incomplete");
}

TEST(SnapshotFile, MissingDatasetIsRejected) {
  TempDir dir("missing_dataset");
  write_snapshot_file(synthetic_set(), dir.file("m.h5"));
  edit_file(dir.file("m.h5"), [](hid_t f) { ASSERT_GE(H5Ldelete(f, "/snapshots/000000/lambda", H5P_DEFAULT), 0); });
  expect_error_naming(dir.file("m.h5"), "missing dataset 'lambda'");
}
