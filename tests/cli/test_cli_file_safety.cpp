// File safety: no lost file, no unbounded read, no mixed output set, no raw control
// character on the terminal. Each test reproduces one way of losing or mixing a file.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/file_bytes.hpp"
#include "cli_fixtures.hpp"
#include "cli_runner.hpp"
#include "support/temp_dir.hpp"
#include "contactrb/common/file_seal.hpp"

namespace fs = std::filesystem;
using contactrb::test::SmallDisk;
using contactrb::test::read_bytes;
using contactrb::test::write_bytes;
using contactrb::test::count_lines_starting;
using contactrb::test::CliResult;
using contactrb::test::lines_of;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;
using nlohmann::json;

namespace {

std::string data(const std::string& name) { return std::string(CONTACTRB_SOURCE_DIR) + "/tests/data/" + name; }


// Exit 1 and exactly one "contactrb: error:" line that holds every word of `words`.
void expect_user_error_words(const CliResult& r, const std::vector<std::string>& words) {
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(count_lines_starting(r.err, "contactrb: error: "), 1) << r.err;
  for (const std::string& w : words) EXPECT_NE(r.err.find(w), std::string::npos) << "missing '" << w << "' in " << r.err;
}

// A small hertz-a snapshot file and model, made once for the suite.
class CliFileSafety : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<contactrb::test::TempDir>("file_safety");
    snapshots_ = dir_->file("s.h5");
    model_ = dir_->file("model.h5");
    contactrb::test::make_small_hertz_model(snapshots_, model_);
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::unique_ptr<contactrb::test::TempDir> dir_;
  static std::string snapshots_, model_;
};
std::unique_ptr<contactrb::test::TempDir> CliFileSafety::dir_;
std::string CliFileSafety::snapshots_, CliFileSafety::model_;

// A batch line with the byte 0xFF ended the run with "internal error: invalid UTF-8"
// and the lines after it were never answered.
TEST_F(CliFileSafety, BatchLineWithInvalidBytesIsAnsweredAndTheRestGoOn) {
  const CliResult r = run_cli("online --model " + shell_quote(model_) + " --batch " + shell_quote(data("batch/bad_bytes.txt")));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_EQ(count_lines_starting(r.err, "contactrb: error: "), 1) << r.err;
  EXPECT_NE(r.err.find("2 of 4 batch lines"), std::string::npos) << r.err;
  const std::vector<std::string> lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 4u) << r.out;
  std::vector<json> answers;
  for (const std::string& l : lines) answers.push_back(json::parse(l));  // every line valid JSON (UTF-8)
  EXPECT_TRUE(answers[0].contains("energy")) << lines[0];
  EXPECT_NE(answers[1].at("error").get<std::string>().find("\\xff"), std::string::npos) << lines[1];
  // The escape sequence of line 3 is quoted escaped, never as the raw ESC byte.
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos);
  EXPECT_NE(answers[2].at("error").get<std::string>().find("\\x1b"), std::string::npos) << lines[2];
  EXPECT_EQ(answers[3].at("line").get<int>(), 4);
  EXPECT_TRUE(answers[3].contains("energy")) << lines[3];
}

// strtod stops at a NUL byte: "0.3<NUL>junk" must not be read as 0.3, and a line holding a NUL
// is quoted with \x00, not cut there.
TEST_F(CliFileSafety, BatchLineWithANulByteIsABadLineQuotedWholly) {
  const std::string input = dir_->file("nul_lines.txt");
  const std::string nul(1, '\0');
  write_bytes(input, "0.3" + nul + "junk\n" + nul + "\n0.3\n");
  const CliResult r = run_cli("online --model " + shell_quote(model_) + " --batch " + shell_quote(input));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("2 of 3 batch lines"), std::string::npos) << r.err;
  const std::vector<std::string> lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  const json first = json::parse(lines[0]);
  ASSERT_TRUE(first.contains("error")) << lines[0];
  EXPECT_NE(first.at("error").get<std::string>().find("0.3\\x00junk' is not a number"), std::string::npos) << lines[0];
  const json second = json::parse(lines[1]);
  ASSERT_TRUE(second.contains("error")) << lines[1];
  EXPECT_NE(second.at("error").get<std::string>().find("'\\x00' is not a number"), std::string::npos) << lines[1];
  EXPECT_TRUE(json::parse(lines[2]).contains("energy")) << lines[2];
}

// Batch from a pipe: /dev/zero has no newline; the line is bounded (never buffered
// whole), answered by one error line, and the next line is still answered.
TEST_F(CliFileSafety, EndlessBatchLineFromStdinIsBounded) {
  const std::string input = dir_->file("zeros_then_value.txt");
  write_bytes(input, std::string(20 * 1024 * 1024, '\0') + "\n0.3\n");
  const CliResult r = run_cli("online --model " + shell_quote(model_) + " --batch - < " + shell_quote(input));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(count_lines_starting(r.err, "contactrb: error: "), 1) << r.err;
  const std::vector<std::string> lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 2u) << r.out.substr(0, 1000);
  EXPECT_NE(json::parse(lines[0]).at("error").get<std::string>().find("longer than"), std::string::npos);
  EXPECT_LT(lines[0].size(), 1000u);  // the message does not quote 20 MB of zeros
  EXPECT_TRUE(json::parse(lines[1]).contains("energy")) << lines[1];
}

// Rows 12 and 14: a device or a directory as a batch file (a directory was answered by
// nothing and exit 0; /dev/urandom was answered without end).
TEST_F(CliFileSafety, BatchFileMustBeARegularFile) {
  expect_user_error_words(run_cli("online --model " + shell_quote(model_) + " --batch /dev/urandom"),
                    {"batch file '/dev/urandom'", "not a regular file"});
  expect_user_error_words(run_cli("online --model " + shell_quote(model_) + " --batch " + shell_quote(dir_->path().string())),
                    {"batch file", "is a directory"});
}

// /dev/zero as a mesh was read without end; a file above the input limit is refused
// before it is read, naming the variable that raises the limit.
TEST(CliInputBounds, MeshMustBeARegularFileBelowTheLimit) {
  const contactrb::test::TempDir dir("input_bounds");
  const std::string out = " --out " + shell_quote(dir.file("m"));
  expect_user_error_words(run_cli("mesh --msh /dev/zero" + out), {"mesh file '/dev/zero'", "not a regular file"});
  const std::string junk = dir.file("junk.msh");
  write_bytes(junk, "$MeshFormat\n" + std::string(3 * 1024 * 1024, 'x') + "\n");
  // Under the default limit (256 MiB) the junk is read and refused as junk.
  const CliResult read = run_cli("mesh --msh " + shell_quote(junk) + out);
  expect_user_error_words(read, {"junk.msh"});
  EXPECT_EQ(read.err.find("above the input limit"), std::string::npos) << read.err;
  // With a 2 MiB limit it is refused by its size.
  expect_user_error_words(run_cli("mesh --msh " + shell_quote(junk) + out, "", "CONTACTRB_MAX_TEXT_INPUT_MB=2"),
                    {"junk.msh", "3.0 MiB", "above the input limit of 2.0 MiB", "CONTACTRB_MAX_TEXT_INPUT_MB"});
  // A valid mesh under a raised limit reads as before; a limit that is not a number is refused.
  const CliResult good = run_cli("mesh --msh " + shell_quote(data("msh/two_squares.msh")) + out, "",
                                 "CONTACTRB_MAX_TEXT_INPUT_MB=4096");
  EXPECT_EQ(good.exit_code, 0) << good.err;
  expect_user_error_words(run_cli("mesh --msh " + shell_quote(data("msh/two_squares.msh")) + out, "",
                            "CONTACTRB_MAX_TEXT_INPUT_MB=-1"),
                    {"CONTACTRB_MAX_TEXT_INPUT_MB must be a positive whole number"});
  // The same bound on the other text readers: a TOML case file, a parameter file.
  expect_user_error_words(run_cli("solve --case-file /dev/zero --mu 0.02" + out), {"case file '/dev/zero'", "not a regular file"});
}

// An output equal to an input destroyed the input.
TEST_F(CliFileSafety, OutputEqualToAnInputIsRefusedAndTheInputKept) {
  const contactrb::test::TempDir dir("out_is_input");
  const fs::path s = dir.path() / "s.h5";
  fs::copy_file(snapshots_, s);
  const std::string before = read_bytes(s);
  expect_user_error_words(run_cli("offline --snapshots " + shell_quote(s.string()) + " --out " + shell_quote(s.string())),
                    {"--out", "is the input --snapshots", "would destroy the input"});
  // The same file under another spelling, and through a hard link.
  fs::create_directory(dir.path() / "sub");
  expect_user_error_words(run_cli("offline --snapshots " + shell_quote(s.string()) + " --out " +
                            shell_quote((dir.path() / "sub" / ".." / "s.h5").string())),
                    {"is the input --snapshots"});
  fs::create_hard_link(s, dir.path() / "sub" / "hard.h5");
  expect_user_error_words(run_cli("offline --snapshots " + shell_quote(s.string()) + " --out " +
                            shell_quote((dir.path() / "sub" / "hard.h5").string())),
                    {"is the input --snapshots"});
  EXPECT_EQ(read_bytes(s), before);

  const fs::path toml = dir.path() / "case.toml";
  fs::copy_file(std::string(CONTACTRB_SOURCE_DIR) + "/examples/two-block-patch/case.toml", toml);
  std::string text = read_bytes(toml);
  // The case's mesh path is relative to the TOML file: point it at the example's mesh.
  const std::string example_dir = std::string(CONTACTRB_SOURCE_DIR) + "/examples/two-block-patch/";
  const std::size_t key = text.find("file = \"");
  ASSERT_NE(key, std::string::npos) << text;
  text.insert(key + 8, example_dir);
  write_bytes(toml, text);
  expect_user_error_words(run_cli("snapshots --case-file " + shell_quote(toml.string()) + " --values 0.02 -q --out " +
                            shell_quote(toml.string())),
                    {"is the input --case-file"});
  EXPECT_EQ(read_bytes(toml), text);
  // mesh --msh D/mesh.msh --out D rewrote its own input.
  const fs::path msh = dir.path() / "mesh.msh";
  fs::copy_file(data("msh/two_squares.msh"), msh);
  expect_user_error_words(run_cli("mesh --msh " + shell_quote(msh.string()) + " --out " + shell_quote(dir.path().string())),
                    {"is the input --msh"});
  EXPECT_EQ(read_bytes(msh), read_bytes(data("msh/two_squares.msh")));
}

// `offline --out d/m.h5` stopped with "the directory of --out does not exist". Every command
// creates the missing parents of its --out (a file's directory, or the output directory itself),
// as `mkdir -p` would; what it writes lands there.
TEST_F(CliFileSafety, OutCreatesEveryMissingParentInEveryCommand) {
  const contactrb::test::TempDir dir("out_parents");
  const auto in = [&](const std::string& path) { return (dir.path() / path).string(); };
  const std::string model = " --model " + shell_quote(model_);
  const std::vector<std::pair<std::string, std::string>> runs = {
      {"solve --case hertz-a --mu 0.3 --out " + shell_quote(in("solve/a/b")), "solve/a/b/solution.json"},
      {"mesh --case hertz-a --out " + shell_quote(in("mesh/a/b")), "mesh/a/b/mesh.msh"},
      {"snapshots --case hertz-a --values 0.2,0.4 --part 1/1 -q --out " + shell_quote(in("snapshots/a/s.h5")),
       "snapshots/a/s.h5"},
      {"merge " + shell_quote(in("snapshots/a/s.h5")) + " --out " + shell_quote(in("merge/a/m.h5")), "merge/a/m.h5"},
      {"offline --snapshots " + shell_quote(snapshots_) + " --out " + shell_quote(in("offline/a/m.h5")),
       "offline/a/offline.json"},
      {"online" + model + " --mu 0.3 --out " + shell_quote(in("online/a/b")), "online/a/b/solution.vtu"},
      {"sample" + model + " --n 5 --no-plot --points " + shell_quote(in("points/a/p.csv")) + " --out " +
           shell_quote(in("sample/a/s.csv")),
       "sample/a/s.csv"},
      {"evaluate" + model + " --set training --repeats 1 -q --out " + shell_quote(in("evaluate/a/b")),
       "evaluate/a/b/evaluation.csv"},
      {"report --case hertz-a --max-training 3 --max-verification 0 --no-plots -q --out " +
           shell_quote(in("report/a/b")),
       "report/a/b/report.md"},
  };
  for (const auto& [command, written] : runs) {
    const CliResult r = run_cli(command);
    ASSERT_EQ(r.exit_code, 0) << command << "\n" << r.out << r.err;
    EXPECT_TRUE(fs::is_regular_file(dir.path() / written)) << command;
  }
  EXPECT_TRUE(fs::is_regular_file(dir.path() / "points/a/p.csv"));
}

// The model named like its sibling offline.json or snapshots.h5 was overwritten by it,
// and "wrote" was printed for both.
TEST(CliOutputSafety, ModelNamedLikeItsSiblingIsRefused) {
  const contactrb::test::TempDir dir("sibling");
  for (const std::string name : {"offline.json", "snapshots.h5"}) {
    const CliResult r = run_cli("offline --case hertz-a --values 0.15,0.3,0.45 -q --out " + shell_quote(dir.file(name)));
    expect_user_error_words(r, {"the outputs --out", name + " next to --out", "are the same file"});
    EXPECT_EQ(r.out.find("wrote"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(dir.path() / name));
  }
}

// A symbolic link, FIFO or device at the output path was replaced by a regular file
// (as root, /dev/null itself; offline.json then went to /dev).
TEST(CliOutputSafety, LinksDevicesAndFifosAreNeverReplaced) {
  const contactrb::test::TempDir dir("special_out");
  const fs::path target = dir.path() / "precious.h5";
  write_bytes(target, "keep me");
  const fs::path link = dir.path() / "link.h5";
  fs::create_symlink(target, link);
  expect_user_error_words(run_cli("snapshots --case hertz-a --values 0.3 -q --out " + shell_quote(link.string())),
                    {"link.h5", "symbolic link"});
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_bytes(target), "keep me");

  const fs::path fifo = dir.path() / "fifo.h5";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_user_error_words(run_cli("snapshots --case hertz-a --values 0.3 -q --out " + shell_quote(fifo.string())),
                    {"fifo.h5", "not a regular file"});
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);

  // A character device: never /dev/null itself (a failing run as root would replace the
  // system's /dev/null and write offline.json into /dev); the same device node made in the
  // test directory when the test may create one (root), where a failure harms nothing.
  const fs::path device = dir.path() / "null";
  if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
    const CliResult r = run_cli("offline --case hertz-a --values 0.15,0.3,0.45 -q --out " + shell_quote(device.string()));
    expect_user_error_words(r, {"null'", "not a regular file"});
    EXPECT_EQ(fs::symlink_status(device).type(), fs::file_type::character);
    EXPECT_FALSE(fs::exists(dir.path() / "offline.json"));
    EXPECT_FALSE(fs::exists(dir.path() / "snapshots.h5"));
  }

  // A link in an output directory (solve writes solution.json there).
  const fs::path out = dir.path() / "solve";
  fs::create_directory(out);
  fs::create_symlink(target, out / "solution.json");
  expect_user_error_words(run_cli("solve --case hertz-a --mu 0.3 --out " + shell_quote(out.string())),
                    {"solution.json", "symbolic link"});
  EXPECT_EQ(read_bytes(target), "keep me");
}

// Two solve runs to the same --out at once left solution.vtu of one beside the json
// and csv of the other (1 in 10). Each file set must be that of one run.
TEST(CliOutputSafety, ConcurrentRunsToOneDirectoryNeverMix) {
  const contactrb::test::TempDir dir("concurrent");
  const std::vector<std::string> mus{"0.2", "0.4"};
  // Reference sets, one run each.
  std::vector<std::string> ref_csv, ref_vtu;
  for (const std::string& mu : mus) {
    const std::string out = dir.file("ref" + mu);
    const CliResult r = run_cli("solve --case hertz-a --mu " + mu + " --out " + shell_quote(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ref_csv.push_back(read_bytes(out + "/multipliers.csv"));
    ref_vtu.push_back(read_bytes(out + "/solution.vtu"));
  }
  const std::string shared = dir.file("shared");
  constexpr int kRounds = 12;
  for (int round = 0; round < kRounds; ++round) {
    auto a = std::async(std::launch::async, [&] { return run_cli("solve --case hertz-a --mu 0.2 --out " + shell_quote(shared)); });
    auto b = std::async(std::launch::async, [&] { return run_cli("solve --case hertz-a --mu 0.4 --out " + shell_quote(shared)); });
    ASSERT_EQ(a.get().exit_code, 0);
    ASSERT_EQ(b.get().exit_code, 0);
    std::ifstream in(shared + "/solution.json");
    const double mu = json::parse(in).at("mu").get<double>();
    const std::size_t k = mu < 0.3 ? 0 : 1;
    EXPECT_EQ(read_bytes(shared + "/multipliers.csv"), ref_csv[k]) << "round " << round << ": csv of the other run";
    EXPECT_EQ(read_bytes(shared + "/solution.vtu"), ref_vtu[k]) << "round " << round << ": vtu of the other run";
  }
  // No temporary file is left behind.
  for (const fs::directory_entry& e : fs::directory_iterator(shared)) {
    EXPECT_EQ(e.path().filename().string().find("tmp"), std::string::npos) << e.path();
  }
}

// Temporary files of a killed run stayed forever; the next run to the same target
// removes those of dead processes and leaves those of live ones.
TEST(CliOutputSafety, StaleTemporaryFilesOfDeadRunsAreRemoved) {
  const contactrb::test::TempDir dir("stale");
  const fs::path out = dir.path() / "out";
  fs::create_directory(out);
  // 999999999 is above any pid_max (2^22): no such process.
  const fs::path dead = out / "solution.json.contactrb-tmp.999999999.0";
  const fs::path live = out / ("solution.json.contactrb-tmp." + std::to_string(::getpid()) + ".0");
  write_bytes(dead, "partial");
  write_bytes(live, "partial");
  const CliResult r = run_cli("solve --case hertz-a --mu 0.3 --out " + shell_quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));
}

// Control characters of the input were echoed raw (an escape sequence cleared the
// terminal).
TEST(CliMessages, ControlCharactersAreEscaped) {
  const contactrb::test::TempDir dir("control");
  const CliResult r = run_cli("mesh --msh " + shell_quote("a\x1b[2J\x07" "b.msh") + " --out " + shell_quote(dir.file("m")));
  expect_user_error_words(r, {"a\\x1b[2J\\x07b.msh"});
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos);
  EXPECT_EQ(r.err.find('\x07'), std::string::npos);
}

// The out-of-domain message rounded mu to the bound ("0.45 is outside [0.15, 0.45]").
TEST(CliMessages, OutOfDomainValueIsPrintedExactly) {
  const contactrb::test::TempDir dir("domain");
  expect_user_error_words(run_cli("solve --case hertz-a --mu 0.4500000001 --out " + shell_quote(dir.file("o"))),
                    {"mu = 0.4500000001", "outside the domain [0.15, 0.45]"});
}

// `mesh` wrote a mesh whose slave group is empty, which `solve` then refused.
TEST(CliMessages, MeshWithAnEmptySlaveGroupIsRefused) {
  const contactrb::test::TempDir dir("empty_slave");
  const CliResult r = run_cli("mesh --msh " + shell_quote(data("msh/empty_slave.msh")) + " --out " + shell_quote(dir.file("m")));
  expect_user_error_words(r, {"empty_slave.msh", "slave"});
  EXPECT_FALSE(fs::exists(dir.path() / "m" / "mesh.msh"));
}

// `--n -1` was taken as "the maximum" while `--mg -3` was refused: every negative size
// given is refused, leaving the flag out asks for the maximum.
TEST_F(CliFileSafety, NegativeSizesAreRefusedAlike) {
  const std::string m = "online --model " + shell_quote(model_) + " --mu 0.3";
  for (const std::string flag : {"--n", "--r", "--mk", "--mg"}) {
    expect_user_error_words(run_cli(m + " " + flag + " -1"), {flag + " must be >= ", "got -1", "leave it out"});
    expect_user_error_words(run_cli(m + " " + flag + " -3"), {flag + " must be >= ", "got -3"});
  }
  expect_user_error_words(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --n -1 --out " +
                            shell_quote(dir_->file("n.h5"))),
                    {"--n must be >= 1", "got -1"});
  EXPECT_EQ(run_cli(m).exit_code, 0);
}

// Found by the fuzz suite: a snapshot dataset whose damaged header declares more elements
// than the file holds was allocated for, and ended in "internal error: std::bad_alloc". The
// fuzz suite's file (tests/data/h5) is of an older format, now refused for its version before
// any dataset is read; the same damage is made here in a file of the current format: a
// contact_dofs dataset declaring 2^40 elements, none of them stored.
TEST(CliInputBounds, DatasetLargerThanItsFileIsADamagedFile) {
  const contactrb::test::TempDir dir("huge_dataset");
  const std::string snapshots = dir.file("s.h5");
  const CliResult s = run_cli("snapshots --case hertz-a --values 0.3 -q --out " + shell_quote(snapshots));
  ASSERT_EQ(s.exit_code, 0) << s.out << s.err;
  {
    const hid_t file = H5Fopen(snapshots.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    ASSERT_GE(H5Ldelete(file, "/discretization/contact_dofs", H5P_DEFAULT), 0);
    const hsize_t dims[1] = {hsize_t{1} << 40};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    ASSERT_GE(H5Pset_layout(dcpl, H5D_CONTIGUOUS), 0);
    ASSERT_GE(H5Pset_alloc_time(dcpl, H5D_ALLOC_TIME_LATE), 0);  // never written: no storage
    const hid_t set =
        H5Dcreate2(file, "/discretization/contact_dofs", H5T_NATIVE_INT, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    ASSERT_GE(set, 0);
    H5Dclose(set);
    H5Pclose(dcpl);
    H5Sclose(space);
    ASSERT_GE(H5Fclose(file), 0);
    contactrb::seal_file(snapshots);  // a crafted file: the reader's checks behind the seal
  }
  ASSERT_LT(fs::file_size(snapshots), (std::uintmax_t{1} << 40));
  const CliResult r =
      run_cli("offline --snapshots " + shell_quote(snapshots) + " --out " + shell_quote(dir.file("model.h5")));
  expect_user_error_words(r, {"snapshot file", "s.h5", "contact_dofs", "declares more elements than the file can hold"});
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "model.h5"));

  // The fuzz suite's original file: an older format version, refused as such.
  const CliResult old = run_cli("offline --snapshots " + shell_quote(data("h5/snapshot_huge_dataset.h5")) +
                                " --out " + shell_quote(dir.file("old.h5")));
  expect_user_error_words(old, {"snapshot file", "snapshot_huge_dataset.h5", "snapshot format 1 is no longer read",
                                "`contactrb snapshots`"});
  EXPECT_EQ(old.err.find("internal error"), std::string::npos) << old.err;
  EXPECT_FALSE(fs::exists(dir.path() / "old.h5"));
}

}  // namespace

namespace {

// One "contactrb: error:" line naming the full disk, exit 1, never a signal.
void expect_no_space(const CliResult& r) {
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // -1 would be a signal (the exit crash of HDF5)
  EXPECT_EQ(count_lines_starting(r.err, "contactrb: error: "), 1) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace

// A full disk: every HDF5 writer (snapshots, offline, merge) ends with one line and exit 1 (an
// HDF5 file whose flush failed stayed open and crashed the process at exit), the file it
// replaces keeps its content, and no temporary is left.
TEST_F(CliFileSafety, FullDiskHdf5WritesEndWithOneLineAndKeepTheOldFile) {
  const SmallDisk disk(dir_->path() / "full_hdf5");
  if (!disk.mounted()) GTEST_SKIP() << "needs root to mount a 64 KiB tmpfs";
  write_bytes(disk.file("m.h5"), "the earlier model");
  for (int run = 0; run < 3; ++run) {
    expect_no_space(run_cli("snapshots --case hertz-a --values 0.2,0.3 -q --out " + shell_quote(disk.file("s.h5"))));
    expect_no_space(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --out " + shell_quote(disk.file("m.h5"))));
  }
  EXPECT_EQ(read_bytes(disk.file("m.h5")), "the earlier model");
  EXPECT_EQ(disk.entries(), std::vector<std::string>{"m.h5"});
}

// A full disk half way through a set of outputs: none of them appears (solve's solution.json
// saying "converged" without its fields; sample's statistics without their figure).
TEST_F(CliFileSafety, FullDiskLeavesNoPartOfAnOutputSet) {
  const SmallDisk disk(dir_->path() / "full_sets");
  if (!disk.mounted()) GTEST_SKIP() << "needs root to mount a 64 KiB tmpfs";
  const CliResult solve = run_cli("solve --case hertz-a --mu 0.3 --out " + shell_quote(disk.file("sol")));
  EXPECT_EQ(solve.exit_code, 1) << solve.out << solve.err;
  EXPECT_TRUE(fs::is_empty(disk.file("sol"))) << solve.err;
  const CliResult sample = run_cli("sample --model " + shell_quote(model_) + " --n 100 --out " +
                                   shell_quote(disk.file("st.csv")));
  EXPECT_NE(sample.exit_code, 0) << sample.out << sample.err;
  EXPECT_EQ(disk.entries(), std::vector<std::string>{"sol"});
}

// --jobs above the hardware threads is capped with a note (a batch with --jobs 1000000 reserved a
// solver per job: 7 GB before its first line).
TEST_F(CliFileSafety, JobsAboveTheHardwareThreadsAreCappedWithANote) {
  const std::string input = dir_->file("three_lines.txt");
  write_bytes(input, "0.2\n0.3\n0.4\n");
  const CliResult r = run_cli("online --model " + shell_quote(model_) + " --batch " + shell_quote(input) +
                              " --jobs 1000000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lines_of(r.out).size(), 3u) << r.out;
  const std::string threads = std::to_string(std::max(1u, std::thread::hardware_concurrency()));
  EXPECT_NE(r.err.find("contactrb: note: online --jobs 1000000 is above the " + threads +
                       " hardware threads of this machine: using " + threads),
            std::string::npos)
      << r.err;
}
