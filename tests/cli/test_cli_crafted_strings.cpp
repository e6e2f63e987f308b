// Crafted snapshot and model files: edited with the HDF5 API, damaged, and sealed again
// (contactrb::seal_file; the seal is an unkeyed hash anyone can recompute), so that the readers
// get past the seal into HDF5. A string stored the way older formats stored every string, as a
// variable-length string, with its global-heap length damaged: HDF5 1.10.8 ends in SIGSEGV
// reading it. The readers never read a variable-length string (docs/file-formats.md, "What
// the seal protects against"): one error line and exit 1.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "support/file_bytes.hpp"
#include "cli_runner.hpp"
#include "contactrb/common/file_seal.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::read_bytes;
using contactrb::test::write_bytes;
using contactrb::test::count_lines_starting;
using contactrb::test::CliResult;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

namespace {

// Exit 1 (not a signal: the shell reports one as 128 + its number) and exactly one
// "contactrb: error:" line holding every word of `words`.
void expect_one_error(const CliResult& r, const std::vector<std::string>& words) {
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(count_lines_starting(r.err, "contactrb: error: "), 1) << r.err;
  for (const std::string& w : words) EXPECT_NE(r.err.find(w), std::string::npos) << "missing '" << w << "' in " << r.err;
}

constexpr const char* kMarker = "crafted-variable-length-string-0123456789";

// Replaces attribute `name` of `object` by a variable-length UTF-8 string, then damages the
// length of its global-heap object (the 8 bytes before its text) and seals the file again.
void plant_damaged_vlen_string(const std::string& path, const std::string& object, const std::string& name) {
  {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hid_t obj = H5Oopen(file, object.c_str(), H5P_DEFAULT);
    ASSERT_GE(obj, 0);
    ASSERT_GE(H5Adelete(obj, name.c_str()), 0);
    const hid_t type = H5Tcopy(H5T_C_S1);
    ASSERT_GE(H5Tset_size(type, H5T_VARIABLE), 0);
    ASSERT_GE(H5Tset_cset(type, H5T_CSET_UTF8), 0);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(attr, 0);
    const char* text = kMarker;
    ASSERT_GE(H5Awrite(attr, type, &text), 0);
    H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
    H5Oclose(obj);
    ASSERT_GE(H5Fclose(file), 0);
  }
  std::string bytes = read_bytes(path);
  const std::size_t at = bytes.find(kMarker);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(bytes.find(kMarker, at + 1), std::string::npos);
  ASSERT_GE(at, 8u);
  // A global-heap object: index (2 bytes), reference count (2), reserved (4), size (8), data.
  std::uint64_t size = 0;
  for (int b = 0; b < 8; ++b) size |= std::uint64_t{static_cast<unsigned char>(bytes[at - 8 + b])} << (8 * b);
  ASSERT_EQ(size, std::strlen(kMarker)) << "not the heap object's length field";
  const std::uint64_t damaged = 0x7ffffffffff0ULL;
  for (int b = 0; b < 8; ++b) bytes[at - 8 + b] = static_cast<char>((damaged >> (8 * b)) & 0xffu);
  write_bytes(path, bytes);
  contactrb::seal_file(path);
}

// Sets the integer root attribute `format_version` to `version` and seals the file again.
void set_format_version(const std::string& path, int version) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t attr = H5Aopen(file, "format_version", H5P_DEFAULT);
  const herr_t written = attr >= 0 ? H5Awrite(attr, H5T_NATIVE_INT, &version) : -1;
  if (attr >= 0) H5Aclose(attr);
  ASSERT_GE(H5Fclose(file), 0);
  ASSERT_GE(written, 0);
  contactrb::seal_file(path);
}

// A small snapshot file and model of the two-block patch case, made once for the suite.
class CliCraftedStrings : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<contactrb::test::TempDir>("crafted_strings");
    snapshots_ = dir_->file("s.h5");
    model_ = dir_->file("model.h5");
    const std::string toml = std::string(CONTACTRB_SOURCE_DIR) + "/examples/two-block-patch/case.toml";
    const CliResult s = run_cli("snapshots --case-file " + shell_quote(toml) + " --values 0.01,0.02,0.03 -q --out " +
                                shell_quote(snapshots_));
    ASSERT_EQ(s.exit_code, 0) << s.out << s.err;
    const CliResult o = run_cli("offline --snapshots " + shell_quote(snapshots_) + " --out " + shell_quote(model_));
    ASSERT_EQ(o.exit_code, 0) << o.out << o.err;
  }
  static void TearDownTestSuite() { dir_.reset(); }

  // A fresh copy of the suite's snapshot file or model, to craft.
  static std::string copy_of(const std::string& original, const std::string& name) {
    const std::string path = dir_->file(name);
    fs::copy_file(original, path, fs::copy_options::overwrite_existing);
    return path;
  }
  static CliResult offline(const std::string& snapshots) {
    return run_cli("offline --snapshots " + shell_quote(snapshots) + " --out " + shell_quote(dir_->file("out.h5")));
  }
  static CliResult online(const std::string& model, bool fields) {
    return run_cli("online --model " + shell_quote(model) + " --mu 0.015" +
                   (fields ? " --out " + shell_quote(dir_->file("fields")) : std::string()));
  }

  static std::unique_ptr<contactrb::test::TempDir> dir_;
  static std::string snapshots_, model_;
};
std::unique_ptr<contactrb::test::TempDir> CliCraftedStrings::dir_;
std::string CliCraftedStrings::snapshots_, CliCraftedStrings::model_;

TEST_F(CliCraftedStrings, DamagedStringInASnapshotFileIsOneError) {
  for (const auto& [object, name] : std::vector<std::pair<std::string, std::string>>{
           {"/case", "name"}, {"/snapshots/000001", "status"}, {"/parameter/000000", "units"}}) {
    SCOPED_TRACE(object + " " + name);
    const std::string path = copy_of(snapshots_, "s_crafted.h5");
    plant_damaged_vlen_string(path, object, name);
    ASSERT_EQ(contactrb::check_seal(path), contactrb::SealState::Valid);
    const CliResult r = offline(path);
    expect_one_error(r, {"s_crafted.h5", "'" + name + "'", "variable-length string"});
    EXPECT_FALSE(fs::exists(dir_->file("out.h5")));
  }
}

TEST_F(CliCraftedStrings, DamagedStringInAModelIsOneError) {
  for (const auto& [object, name] : std::vector<std::pair<std::string, std::string>>{
           {"/meta", "case_name"}, {"/parameters/000000", "name"}, {"/surface", "discretization"}}) {
    SCOPED_TRACE(object + " " + name);
    const std::string path = copy_of(model_, "m_crafted.h5");
    plant_damaged_vlen_string(path, object, name);
    ASSERT_EQ(contactrb::check_seal(path), contactrb::SealState::Valid);
    expect_one_error(online(path, false), {"m_crafted.h5", "'" + name + "'", "variable-length string"});
  }
  // /mesh is read by the reconstruction alone (online --out): a query without it answers.
  const std::string path = copy_of(model_, "m_crafted.h5");
  plant_damaged_vlen_string(path, "/mesh/boundaries/000000", "name");
  EXPECT_EQ(online(path, false).exit_code, 0);
  expect_one_error(online(path, true), {"m_crafted.h5", "'name'", "variable-length string"});
  EXPECT_FALSE(fs::exists(dir_->file("fields") + "/solution.vtu"));
}

// An older file (snapshot format 4, model format 5) stored its `format` as a variable-length
// string: it is refused from the attribute's type alone, with its version and the command that
// writes the current format. The planted string is damaged: reading it would crash.
TEST_F(CliCraftedStrings, OlderSnapshotFormatIsRefusedWithoutReadingItsStrings) {
  const std::string path = copy_of(snapshots_, "s_old.h5");
  plant_damaged_vlen_string(path, "/", "format");
  set_format_version(path, 4);
  expect_one_error(offline(path), {"s_old.h5", "snapshot format 4 is no longer read (this build reads formats 5 to 8)",
                                   "`contactrb snapshots`"});
  // A version this build reads with a variable-length `format`: a damaged file, not an old one.
  for (int version : {5, 6, 7, 8}) {
    set_format_version(path, version);
    expect_one_error(offline(path), {"s_old.h5", "damaged", "'format' is a variable-length string"});
  }
  set_format_version(path, 4);
  const CliResult merged = run_cli("merge " + shell_quote(path) + " " + shell_quote(snapshots_) + " --out " +
                                   shell_quote(dir_->file("merged.h5")));
  expect_one_error(merged, {"s_old.h5", "snapshot format 4 is no longer read"});
  EXPECT_FALSE(fs::exists(dir_->file("merged.h5")));
  // Given as a model, it is named as a snapshot file.
  expect_one_error(online(path, false), {"s_old.h5", "a contactrb snapshot file, not a reduced model"});
}

TEST_F(CliCraftedStrings, OlderModelFormatIsRefusedWithoutReadingItsStrings) {
  const std::string path = copy_of(model_, "m_old.h5");
  plant_damaged_vlen_string(path, "/", "format");
  set_format_version(path, 5);
  for (bool fields : {false, true}) {
    expect_one_error(online(path, fields),
                     {"m_old.h5",
                      "model format 5 is no longer read (this build reads format " +
                          std::to_string(contactrb::model::kReducedModelFormatVersion) + ")",
                      "rebuild it with `contactrb offline`"});
  }
  const CliResult e = run_cli("evaluate --model " + shell_quote(path) + " --set verification --repeats 1 -q --out " +
                              shell_quote(dir_->file("evaluation")));
  expect_one_error(e, {"m_old.h5", "model format 5 is no longer read"});
  // Given as snapshots, it is named as a model.
  expect_one_error(offline(path), {"m_old.h5", "is a contactrb reduced model file, not a snapshot file"});
}

}  // namespace
