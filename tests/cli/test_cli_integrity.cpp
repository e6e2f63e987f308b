// Damaged and degenerate inputs through the command line: damaged snapshot files, a file of one kind
// given for the other, physically degenerate or overflowing case data (the fixtures in
// tests/data/numerics/ reproduce each kind), empty and underflowing parameter values,
// and repeated training values. Each ends in exit code 1 and one line `contactrb: error: ...`.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli_fixtures.hpp"
#include "cli_runner.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

namespace {

const fs::path kFixtures = fs::path(CONTACTRB_SOURCE_DIR) / "tests" / "data" / "numerics";

std::string fixture(const std::string& name) { return shell_quote((kFixtures / name).string()); }

void expect_one_line_user_error(const CliResult& r, const std::string& words) {
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(r.err.rfind("contactrb: error: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
  EXPECT_NE(r.err.find(words), std::string::npos) << "'" << words << "' not in: " << r.err;
}

// A small snapshot file and a model from it, made once for the suite.
class CliIntegrity : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<contactrb::test::TempDir>("cli_integrity");
    snapshots_ = dir_->file("s.h5");
    model_ = dir_->file("model.h5");
    contactrb::test::make_small_hertz_model(snapshots_, model_);
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::unique_ptr<contactrb::test::TempDir> dir_;
  static std::string snapshots_, model_;
};
std::unique_ptr<contactrb::test::TempDir> CliIntegrity::dir_;
std::string CliIntegrity::snapshots_, CliIntegrity::model_;

// A copy of the suite's snapshot file with entry `index` of /discretization/free_dofs set to
// `value` (another program's edit, or a flipped byte).
std::string with_free_dof(const contactrb::test::TempDir& dir, const std::string& source, const std::string& name,
                          std::size_t index, int value) {
  const std::string path = dir.file(name);
  fs::copy_file(source, path, fs::copy_options::overwrite_existing);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t set = H5Dopen2(file, "/discretization/free_dofs", H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  std::vector<int> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  H5Dread(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  if (value == -2) value = v.at(index - 1);  // the previous entry: a duplicate
  v.at(index) = value;
  H5Dwrite(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(set);
  H5Fclose(file);
  return path;
}

}  // namespace

// Free_dofs out of range, negative or duplicated made `offline --snapshots` die of
// SIGSEGV or "double free or corruption" (Eigen setFromTriplets with unchecked indices).
TEST_F(CliIntegrity, DamagedFreeDofsGiveOneErrorAndNoModel) {
  struct Edit {
    const char* name;
    std::size_t index;
    int value;
  };
  for (const Edit& e : {Edit{"out_of_range.h5", 10, 1 << 30}, Edit{"negative.h5", 0, -5}, Edit{"duplicated.h5", 7, -2}}) {
    SCOPED_TRACE(e.name);
    const std::string damaged = with_free_dof(*dir_, snapshots_, e.name, e.index, e.value);
    const std::string out = dir_->file(std::string("model_") + e.name);
    const CliResult r = run_cli("offline --snapshots " + shell_quote(damaged) + " --out " + shell_quote(out));
    expect_one_line_user_error(r, "snapshot file '" + damaged + "' is truncated or damaged: checksum mismatch");
    EXPECT_FALSE(fs::exists(out));
  }
}

// Each file kind says what it is when given for the other.
TEST_F(CliIntegrity, AFileOfTheOtherKindIsNamed) {
  expect_one_line_user_error(run_cli("online --model " + shell_quote(snapshots_) + " --mu 0.3"),
                    "'" + snapshots_ + "': a contactrb snapshot file, not a reduced model");
  expect_one_line_user_error(run_cli("offline --snapshots " + shell_quote(model_) + " --out " + shell_quote(dir_->file("m2.h5"))),
                    "'" + model_ + "' is a contactrb reduced model file, not a snapshot file");
}

// CLI11 turned an empty value into 0, and strtod turns 1e-400 into 0: both solved at
// mu = 0 (outside hertz-a's domain here, but inside a domain that contains 0 they would be
// silent wrong answers).
TEST_F(CliIntegrity, EmptyAndUnderflowingParameterValuesAreRefused) {
  const std::string out = " --out " + shell_quote(dir_->file("solve"));
  expect_one_line_user_error(run_cli("solve --case hertz-a --mu ''" + out), "--mu: the value is empty");
  expect_one_line_user_error(run_cli("solve --case hertz-a --mu 1e-400" + out),
                    "--mu: '1e-400' is below the smallest normal double (2.2e-308): it would be read as 0");
  expect_one_line_user_error(run_cli("online --model " + shell_quote(model_) + " --mu ''"), "--mu: the value is empty");
  expect_one_line_user_error(run_cli("online --model " + shell_quote(model_) + " --mu 1e-400"), "--mu: '1e-400' is below");
  const std::string h5 = " --out " + shell_quote(dir_->file("v.h5"));
  expect_one_line_user_error(run_cli("snapshots --case hertz-a --values ''" + h5), "--values value 1: the value is empty");
  expect_one_line_user_error(run_cli("snapshots --case hertz-a --values 0.2,1e-400" + h5), "--values value 2: '1e-400' is below");
  expect_one_line_user_error(run_cli("offline --case hertz-a --values ''" + h5), "--values value 1: the value is empty");
  EXPECT_FALSE(fs::exists(dir_->file("v.h5")));
  EXPECT_FALSE(fs::exists(dir_->file("solve")));
}

// A zero step or a repeated value was accepted, and the model answered a contact force
// of 65.4 where the HF solve gives 1.47, with converged = true.
TEST_F(CliIntegrity, RepeatedTrainingValuesAreRefused) {
  const std::string h5 = " --out " + shell_quote(dir_->file("r.h5"));
  expect_one_line_user_error(run_cli("snapshots --case-file " + fixture("zero-step.toml") + " -q" + h5),
                    "zero-step.toml:38: key 'parameter.training.step' must be > 0 (the values must be strictly "
                    "increasing), got 0");
  expect_one_line_user_error(run_cli("snapshots --case-file " + fixture("repeated.toml") + " -q" + h5),
                    "repeated.toml:37: key 'parameter.training' must be strictly increasing, but element 3 (0.3) is "
                    "not above element 2 (0.3)");
  expect_one_line_user_error(run_cli("snapshots --case hertz-a --values 0.2,0.3,0.3 -q" + h5),
                    "--values: the values must be strictly increasing, but value 3 (0.3) is not above value 2 (0.3)");
  expect_one_line_user_error(run_cli("offline --case hertz-a --values 0.3,0.2 -q" + h5),
                    "--values: the values must be strictly increasing, but value 2 (0.2) is not above value 1 (0.3)");
  EXPECT_FALSE(fs::exists(dir_->file("r.h5")));
  const std::string report = " --out " + shell_quote(dir_->file("report"));
  expect_one_line_user_error(run_cli("report --case hertz-a --training-values 0.2,0.2" + report),
                    "--training-values: the values must be strictly increasing");
  expect_one_line_user_error(run_cli("report --case hertz-a --verification-values ''" + report),
                    "--verification-values value 1: the value is empty");
}

// Rows 3, 4, 5 and the stiffness ratio of item 2: refused before any solve, naming the datum.
TEST_F(CliIntegrity, DegenerateOrOverflowingCaseDataAreRefused) {
  const auto solve = [&](const std::string& name) {
    return run_cli("solve --case-file " + fixture(name) + " --mu 0.3 --out " + shell_quote(dir_->file("d")));
  };
  expect_one_line_user_error(solve("uy-1e155.toml"),
                    "Dirichlet data on 'top' reaches magnitude 1e+155 on the parameter domain, above 1e50");
  expect_one_line_user_error(solve("load-1e155.toml"), "body 1: body load of magnitude 1e+155 is above 1e50");
  expect_one_line_user_error(solve("uy-1e154.toml"), "Dirichlet data on 'top' reaches magnitude 1e+154");
  expect_one_line_user_error(solve("nu-half.toml"),
                    "body 1: Poisson's ratio nu = 0.49999999999999994 is within 1e-6 of 0.5: a nearly incompressible "
                    "material");
  expect_one_line_user_error(solve("stiffness-ratio.toml"),
                    "the Young's moduli of the two bodies (15, 1e-12) differ by a factor 1.5e+13 above 1e12");
  EXPECT_FALSE(fs::exists(dir_->file("d")));
}

// Beyond --mu, every numeric option read '' as 0 (`--eps-pod ''` built a model at
// eps_pod = 0) and '1e-400' as 0. Both are usage errors now (CLI11's validation code, 105).
TEST_F(CliIntegrity, EmptyAndUnderflowingNumericOptionsAreUsageErrors) {
  const auto expect_usage_error = [](const CliResult& r, const std::string& words) {
    EXPECT_EQ(r.exit_code, 105) << r.out << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
  };
  const std::string out = " -q --out " + shell_quote(dir_->file("u.h5"));
  expect_usage_error(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --eps-pod ''" + out),
                     "--eps-pod: the value is empty (expected a number)");
  expect_usage_error(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --eps-du 1e-400" + out),
                     "--eps-du: '1e-400' is below the smallest normal double");
  expect_usage_error(run_cli("online --model " + shell_quote(model_) + " --mu 0.3 --n ''"),
                     "--n: the value is empty");
  expect_usage_error(run_cli("snapshots --case hertz-a --values 0.2 --jobs ''" + out), "--jobs: the value is empty");
  EXPECT_FALSE(fs::exists(dir_->file("u.h5")));
  // Ordinary values still pass (a negative size is refused like any other).
  const CliResult ok = run_cli("online --model " + shell_quote(model_) + " --mu 0.3 --tol 1e-4");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}
