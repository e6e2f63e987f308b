// A row-cone model (`offline --dual rows`, docs/offline-online.md, "The row cone") through the
// commands that answer many queries: `sample` answers as `online`, its peak pressure is the largest
// reduced multiplier (one unit generator per kept row); `evaluate --iteration newton` answers as
// `online --iteration newton` and holds every HF pressure in the cone; `online --batch` under
// mpirun prints the serial lines, with either iteration. One hertz-b model for the suite.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "csv_text.hpp"
#include "mpi_runner.hpp"
#include "support/temp_dir.hpp"

using contactrb::test::CliResult;
using contactrb::test::file_text;
using contactrb::test::read_csv;
using contactrb::test::expect_user_error;
using contactrb::test::lines_of;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;
using nlohmann::json;

namespace {

// The JSON lines without their timing.
std::vector<std::string> without_time(const std::string& out) {
  std::vector<std::string> lines;
  for (const std::string& l : lines_of(out)) {
    json j = json::parse(l);
    j.erase("time_s");
    lines.push_back(j.dump());
  }
  return lines;
}

class CliRowCone : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<contactrb::test::TempDir>("row_cone");
    snapshots_ = dir_->file("snapshots.h5");
    model_ = dir_->file("model.h5");
    const CliResult s = run_cli("snapshots --case hertz-b -q --out " + shell_quote(snapshots_));
    ASSERT_EQ(s.exit_code, 0) << s.out << s.err;
    const CliResult r = run_cli("offline --snapshots " + shell_quote(snapshots_) + " --dual rows --out " + shell_quote(model_));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  }
  static void TearDownTestSuite() { dir_.reset(); }
  // `online --batch` at the values of a file, one JSON object per line.
  static std::vector<json> online_batch(const std::string& batch, const std::string& extra = "") {
    const CliResult r = run_cli("online --model " + shell_quote(model_) + " --batch " + shell_quote(batch) + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<json> out;
    for (const std::string& l : lines_of(r.out)) out.push_back(json::parse(l));
    return out;
  }
  static std::unique_ptr<contactrb::test::TempDir> dir_;
  static std::string snapshots_, model_;
};
std::unique_ptr<contactrb::test::TempDir> CliRowCone::dir_;
std::string CliRowCone::snapshots_, CliRowCone::model_;

}  // namespace

TEST_F(CliRowCone, SampleAnswersAsOnlineAndItsPeakIsTheLargestRowPressure) {
  const std::string stats = dir_->file("sample.csv"), points = dir_->file("sample_points.csv");
  const CliResult r = run_cli("sample --model " + shell_quote(model_) + " --n 40 --seed 4 --jobs 1 --no-plot --out " +
                              shell_quote(stats) + " --points " + shell_quote(points));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  auto p = read_csv(points);
  const std::vector<std::string>& mu = p["lower radius R2"];
  ASSERT_EQ(mu.size(), 40u);
  const std::string batch = dir_->file("sample_batch.txt");
  {
    std::ofstream f(batch);
    for (const std::string& m : mu) f << m << "\n";
  }
  const std::vector<json> answers = online_batch(batch);
  ASSERT_EQ(answers.size(), 40u);
  for (std::size_t i = 0; i < answers.size(); ++i) {
    const json& a = answers[i];
    ASSERT_TRUE(a.at("converged").get<bool>()) << i;
    EXPECT_EQ(a.at("contact_force").get<double>(), std::stod(p["contact_force"][i])) << i;
    EXPECT_EQ(a.at("energy").get<double>(), std::stod(p["energy"][i])) << i;
    EXPECT_EQ(a.at("estimate").at("energy").get<double>(), std::stod(p["estimate"][i])) << i;
    // The row cone's generators are the unit rows: the reconstructed pressure is lambda_hat itself.
    const std::vector<double> lambda = a.at("lambda_hat").get<std::vector<double>>();
    ASSERT_FALSE(lambda.empty());
    EXPECT_GE(*std::min_element(lambda.begin(), lambda.end()), 0.0) << i;
    EXPECT_EQ(*std::max_element(lambda.begin(), lambda.end()), std::stod(p["peak_pressure"][i])) << i;
  }
  // The peak of one answer against the pressure written on the HF rows (`online --out`).
  const std::string out = dir_->file("one");
  ASSERT_EQ(run_cli("online --model " + shell_quote(model_) + " --mu " + mu[0] + " --out " + shell_quote(out)).exit_code, 0);
  auto rows = read_csv(out + "/multipliers.csv");
  ASSERT_FALSE(rows["lambda"].empty());
  double peak = 0.0;
  for (const std::string& c : rows["lambda"]) peak = std::max(peak, std::stod(c));
  EXPECT_EQ(peak, std::stod(p["peak_pressure"][0]));
}

TEST_F(CliRowCone, EvaluateWithTheNewtonAnswersAsOnlineNewton) {
  const std::string values = dir_->file("values.txt");
  {
    std::ofstream f(values);
    f << "0.91\n1.0\n1.115\n";
  }
  const std::string out = dir_->file("ev");
  const CliResult r = run_cli("evaluate --model " + shell_quote(model_) + " --set " + shell_quote(values) +
                              " --iteration newton --repeats 1 -q --out " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json j = json::parse(file_text(out + "/evaluation.json"));
  EXPECT_EQ(j.at("iteration"), "newton");
  auto e = read_csv(out + "/evaluation.csv");
  const std::vector<json> answers = online_batch(values, " --iteration newton");
  ASSERT_EQ(answers.size(), 3u);
  ASSERT_EQ(e["estimate"].size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(std::stod(e["estimate"][i]), answers[i].at("estimate").at("energy").get<double>()) << i;
    EXPECT_EQ(std::stoi(e["rb_iterations"][i]), answers[i].at("iterations").get<int>()) << i;
    // Every HF pressure lies in the row cone; the reduced one is within 1e-2 of it (the Newton's
    // answer satisfies the contact conditions at its rows).
    EXPECT_EQ(std::stod(e["e_press_cone"][i]), 0.0) << i;
    EXPECT_LT(std::stod(e["e_press"][i]), 1e-2) << i;
    EXPECT_LT(std::stod(e["e_displ"][i]), 1e-3) << i;
  }
  // The default iteration answers otherwise (it stops on the fixed-point test): the flag is used.
  const CliResult d = run_cli("evaluate --model " + shell_quote(model_) + " --set " + shell_quote(values) +
                              " --repeats 1 -q --out " + shell_quote(dir_->file("ev_default")));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_EQ(json::parse(file_text(dir_->file("ev_default") + "/evaluation.json")).at("iteration"), "automatic");
  EXPECT_NE(read_csv(dir_->file("ev_default") + "/evaluation.csv")["estimate"], e["estimate"]);
}

TEST_F(CliRowCone, NewtonOnAGlobalConeIsAUserError) {
  const std::string cpg = dir_->file("cpg.h5");
  ASSERT_EQ(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --dual cpg --out " + shell_quote(cpg)).exit_code, 0);
  expect_user_error(run_cli("evaluate --model " + shell_quote(cpg) + " --iteration newton -q --out " +
                            shell_quote(dir_->file("ev_cpg"))),
                    "--iteration newton needs a model built with `contactrb offline --dual rows` (its dual cone is 'cpg')");
  expect_user_error(run_cli("evaluate --model " + shell_quote(model_) + " --iteration fast -q --out " +
                            shell_quote(dir_->file("ev_fast"))),
                    "--iteration: ");
}

TEST_F(CliRowCone, BatchUnderMpirunPrintsTheSerialOutput) {
  SKIP_WITHOUT_MPI();
  const std::string batch = dir_->file("mpi_batch.txt");
  {
    std::ofstream f(batch);
    for (int i = 0; i < 60; ++i) f << 0.9 + 0.22 * (0.37 * i - static_cast<int>(0.37 * i)) << "\n";
  }
  for (const std::string iteration : {"automatic", "newton"}) {
    const std::string args = "online --model " + shell_quote(model_) + " --batch " + shell_quote(batch) + " --iteration " + iteration;
    const CliResult serial = run_cli(args);
    ASSERT_EQ(serial.exit_code, 0) << serial.err;
    const CliResult r = contactrb::test::mpirun(2, args);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_EQ(lines_of(r.out).size(), 60u) << iteration;
    EXPECT_EQ(without_time(r.out), without_time(serial.out)) << iteration;
  }
}
