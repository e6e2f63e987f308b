// Many queries (docs/parallel.md): `online --batch --jobs J` prints the serial output, line for
// line (all but time_s); `contactrb sample` gives the same files whatever the number of threads
// (and MPI ranks), its statistics are those of its --points file, its answers those of
// `online`, and its points follow the distribution asked for. One hertz-b model for the suite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "csv_text.hpp"
#include "support/meshio_reader.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::file_text;
using contactrb::test::read_csv;
using contactrb::test::expect_user_error;
using contactrb::test::lines_of;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;
using nlohmann::json;

namespace {


class CliManyQueries : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<contactrb::test::TempDir>("many_queries");
    model_ = dir_->file("model.h5");
    const CliResult r = run_cli("offline --case hertz-b -q --out " + shell_quote(model_));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  }
  static void TearDownTestSuite() { dir_.reset(); }
  static CliResult sample(const std::string& args) { return run_cli("sample --model " + shell_quote(model_) + " " + args); }
  static std::unique_ptr<contactrb::test::TempDir> dir_;
  static std::string model_;
};
std::unique_ptr<contactrb::test::TempDir> CliManyQueries::dir_;
std::string CliManyQueries::model_;

// The JSON lines without their timing.
// stderr without the note of a --jobs above the hardware threads (capped: 3 jobs on a 2-thread
// machine run on 2).
std::string without_jobs_note(const std::string& err) {
  std::istringstream in(err);
  std::string kept, line;
  while (std::getline(in, line)) {
    if (line.rfind("contactrb: note: online --jobs ", 0) != 0) kept += line + "\n";
  }
  return kept;
}

std::vector<std::string> without_time(const std::string& out) {
  std::vector<std::string> lines;
  for (const std::string& l : lines_of(out)) {
    json j = json::parse(l);
    j.erase("time_s");
    lines.push_back(j.dump());
  }
  return lines;
}

// A batch file of 700 lines: 0.9 + 0.22 frac(step i), inside hertz-b's domain [0.9, 1.12], with
// line i replaced by special(i) where that is not empty (bad lines, values outside the domain).
void write_batch(const std::string& path, double step, const std::function<std::string(int)>& special) {
  std::ofstream f(path);
  for (int i = 0; i < 700; ++i) {
    const std::string text = special(i);
    if (!text.empty()) {
      f << text << "\n";
    } else {
      f << 0.9 + 0.22 * std::fmod(step * i, 1.0) << "\n";
    }
  }
}

}  // namespace

TEST_F(CliManyQueries, ThreadedBatchPrintsTheSerialOutput) {
  // 700 lines (more than one chunk of 2 x 64 and 3 x 64 lines), bad lines and a value outside
  // the domain [0.9, 1.12] among them.
  const std::string batch = dir_->file("batch.txt");
  write_batch(batch, 0.618033988749895, [](int i) -> std::string {
    if (i % 97 == 5) return "not-a-number";
    return i == 333 ? "1.5" : "";
  });
  const std::string args = "online --model " + shell_quote(model_) + " --batch " + shell_quote(batch);
  const CliResult serial = run_cli(args);
  EXPECT_EQ(serial.exit_code, 1) << serial.err;  // the bad lines
  const std::vector<std::string> expected = without_time(serial.out);
  ASSERT_EQ(expected.size(), 700u);
  EXPECT_NE(expected[5].find("\"error\""), std::string::npos) << expected[5];
  EXPECT_NE(expected[333].find("\"error\""), std::string::npos) << expected[333];
  EXPECT_NE(expected[0].find("\"contact_force\""), std::string::npos) << expected[0];
  for (int jobs : {2, 3}) {
    const CliResult r = run_cli(args + " --jobs " + std::to_string(jobs));
    EXPECT_EQ(r.exit_code, serial.exit_code) << jobs;
    EXPECT_EQ(without_jobs_note(r.err), serial.err) << jobs;
    const std::vector<std::string> got = without_time(r.out);
    ASSERT_EQ(got.size(), expected.size()) << jobs;
    for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], expected[i]) << "line " << i + 1 << ", jobs " << jobs;
  }
}

// --format csv and npy on threads: the serial run's bytes (no timing in them), from a file and
// through a pipe (stdin), with bad lines among 700; the npy rows checked apart: one per line,
// in input order, and the CSV's numbers.
TEST_F(CliManyQueries, ThreadedCompactFormatsAreTheSerialBytes) {
  const std::string batch = dir_->file("batch_compact.txt");
  write_batch(batch, 0.414213562373095, [](int i) -> std::string { return i % 101 == 7 ? "x" : ""; });
  const std::string model = "online --model " + shell_quote(model_);
  std::map<std::string, std::string> serial_out;
  for (const std::string format : {"csv", "npy"}) {
    const CliResult serial = run_cli(model + " --batch " + shell_quote(batch) + " --format " + format);
    EXPECT_EQ(serial.exit_code, 1) << serial.err;  // the bad lines
    EXPECT_NE(serial.err.find("batch line 8:"), std::string::npos) << serial.err;
    serial_out[format] = serial.out;
    for (int jobs : {2, 3}) {
      const std::string j = " --jobs " + std::to_string(jobs) + " --format " + format;
      const CliResult file = run_cli(model + " --batch " + shell_quote(batch) + j);
      EXPECT_EQ(file.exit_code, 1) << format << jobs;
      EXPECT_EQ(without_jobs_note(file.err), serial.err) << format << jobs;
      EXPECT_TRUE(file.out == serial.out) << format << ", jobs " << jobs << ": the output differs";
      const CliResult pipe =
          contactrb::test::run_shell("cat " + shell_quote(batch) + " | " + shell_quote(CONTACTRB_CLI) + " " + model + " --batch -" + j);
      EXPECT_EQ(pipe.exit_code, 1) << format << jobs;
      EXPECT_TRUE(pipe.out == serial.out) << format << ", jobs " << jobs << ", stdin: the output differs";
    }
  }
  // npy: a 10-byte preamble, the header (shape (700, 7)), then 700 rows of 7 float64.
  const std::string& npy = serial_out["npy"];
  ASSERT_GT(npy.size(), 10u);
  const std::size_t header = static_cast<unsigned char>(npy[8]) + 256 * static_cast<unsigned char>(npy[9]);
  EXPECT_NE(npy.find("'shape': (700, 7)"), std::string::npos);
  ASSERT_EQ(npy.size(), 10 + header + 700 * 7 * sizeof(double));
  const std::vector<std::string> csv = lines_of(serial_out["csv"]);
  ASSERT_EQ(csv.size(), 701u);  // the header line, then one row per line
  for (std::size_t i = 0; i < 700; ++i) {
    double row[7];
    std::memcpy(row, npy.data() + 10 + header + i * sizeof row, sizeof row);
    EXPECT_EQ(row[0], static_cast<double>(i + 1));
    const std::vector<std::string> cells = contactrb::test::split_csv_line(csv[i + 1]);
    ASSERT_EQ(cells.size(), 7u) << csv[i + 1];
    EXPECT_EQ(cells[0], std::to_string(i + 1));
    if (i % 101 == 7) {
      EXPECT_EQ(cells[2], "error");
      EXPECT_EQ(row[2], -1.0);
      EXPECT_TRUE(std::isnan(row[1]));
    } else {
      EXPECT_EQ(row[1], std::stod(cells[1])) << i;  // mu: shortest round-trip text
      EXPECT_EQ(row[4], std::stod(cells[4])) << i;  // energy
      EXPECT_EQ(row[5], std::stod(cells[5])) << i;  // contact_force
    }
  }
}

// Statistics against the --points file, answers against `online`, threads against one thread.
TEST_F(CliManyQueries, SampleStatisticsAreThoseOfItsPoints) {
  const std::string s1 = dir_->file("u1.csv"), p1 = dir_->file("u1_points.csv");
  const CliResult one = sample("--n 3000 --seed 11 --jobs 1 --no-plot --out " + shell_quote(s1) + " --points " + shell_quote(p1));
  ASSERT_EQ(one.exit_code, 0) << one.out << one.err;
  const std::string s2 = dir_->file("u2.csv"), p2 = dir_->file("u2_points.csv");
  const CliResult two = sample("--n 3000 --seed 11 --jobs 2 --no-plot --out " + shell_quote(s2) + " --points " + shell_quote(p2));
  ASSERT_EQ(two.exit_code, 0) << two.out << two.err;
  EXPECT_EQ(file_text(s1), file_text(s2));
  EXPECT_EQ(file_text(p1), file_text(p2));
  EXPECT_EQ(file_text(dir_->file("u1_histograms.csv")), file_text(dir_->file("u2_histograms.csv")));
  EXPECT_FALSE(fs::exists(dir_->file("u1.png")));  // --no-plot

  auto points = read_csv(p1);
  const std::vector<std::string>& mu_text = points["lower radius R2"];
  ASSERT_EQ(mu_text.size(), 3000u);
  // Uniform on [0.9, 1.12]: inside, and the mean within 4 standard errors of the middle.
  double mean_mu = 0.0;
  for (const std::string& m : mu_text) {
    const double x = std::stod(m);
    EXPECT_GE(x, 0.9);
    EXPECT_LE(x, 1.12);
    mean_mu += x / 3000.0;
  }
  EXPECT_NEAR(mean_mu, 1.01, 4.0 * 0.22 / std::sqrt(12.0 * 3000.0));

  // stats.csv: count, min, max, mean and median of each output recomputed from the points.
  const auto stats = read_csv(s1);
  const std::vector<std::string>& names = stats.at("output");
  ASSERT_EQ(names, (std::vector<std::string>{"contact_force", "peak_pressure", "energy", "estimate", "iterations"}));
  for (std::size_t k = 0; k < names.size(); ++k) {
    std::vector<double> v;
    for (const std::string& c : points[names[k]]) {
      if (!c.empty()) v.push_back(std::stod(c));
    }
    ASSERT_EQ(std::to_string(v.size()), stats.at("count")[k]) << names[k];
    double mean = 0.0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    std::sort(v.begin(), v.end());
    EXPECT_EQ(std::stod(stats.at("min")[k]), v.front()) << names[k];
    EXPECT_EQ(std::stod(stats.at("max")[k]), v.back()) << names[k];
    EXPECT_NEAR(std::stod(stats.at("mean")[k]), mean, 1e-12 * std::abs(mean)) << names[k];
    EXPECT_EQ(std::stod(stats.at("q50")[k]), 0.5 * (v[1499] + v[1500])) << names[k];
  }
  // The histogram of each output counts every value once.
  const auto hist = read_csv(dir_->file("u1_histograms.csv"));
  long long total = 0;
  for (std::size_t i = 0; i < hist.at("output").size(); ++i) {
    if (hist.at("output")[i] == "contact_force") total += std::stoll(hist.at("count")[i]);
  }
  EXPECT_EQ(total, 3000);

  // The first 25 points answered by `online --batch`: the same contact force, to the bit.
  const std::string batch = dir_->file("points_batch.txt");
  {
    std::ofstream f(batch);
    for (int i = 0; i < 25; ++i) f << mu_text[static_cast<std::size_t>(i)] << "\n";
  }
  const CliResult online = run_cli("online --model " + shell_quote(model_) + " --batch " + shell_quote(batch));
  ASSERT_EQ(online.exit_code, 0) << online.err;
  const std::vector<std::string> answers = lines_of(online.out);
  ASSERT_EQ(answers.size(), 25u);
  for (std::size_t i = 0; i < answers.size(); ++i) {
    EXPECT_EQ(json::parse(answers[i]).at("contact_force").get<double>(), std::stod(points["contact_force"][i])) << i;
  }
}

// max_gap and min_gap of `sample` (the deformed normal gap over the slave nodes, from the
// model's contact surface) against the gap field of the reconstructed solution on the HF mesh
// (`online --mu --out`, contact.vtu, read by meshio): another code path to the same numbers.
TEST_F(CliManyQueries, SampleGapsAreThoseOfTheReconstructedSolution) {
  SKIP_WITHOUT_MESHIO();
  const std::string s = dir_->file("g.csv"), p = dir_->file("g_points.csv");
  const CliResult r = sample("--n 3 --seed 3 --gaps --no-plot --out " + shell_quote(s) + " --points " + shell_quote(p));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  auto points = read_csv(p);
  ASSERT_EQ(points["max_gap"].size(), 3u);
  EXPECT_EQ(read_csv(s).at("output"),
            (std::vector<std::string>{"contact_force", "peak_pressure", "max_gap", "min_gap", "energy", "estimate", "iterations"}));
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string out = dir_->file("g" + std::to_string(i));
    const CliResult o = run_cli("online --model " + shell_quote(model_) + " --mu " + points["lower radius R2"][i] +
                                " --out " + shell_quote(out));
    ASSERT_EQ(o.exit_code, 0) << o.out << o.err;
    const json f = contactrb::test::read_vtu_with_meshio(fs::path(out) / "contact.vtu");
    ASSERT_FALSE(f.is_null());
    const std::vector<double> gap = f["point_data"]["gap"].get<std::vector<double>>();
    ASSERT_GT(gap.size(), 10u);
    const double max = *std::max_element(gap.begin(), gap.end()), min = *std::min_element(gap.begin(), gap.end());
    EXPECT_NEAR(std::stod(points["max_gap"][i]), max, 1e-12 * std::abs(max)) << i;
    EXPECT_NEAR(std::stod(points["min_gap"][i]), min, 1e-12) << i;
    EXPECT_GT(max, 0.5);   // the slave chain's open end
    EXPECT_LT(min, 1e-3);  // in contact
  }
}

TEST_F(CliManyQueries, NormalSampleAndFigure) {
  const std::string s = dir_->file("n.csv"), p = dir_->file("n_points.csv");
  const CliResult r = sample("--n 2000 --dist normal:1.0:0.02 --seed 5 --out " + shell_quote(s) + " --points " + shell_quote(p));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  auto points = read_csv(p);
  double mean = 0.0, m2 = 0.0;
  for (const std::string& m : points["lower radius R2"]) mean += std::stod(m) / 2000.0;
  for (const std::string& m : points["lower radius R2"]) m2 += std::pow(std::stod(m) - mean, 2) / 1999.0;
  EXPECT_NEAR(mean, 1.0, 4.0 * 0.02 / std::sqrt(2000.0));
  EXPECT_NEAR(std::sqrt(m2), 0.02, 0.002);  // the standard error of a sd is sd / sqrt(2 n) = 3e-4
  // The figure: a PNG file.
  const std::string png = file_text(dir_->file("n.png"));
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST_F(CliManyQueries, SampleUserErrors) {
  const std::string out = " --no-plot --out " + shell_quote(dir_->file("e.csv"));
  expect_user_error(sample("--n 10 --dist normal:2:0.1" + out), "the mean of lower radius R2 is outside the model's domain");
  expect_user_error(sample("--n 10 --dist normal:1:0" + out), "standard deviation of lower radius R2 must be > 0");
  expect_user_error(sample("--n 10 --dist gamma" + out), "expected uniform, normal, or normal:MEAN:SD");
  expect_user_error(sample("--n 10 --dist normal:1:0.1,1:0.1" + out), "2 MEAN:SD pairs for 1 parameter");
  expect_user_error(sample("--n 0" + out), "--n must be >= 1");
  expect_user_error(sample("--n 10 --no-plot --out " + shell_quote(dir_->file("e.txt"))), "expected a .csv file name");
  EXPECT_FALSE(fs::exists(dir_->file("e.csv")));
}

TEST_F(CliManyQueries, SampleUnderMpirunEqualsSerial) {
  if (std::string(CONTACTRB_MPIEXEC).empty()) {
    GTEST_SKIP() << "this build has no MPI (CONTACTRB_WITH_MPI off or no MPI C library found)";
  }
  const std::string serial = dir_->file("m1.csv"), parallel = dir_->file("m2.csv");
  ASSERT_EQ(sample("--n 1001 --seed 2 --jobs 1 --no-plot --out " + shell_quote(serial)).exit_code, 0);
  const CliResult r = contactrb::test::run_shell(
      "timeout 300 " + shell_quote(CONTACTRB_MPIEXEC) + " --oversubscribe -np 2 " + shell_quote(CONTACTRB_CLI) +
          " sample --model " + shell_quote(model_) + " --n 1001 --seed 2 --jobs 1 --no-plot --out " + shell_quote(parallel),
      "", contactrb::test::mpirun_environment());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("2 MPI ranks"), std::string::npos) << r.out;
  EXPECT_EQ(file_text(serial), file_text(parallel));
  EXPECT_EQ(file_text(dir_->file("m1_histograms.csv")), file_text(dir_->file("m2_histograms.csv")));
}

TEST_F(CliManyQueries, BatchUnderMpirunPrintsTheSerialOutput) {
  if (std::string(CONTACTRB_MPIEXEC).empty()) {
    GTEST_SKIP() << "this build has no MPI (CONTACTRB_WITH_MPI off or no MPI C library found)";
  }
  const std::string batch = dir_->file("mpi_batch.txt");
  {
    std::ofstream f(batch);
    for (int i = 0; i < 300; ++i) f << (i == 7 ? std::string("x") : std::to_string(0.9 + 0.22 * std::fmod(0.37 * i, 1.0))) << "\n";
  }
  const std::string args = "online --model " + shell_quote(model_) + " --batch " + shell_quote(batch);
  const CliResult serial = run_cli(args);
  EXPECT_EQ(serial.exit_code, 1) << serial.err;  // line 8
  const CliResult r = contactrb::test::run_shell("timeout 300 " + shell_quote(CONTACTRB_MPIEXEC) +
                                                     " --oversubscribe -np 2 " + shell_quote(CONTACTRB_CLI) + " " + args,
                                                 "", contactrb::test::mpirun_environment());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.exit_code, 124) << "timed out: a hang";
  EXPECT_NE(r.err.find("1 of 300 batch lines could not be answered"), std::string::npos) << r.err;
  EXPECT_EQ(without_time(r.out), without_time(serial.out));
}
