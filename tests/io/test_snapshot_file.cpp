// Snapshot files: bitwise round trip, atomic writing, and every damaged or foreign file
// rejected with a message naming it. The sets here are synthetic (no solve): fast.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "contactrb/common/file_seal.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/io/snapshot_rows.hpp"
#include "support/snapshot_fixtures.hpp"

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
  s.parameters = {{"ring radius R1", "body-scaling", "", 0.95, 1.15}};
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
    snap.mu = Eigen::VectorXd::Constant(1, 0.95 + 0.01 * i);
    snap.iterations = 10 + i;
    snap.time_s = 0.125 * (i + 1);
    snap.cpu_time_s = 0.1 * (i + 1);
    if (i != 1) {
      snap.u0 = random(14);
      snap.u = random(20);
      snap.lambda = random(R).cwiseAbs();
      Eigen::MatrixXd K = Eigen::MatrixXd::NullaryExpr(R, nc, [&] { return normal(rng); });
      K(0, 1) = K(1, 0) = K(1, 7) = 0.0;  // not stored: sparse rows
      snap.K = contactrb::io::rows_from_dense(K);
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

// Modifies a written file through the HDF5 C API (what another program could do) and seals it
// again (common/file_seal.hpp): a crafted file, which meets the reader's checks behind the seal.
template <typename F>
void edit_file(const std::string& path, F edit) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  edit(file);
  ASSERT_GE(H5Fclose(file), 0);
  contactrb::seal_file(path);
}

// Marks a written file as another format version (and seals it again), its contents unchanged.
void set_format_version(const std::string& path, int version) {
  edit_file(path, [version](hid_t f) {
    const hid_t attr = H5Aopen(f, "format_version", H5P_DEFAULT);
    ASSERT_GE(H5Awrite(attr, H5T_NATIVE_INT, &version), 0);
    H5Aclose(attr);
  });
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
  set_format_version(dir.file("v.h5"), contactrb::io::kSnapshotFormatVersion + 1);
  expect_error_naming(dir.file("v.h5"), "snapshot format " + std::to_string(contactrb::io::kSnapshotFormatVersion + 1) +
                                            " is newer than this build reads (format " +
                                            std::to_string(contactrb::io::kSnapshotFormatVersion) +
                                            "): generate the snapshots again with `contactrb snapshots`");
}

// The dimension (format 6): a 2D set reads back as 2D; a damaged or edited value is refused,
// and a 2D layout cannot pass for 3D (20 DOFs are not 3 x nodes).
TEST(SnapshotFile, DimensionIsRecordedAndChecked) {
  TempDir dir("dimension");
  write_snapshot_file(synthetic_set(), dir.file("d.h5"));
  EXPECT_EQ(read_snapshot_file(dir.file("d.h5")).dimension, 2);
  const auto set_dimension = [&](const std::string& name, int value) {
    fs::copy_file(dir.file("d.h5"), dir.file(name));
    edit_file(dir.file(name), [value](hid_t f) {
      const hid_t attr = H5Aopen(f, "dimension", H5P_DEFAULT);
      ASSERT_GE(H5Awrite(attr, H5T_NATIVE_INT, &value), 0);
      H5Aclose(attr);
    });
    return dir.file(name);
  };
  expect_error_naming(set_dimension("four.h5", 4), "the root attribute dimension is 4 (expected 2 or 3)");
  expect_error_naming(set_dimension("three.h5", 3), "checksum mismatch");
  SnapshotSet three = synthetic_set();
  three.dimension = 3;
  EXPECT_THROW(write_snapshot_file(three, dir.file("t.h5")), contactrb::Error);
}

namespace {

// `path` rewritten as format `version` by tests/io/snapshot_as_older_format.py (the layout of that
// writer, its checksum recomputed by an independent implementation), then sealed again; false
// when h5py or numpy is missing.
bool rewrite_as_format(const std::string& path, int version) {
  const std::string python = "/usr/bin/python3";
  if (!fs::exists(python) || std::system((python + " -c 'import h5py, numpy' >/dev/null 2>&1").c_str()) != 0) {
    return false;
  }
  const std::string cmd = python + " " + CONTACTRB_SOURCE_DIR + "/tests/io/snapshot_as_older_format.py '" + path +
                          "' " + std::to_string(version);
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  contactrb::seal_file(path);
  return true;
}

}  // namespace

// A format 5 file (no `dimension`, no `solver`) is still read, as 2D Kacanov, with every field as written.
TEST(SnapshotFile, AFormat5FileIsReadAsTwoDimensional) {
  TempDir dir("format5");
  const SnapshotSet set = synthetic_set();
  write_snapshot_file(set, dir.file("v5.h5"));
  if (!rewrite_as_format(dir.file("v5.h5"), 5)) GTEST_SKIP() << "no h5py or numpy under /usr/bin/python3";
  const SnapshotSet read = read_snapshot_file(dir.file("v5.h5"));
  EXPECT_EQ(read.dimension, 2);
  EXPECT_EQ(read.solver, "kacanov");
  contactrb::test::expect_same_data(set, read, /*with_timings=*/true);
  // The same file without its `dimension` but still marked format 6 is damaged.
  set_format_version(dir.file("v5.h5"), 6);
  expect_error_naming(dir.file("v5.h5"), "dimension");
}

// A format 6 file (no /settings `solver`) is read as Kacanov, the only method of that format;
// the same file still marked format 7 is damaged.
TEST(SnapshotFile, AFormat6FileIsReadAsKacanov) {
  TempDir dir("format6");
  const SnapshotSet set = synthetic_set();
  write_snapshot_file(set, dir.file("v6.h5"));
  if (!rewrite_as_format(dir.file("v6.h5"), 6)) GTEST_SKIP() << "no h5py or numpy under /usr/bin/python3";
  const SnapshotSet read = read_snapshot_file(dir.file("v6.h5"));
  EXPECT_EQ(read.solver, "kacanov");
  contactrb::test::expect_same_data(set, read, /*with_timings=*/true);
  set_format_version(dir.file("v6.h5"), 7);
  expect_error_naming(dir.file("v6.h5"), "solver");
}

// A format 7 file (each K a dense R x n_c dataset) is read with K as its non-zero entries.
TEST(SnapshotFile, AFormat7FileIsReadWithItsDenseK) {
  TempDir dir("format7");
  const SnapshotSet set = synthetic_set();
  write_snapshot_file(set, dir.file("v7.h5"));
  if (!rewrite_as_format(dir.file("v7.h5"), 7)) GTEST_SKIP() << "no h5py or numpy under /usr/bin/python3";
  const SnapshotSet read = read_snapshot_file(dir.file("v7.h5"));
  EXPECT_EQ(read.snapshots[0].K.nonZeros(), 13);  // 16 entries, 3 of them zero
  contactrb::test::expect_same_data(set, read, /*with_timings=*/true);
  // The same file marked format 8 lacks the compressed rows.
  set_format_version(dir.file("v7.h5"), 8);
  expect_error_naming(dir.file("v7.h5"), "K_indptr");
}

// The compressed rows of a file with a valid checksum (a crafted one) are checked before Eigen
// sees them: each bad entry named (snapshot_crafted.py sets it and recomputes the checksum).
TEST(SnapshotFile, CraftedCompressedRowsAreNamed) {
  TempDir dir("crafted_rows");
  write_snapshot_file(synthetic_set(), dir.file("good.h5"));
  const std::string python = "/usr/bin/python3";
  if (!fs::exists(python) || std::system((python + " -c 'import h5py, numpy' >/dev/null 2>&1").c_str()) != 0) {
    GTEST_SKIP() << "no h5py or numpy under /usr/bin/python3";
  }
  struct Case {
    const char* label;
    const char* dataset;
    int index;
    const char* value;
    const char* words;
  };
  // Snapshot 0: row 0 holds columns 0, 2..7 (7 entries), row 1 columns 1..6 (6 entries).
  const std::vector<Case> cases = {
      {"start", "/snapshots/000000/K_indptr", 0, "1", "/snapshots/000000/K_indptr[0] = 1 (expected 0)"},
      {"decreasing", "/snapshots/000000/K_indptr", 1, "14", "/snapshots/000000/K_indptr[2] = 13 is below"},
      {"end", "/snapshots/000000/K_indptr", 2, "12", "K_indptr ends at 12 entries, K_indices holds 13"},
      {"column", "/snapshots/000000/K_indices", 4, "8", "/snapshots/000000/K_indices[4] = 8 is outside [0, n_c = 8)"},
      {"negative", "/snapshots/000002/K_indices", 0, "-1", "/snapshots/000002/K_indices[0] = -1 is outside"},
      {"order", "/snapshots/000000/K_indices", 2, "2", "K_indices[2] = 2 is not above the column before it in row 0"},
      {"value", "/snapshots/000000/K_data", 3, "nan", "/snapshots/000000/K_data holds a non-finite value (nan) at (0, 4)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.label);
    const std::string path = dir.file(std::string(c.label) + ".h5");
    fs::copy_file(dir.file("good.h5"), path);
    const std::string cmd = python + " " + CONTACTRB_SOURCE_DIR + "/tests/io/snapshot_crafted.py '" + path + "' " +
                            c.dataset + " " + std::to_string(c.index) + " " + c.value;
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    contactrb::seal_file(path);
    expect_error_naming(path, c.words);
  }
}

// The same checks on arrays in memory (rows_from_csr, also used for the MPI messages).
TEST(SnapshotRows, BadArraysAreNamed) {
  using contactrb::io::CsrArrays;
  using contactrb::io::rows_from_csr;
  const CsrArrays good{{0, 2, 3}, {0, 3, 1}, {1.0, -2.0, 0.5}};
  const contactrb::io::SnapshotRows K = rows_from_csr(good, 4, "/x");
  EXPECT_EQ(Eigen::MatrixXd(K), (Eigen::MatrixXd(2, 4) << 1, 0, 0, -2, 0, 0.5, 0, 0).finished());
  const auto expect_named = [](const CsrArrays& a, Eigen::Index cols, const std::string& words) {
    try {
      (void)rows_from_csr(a, cols, "/x");
      ADD_FAILURE() << "no error, expected '" << words << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << "expected '" << words << "' in: " << e.what();
    }
  };
  expect_named({{}, {}, {}}, 4, "/x/K_indptr is empty (expected R + 1 entries)");
  expect_named({{1, 2, 3}, {0, 3, 1}, {1.0, -2.0, 0.5}}, 4, "/x/K_indptr[0] = 1 (expected 0)");
  expect_named({{0, 2, 1, 3}, {0, 3, 1}, {1.0, -2.0, 0.5}}, 4, "/x/K_indptr[2] = 1 is below the entry before it");
  expect_named({{0, 2, 3}, {0, 3, 1}, {1.0, -2.0}}, 4, "/x/K_indptr ends at 3 entries, K_indices holds 3 and K_data 2");
  expect_named({{0, 2, 4}, {0, 3, 1}, {1.0, -2.0, 0.5}}, 4, "/x/K_indptr ends at 4 entries");
  expect_named(good, 3, "/x/K_indices[1] = 3 is outside [0, n_c = 3)");
  expect_named({{0, 2, 3}, {0, 3, -1}, {1.0, -2.0, 0.5}}, 4, "/x/K_indices[2] = -1 is outside");
  expect_named({{0, 2, 3}, {3, 0, 1}, {1.0, -2.0, 0.5}}, 4, "/x/K_indices[1] = 0 is not above the column before it in row 0");
  expect_named({{0, 2, 3}, {3, 3, 1}, {1.0, -2.0, 0.5}}, 4, "/x/K_indices[1] = 3 is not above");
}

// The solver is written and read back (h5py reads it too: tests/io, ctest io_snapshots_3d_h5py
// reads files of the CLI); an unknown method is refused by the writer's check.
TEST(SnapshotFile, SolverIsRecorded) {
  TempDir dir("solver");
  SnapshotSet set = synthetic_set();
  set.solver = "newton";
  write_snapshot_file(set, dir.file("n.h5"));
  EXPECT_EQ(read_snapshot_file(dir.file("n.h5")).solver, "newton");
  set.solver = "gauss-seidel";
  try {
    write_snapshot_file(set, dir.file("x.h5"));
    ADD_FAILURE() << "an unknown solver was written";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("solver (/settings solver) is 'gauss-seidel'"), std::string::npos) << e.what();
  }
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

// ---------------------------------------------------------------------------- damaged files

namespace {

// The message of check_snapshot_set for `set`, or "" when it accepts it.
std::string check_error(const SnapshotSet& set) {
  try {
    contactrb::io::check_snapshot_set(set);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Overwrites the int dataset `name` with `values` (its size unchanged).
void put_ints(const std::string& path, const char* name, const std::vector<int>& values) {
  edit_file(path, [&](hid_t f) {
    const hid_t set = H5Dopen2(f, name, H5P_DEFAULT);
    ASSERT_GE(set, 0);
    ASSERT_GE(H5Dwrite(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    H5Dclose(set);
  });
}

// Overwrites entry `i` of the double dataset `name` (the whole dataset rewritten).
void put_double(const std::string& path, const char* name, std::size_t i, double value) {
  edit_file(path, [&](hid_t f) {
    const hid_t set = H5Dopen2(f, name, H5P_DEFAULT);
    ASSERT_GE(set, 0);
    const hid_t space = H5Dget_space(set);
    const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
    H5Sclose(space);
    std::vector<double> v(n);
    ASSERT_GE(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
    ASSERT_LT(i, n);
    v[i] = value;
    ASSERT_GE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
    H5Dclose(set);
  });
}

void put_double_attribute(const std::string& path, const char* object, const char* name, double value) {
  edit_file(path, [&](hid_t f) {
    // Through the open object: HDF5 1.10 cannot write an attribute opened by path alone.
    const hid_t obj = H5Oopen(f, object, H5P_DEFAULT);
    const hid_t attr = H5Aopen(obj, name, H5P_DEFAULT);
    const herr_t written = H5Awrite(attr, H5T_NATIVE_DOUBLE, &value);
    H5Aclose(attr);
    H5Oclose(obj);
    EXPECT_GE(written, 0);
  });
}

}  // namespace

// Free_dofs out of range, negative or repeated made `offline` crash in
// Eigen's setFromTriplets. Every such edit is now caught by the checksum, naming the file.
TEST(SnapshotFile, EditedIndicesAreCaughtByTheChecksum) {
  TempDir dir("edited_indices");
  write_snapshot_file(synthetic_set(), dir.file("good.h5"));
  const std::vector<int> free = synthetic_set().free_dofs;
  struct Case {
    const char* label;
    const char* dataset;
    std::vector<int> values;
  };
  std::vector<int> out_of_range = free, negative = free, repeated = free;
  out_of_range[3] = 1000000;
  negative[0] = -7;
  repeated[5] = repeated[4];
  std::vector<int> slave = synthetic_set().slave;
  slave[1] = 9999;
  const std::vector<Case> cases = {{"out of range", "/discretization/free_dofs", out_of_range},
                                   {"negative", "/discretization/free_dofs", negative},
                                   {"repeated", "/discretization/free_dofs", repeated},
                                   {"slave out of range", "/discretization/slave", slave}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.label);
    const std::string path = dir.file(std::string(c.label) + ".h5");
    fs::copy_file(dir.file("good.h5"), path);
    put_ints(path, c.dataset, c.values);
    expect_error_naming(path, "checksum mismatch");
  }
}

TEST(SnapshotFile, EditedValuesAreCaughtByTheChecksum) {
  TempDir dir("edited_values");
  write_snapshot_file(synthetic_set(), dir.file("good.h5"));
  const auto edited = [&](const std::string& label) {
    const std::string path = dir.file(label + ".h5");
    fs::copy_file(dir.file("good.h5"), path);
    return path;
  };
  // One ulp in one displacement entry of a converged snapshot.
  std::string path = edited("u");
  put_double(path, "/snapshots/000000/u", 5, std::nextafter(synthetic_set().snapshots[0].u(5), 10.0));
  expect_error_naming(path, "checksum mismatch");
  path = edited("K");
  put_double(path, "/snapshots/000002/K_data", 3, 0.0);  // a failed snapshot's arrays are covered too
  expect_error_naming(path, "checksum mismatch");
  path = edited("domain");
  put_double_attribute(path, "/parameter/000000", "max", 2.0);
  expect_error_naming(path, "checksum mismatch");
  path = edited("mu");
  put_double(path, "/snapshots/000001/mu", 0, 1.0);
  expect_error_naming(path, "checksum mismatch");
  path = edited("deleted");  // an optional array of a failed snapshot removed
  edit_file(path, [](hid_t f) { ASSERT_GE(H5Ldelete(f, "/snapshots/000002/gap_pointwise", H5P_DEFAULT), 0); });
  expect_error_naming(path, "checksum mismatch");
  path = edited("no_checksum");
  edit_file(path, [](hid_t f) { ASSERT_GE(H5Adelete(f, "checksum"), 0); });
  expect_error_naming(path, "missing attribute 'checksum'");
}

TEST(SnapshotFile, CompleteOtherThanOneIsRefused) {
  TempDir dir("complete_zero");
  for (const int value : {0, 2}) {
    std::string name = "c";  // appended, not "c" + ...: GCC 12's -Wrestrict false positive there
    name += std::to_string(value);
    name += ".h5";
    const std::string path = dir.file(name);
    write_snapshot_file(synthetic_set(), path);
    edit_file(path, [&](hid_t f) {
      const hid_t attr = H5Aopen(f, "complete", H5P_DEFAULT);
      ASSERT_GE(H5Awrite(attr, H5T_NATIVE_INT, &value), 0);
      H5Aclose(attr);
    });
    expect_error_naming(path, "incomplete");
  }
}

// The checks behind the checksum, for a file with a valid checksum over bad contents (a
// faulty writer, a crafted file) and for sets handed to the offline builder directly. Each
// case names the field.
TEST(SnapshotFile, CheckSnapshotSetNamesTheBadField) {
  EXPECT_EQ(check_error(synthetic_set()), "");
  const auto expect_named = [](const SnapshotSet& s, const std::string& words) {
    const std::string e = check_error(s);
    EXPECT_NE(e.find(words), std::string::npos) << "expected '" << words << "' in: " << e;
  };
  SnapshotSet s = synthetic_set();
  s.free_dofs[3] = 20;  // == num_dofs
  expect_named(s, "/discretization/free_dofs[3] = 20 is outside [0, num_dofs = 20)");
  s = synthetic_set();
  s.free_dofs[0] = -1;
  expect_named(s, "/discretization/free_dofs[0] = -1 is outside");
  s = synthetic_set();
  s.free_dofs[5] = s.free_dofs[4];
  expect_named(s, "/discretization/free_dofs[5] = 6 appears twice");
  s = synthetic_set();
  s.slave[0] = 10;  // nodes = 10
  expect_named(s, "/discretization/slave[0] = 10 is outside [0, nodes = 10)");
  s = synthetic_set();
  s.master = {6, 6};
  expect_named(s, "/discretization/master[1] = 6 appears twice");
  s = synthetic_set();
  s.master = {6, 7, 3, 6};  // a closed chain repeats its first node at the end: accepted
  s.contact_dofs = {4, 5, 6, 7, 12, 13, 14, 15};
  s.contact_dofs.insert(s.contact_dofs.begin() + 4, {6, 7});
  std::sort(s.contact_dofs.begin(), s.contact_dofs.end());
  s.contact_dofs.erase(std::unique(s.contact_dofs.begin(), s.contact_dofs.end()), s.contact_dofs.end());
  EXPECT_EQ(check_error(s), "");
  s = synthetic_set();
  s.contact_dofs[1] = 4;
  expect_named(s, "/discretization/contact_dofs (8 entries) are not the two components");
  s = synthetic_set();
  s.num_dofs = 21;
  expect_named(s, "num_dofs = 21");
  s = synthetic_set();  // a damaged count: checked without memory in proportion to it
  s.num_dofs = 2000000000;
  expect_named(s, "/snapshots/000000: u has 20 entries, expected 2000000000");
  // Non-finite values of a converged snapshot, by dataset.
  s = synthetic_set();
  s.snapshots[0].u(7) = std::numeric_limits<double>::quiet_NaN();
  expect_named(s, "/snapshots/000000/u holds a non-finite value (nan) at entry 7");
  s = synthetic_set();
  s.snapshots[0].K.coeffRef(1, 2) = -std::numeric_limits<double>::infinity();
  expect_named(s, "/snapshots/000000/K_data holds a non-finite value (-inf) at (1, 2)");
  s = synthetic_set();
  s.snapshots[0].g(0) = std::numeric_limits<double>::infinity();
  expect_named(s, "/snapshots/000000/g holds a non-finite value");
  s = synthetic_set();  // a failed snapshot keeps whatever its last iterate was
  s.snapshots[2].u(0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(check_error(s), "");
  // Parameter values against the stored domain, and the domain itself.
  s = synthetic_set();
  s.snapshots[1].mu(0) = 1.2;
  expect_named(s, "/snapshots/000001: mu = 1.2 (ring radius R1) is outside the stored domain [0.95, 1.15]");  // shortest digits
  s = synthetic_set();
  s.snapshots[1].mu(0) = std::nextafter(0.95, 0.0);
  expect_named(s, "is outside the stored domain");
  s = synthetic_set();
  s.snapshots[1].mu = Eigen::Vector2d(1.0, 1.0);
  expect_named(s, "/snapshots/000001: mu has 2 values for 1 parameters");
  s = synthetic_set();
  std::swap(s.parameters[0].min, s.parameters[0].max);
  expect_named(s, "the domain [1.15, 0.95] of parameter 'ring radius R1' (/parameter/000000 min, max) is not an interval");
  s = synthetic_set();
  s.parameters[0].max = std::numeric_limits<double>::quiet_NaN();
  expect_named(s, "is not an interval");
  s = synthetic_set();
  s.parameters.clear();
  expect_named(s, "/parameter holds no parameter");
  // Status and flag, settings, kinds.
  s = synthetic_set();
  s.snapshots[2].converged = true;
  expect_named(s, "/snapshots/000002: status 'max_iterations' disagrees with /snapshots/converged = 1");
  s = synthetic_set();
  s.kacanov_alpha = 0.0;
  expect_named(s, "Kacanov settings");
  s = synthetic_set();
  s.constraint = "mortar";
  expect_named(s, "/case/constraint is 'mortar'");
}

TEST(SnapshotFile, WriterRefusesWhatTheReaderWouldRefuse) {
  TempDir dir("writer_refuses");
  SnapshotSet bad = synthetic_set();
  bad.free_dofs[2] = 99;
  try {
    write_snapshot_file(bad, dir.file("bad.h5"));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/discretization/free_dofs[2] = 99"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir.path()));
  // A set whose every solve threw before its discretization existed is still written (the
  // failures are the record).
  SnapshotSet failed = synthetic_set();
  failed.num_dofs = 0;
  failed.constraint.clear();
  failed.free_dofs.clear();
  failed.contact_dofs.clear();
  failed.slave.clear();
  failed.master.clear();
  failed.snapshots = {failed.snapshots[1]};
  write_snapshot_file(failed, dir.file("failed.h5"));
  EXPECT_EQ(read_snapshot_file(dir.file("failed.h5")).num_failed(), 1);
}

TEST(SnapshotFile, AReducedModelFileIsNamedAsSuch) {
  TempDir dir("model_as_snapshots");
  const std::string path = dir.file("model.h5");
  contactrb::io::write_reduced_model_file(contactrb::model::ReducedModel{}, path);
  expect_error_naming(path, "is a contactrb reduced model file, not a snapshot file");
  EXPECT_FALSE(contactrb::io::is_snapshot_file(path));
  write_snapshot_file(synthetic_set(), dir.file("s.h5"));
  EXPECT_TRUE(contactrb::io::is_snapshot_file(dir.file("s.h5")));
  EXPECT_FALSE(contactrb::io::is_snapshot_file(dir.file("nothing.h5")));
}

// Random byte flips of a snapshot file: every flip is either refused with a message naming the
// file or lands in bytes that carry no data (HDF5 padding, free space): the data read back are then
// bitwise the written ones. Seeded, so a failure reproduces.
TEST(SnapshotFile, EveryByteFlipIsRefusedOrHarmless) {
#if defined(__SANITIZE_ADDRESS__)
  // HDF5 1.10.8 itself reads freed memory (H5O__attr_exists from H5Aexists) and asks malloc for
  // petabytes (H5C_protect) on some of these flips, before any of our checks can run: ASan
  // reports the library, not contactrb. Our checks are the same in the Release build, where
  // this test runs. (A hash of the raw file bytes verified before HDF5 opens the file would
  // keep accidental damage away from HDF5's parser: not done.)
  GTEST_SKIP() << "HDF5 1.10.8 has memory errors on corrupted files (see the comment)";
#endif
  TempDir dir("byte_flips");
  const SnapshotSet s = synthetic_set();
  write_snapshot_file(s, dir.file("good.h5"));
  std::ifstream in(dir.file("good.h5"), std::ios::binary);
  const std::vector<char> good{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_GT(good.size(), 1000u);
  std::mt19937 rng(20261123);
  std::uniform_int_distribution<std::size_t> where(0, good.size() - 1);
  std::uniform_int_distribution<int> bit(0, 7);
  int refused = 0, harmless = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<char> bytes = good;
    const std::size_t at = where(rng);
    bytes[at] = static_cast<char>(bytes[at] ^ (1 << bit(rng)));
    const std::string path = dir.file("flip.h5");
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    try {
      const SnapshotSet r = read_snapshot_file(path);
      SCOPED_TRACE("byte " + std::to_string(at) + " accepted");
      contactrb::test::expect_same_data(s, r, /*with_timings=*/true);
      ++harmless;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      ++refused;
    }
  }
  std::printf("  300 single-bit flips: %d refused, %d in bytes without data\n", refused, harmless);
  // Measured: all 300 flips refused by the seal (common/file_seal.hpp: the hash of every byte,
  // checked before HDF5 parses the file; before it, 97 of 300 were refused and the others hit
  // bytes HDF5 never reads back). Far fewer would mean the reader stopped looking.
  EXPECT_GT(refused, 50);
}

// A crafted file can carry a valid seal and checksum over wrong contents: the reader's semantic
// checks still refuse pressures that are not pressures (a negated lambda) and negative weights.
TEST(SnapshotFile, NegativePressuresAreRefused) {
  SnapshotSet s = synthetic_set();
  ASSERT_TRUE(s.snapshots[0].converged);
  ASSERT_GT(s.snapshots[0].lambda.maxCoeff(), 0.0);
  s.snapshots[0].lambda = -s.snapshots[0].lambda;
  EXPECT_NE(check_error(s).find("/snapshots/000000/lambda: a contact pressure is negative"), std::string::npos)
      << check_error(s);
  s = synthetic_set();
  s.snapshots[0].lambda(0) = -1e-14 * s.snapshots[0].lambda.maxCoeff();  // round-off of a solver: accepted
  EXPECT_EQ(check_error(s), "");
  s = synthetic_set();
  s.snapshots[0].weight(0) = -s.snapshots[0].weight(0);
  EXPECT_NE(check_error(s).find("a weight |I_r| is negative"), std::string::npos) << check_error(s);
}

TEST(SnapshotFile, ALevelAboveTheFinestIsRefused) {
  SnapshotSet s = synthetic_set();
  s.level = 40;
  EXPECT_NE(check_error(s).find("/case/level is 40 (expected 0 to 16"), std::string::npos) << check_error(s);
}

namespace {

// Every attribute of every object of a file: "object@attribute" and its datatype.
struct AttributeTypes {
  std::vector<std::pair<std::string, hid_t>> list;
  ~AttributeTypes() {
    for (auto& [name, type] : list) H5Tclose(type);
  }
};

herr_t collect_attribute(hid_t loc, const char* name, const H5A_info_t*, void* data) {
  auto& out = *static_cast<std::pair<std::string, AttributeTypes*>*>(data);
  const hid_t attr = H5Aopen(loc, name, H5P_DEFAULT);
  out.second->list.emplace_back(out.first + "@" + name, H5Aget_type(attr));
  H5Aclose(attr);
  return 0;
}

herr_t collect_object(hid_t root, const char* name, const H5O_info_t*, void* data) {
  const hid_t obj = H5Oopen(root, name, H5P_DEFAULT);
  std::pair<std::string, AttributeTypes*> where{name, static_cast<AttributeTypes*>(data)};
  H5Aiterate2(obj, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_attribute, &where);
  H5Oclose(obj);
  return 0;
}

// The stored bytes of a scalar string attribute, read with its own (fixed-length) type.
std::string raw_string_attribute(hid_t file, const char* object, const char* name) {
  const hid_t attr = H5Aopen_by_name(file, object, name, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t type = H5Aget_type(attr);
  std::string bytes(H5Tget_size(type), '?');
  EXPECT_GE(H5Aread(attr, type, bytes.data()), 0) << object << " " << name;
  H5Tclose(type);
  H5Aclose(attr);
  return bytes;
}

}  // namespace

// Every string is a fixed-length UTF-8 string of its byte length (at least 1, NUL-padded): no
// variable-length data, which HDF5 1.10 cannot read safely from a damaged file. Checked with
// the HDF5 API, independently of the reader.
TEST(SnapshotFile, StringsAreFixedLengthUtf8OfTheirByteLength) {
  TempDir dir("strings");
  const SnapshotSet s = synthetic_set();
  ASSERT_EQ(s.parameters[0].units, "");  // the empty string: one NUL byte
  write_snapshot_file(s, dir.file("s.h5"));
  const hid_t file = H5Fopen(dir.file("s.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  AttributeTypes types;
  std::pair<std::string, AttributeTypes*> root{"", &types};
  H5Aiterate2(file, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_attribute, &root);
  H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_INC, collect_object, &types, H5O_INFO_BASIC);
  int strings = 0;
  for (const auto& [name, type] : types.list) {
    if (H5Tget_class(type) != H5T_STRING) continue;
    ++strings;
    EXPECT_EQ(H5Tis_variable_str(type), 0) << name;
    EXPECT_EQ(H5Tget_cset(type), H5T_CSET_UTF8) << name;
    EXPECT_EQ(H5Tget_strpad(type), H5T_STR_NULLPAD) << name;
    EXPECT_GE(H5Tget_size(type), 1u) << name;
  }
  // format, description, contactrb_version, 5 in /case, 4 in /parameter, 3 per snapshot, and
  // shape_meaning and units of every dataset: well above 30.
  EXPECT_GT(strings, 30);
  EXPECT_EQ(raw_string_attribute(file, "/", "format"), std::string(contactrb::io::kSnapshotFormatName));
  EXPECT_EQ(raw_string_attribute(file, "/case", "spec"), s.case_spec);  // UTF-8 bytes as written
  EXPECT_EQ(raw_string_attribute(file, "/parameter/000000", "units"), std::string(1, '\0'));
  EXPECT_EQ(raw_string_attribute(file, "/snapshots/000001", "status"), s.snapshots[1].status);
  H5Fclose(file);
  const SnapshotSet r = read_snapshot_file(dir.file("s.h5"));
  EXPECT_EQ(r.case_spec, s.case_spec);
  EXPECT_EQ(r.parameters[0].units, "");
}

// A variable-length string planted in a file of this format (sealed again) is refused without
// being read, naming the attribute.
TEST(SnapshotFile, AVariableLengthStringIsRefusedUnread) {
  TempDir dir("vlen");
  write_snapshot_file(synthetic_set(), dir.file("s.h5"));
  edit_file(dir.file("s.h5"), [](hid_t f) {
    const hid_t group = H5Gopen2(f, "/case", H5P_DEFAULT);
    ASSERT_GE(H5Adelete(group, "constraint"), 0);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(group, "constraint", type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = "lac";
    ASSERT_GE(H5Awrite(attr, type, &text), 0);
    H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
    H5Gclose(group);
  });
  expect_error_naming(dir.file("s.h5"), "attribute 'constraint' is a variable-length string");
}
