// The online library alone (docs/rb.md "Layout"): this executable links
// contactrb::online and GoogleTest only (tests/CMakeLists.txt; check_link_closure.sh checks
// what it loads). A model made by the suite's CLI (snapshots and offline, contactrb-full) is
// read and answered here, and the answer must be the full executable's bit for bit; the light
// `contactrb online` must give the same, and its --format csv and npy rows the JSON's numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "support/temp_dir.hpp"

namespace {

using json = nlohmann::json;

struct Result {
  int exit_code = -1;
  std::string out;
};

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// `exe args` through the shell; stdout captured, stderr to `err_file` if given.
Result run(const std::string& exe, const std::string& args, const std::string& err_file = "/dev/null") {
  const std::string cmd = quote(exe) + " " + args + " 2>" + quote(err_file);
  FILE* pipe = ::popen(cmd.c_str(), "r");
  Result r;
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == sep) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

// Bitwise equality of doubles (NaN == NaN).
bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
double number(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

class OnlineOnly : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<contactrb::test::TempDir>("online_only");
    model_ = dir_->file("model.h5");
    const std::string snapshots = dir_->file("s.h5");
    const Result s = run(CONTACTRB_CLI, "snapshots --case hertz-a --values 0.15,0.225,0.3,0.375,0.45 -j 2 -q --out " +
                                         quote(snapshots));
    ASSERT_EQ(s.exit_code, 0) << s.out;
    const Result o = run(CONTACTRB_CLI, "offline --snapshots " + quote(snapshots) + " --out " + quote(model_));
    ASSERT_EQ(o.exit_code, 0) << o.out;
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::unique_ptr<contactrb::test::TempDir> dir_;
  static std::string model_;
};
std::unique_ptr<contactrb::test::TempDir> OnlineOnly::dir_;
std::string OnlineOnly::model_;

void expect_same_vector(const Eigen::VectorXd& v, const json& a, const char* what) {
  ASSERT_EQ(static_cast<std::size_t>(v.size()), a.size()) << what;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    EXPECT_TRUE(same(v(i), a[static_cast<std::size_t>(i)].get<double>())) << what << "[" << i << "]";
  }
}

TEST_F(OnlineOnly, AnswersAsTheFullExecutableBitForBit) {
  const contactrb::model::ReducedModel model = contactrb::io::read_reduced_model_file(model_);
  contactrb::online::OnlineSolver solver(model);
  for (const char* mu : {"0.26", "0.41"}) {  // between training values
    SCOPED_TRACE(mu);
    const contactrb::online::OnlineSolution s = solver.solve(std::strtod(mu, nullptr));
    ASSERT_TRUE(s.converged()) << s.message;
    for (const char* exe : {CONTACTRB_FULL_CLI, CONTACTRB_CLI}) {
      SCOPED_TRACE(exe);
      const Result r = run(exe, "online --model " + quote(model_) + " --mu " + mu);
      ASSERT_EQ(r.exit_code, 0) << r.out;
      const json j = json::parse(r.out);
      EXPECT_TRUE(same(s.energy, j.at("energy").get<double>()));
      EXPECT_TRUE(same(s.contact_force, j.at("contact_force").get<double>()));
      EXPECT_EQ(s.iterations, j.at("iterations").get<int>());
      expect_same_vector(s.u_hat, j.at("u_hat"), "u_hat");
      expect_same_vector(s.lambda_hat, j.at("lambda_hat"), "lambda_hat");
      ASSERT_TRUE(s.estimate.available);
      EXPECT_TRUE(same(s.estimate.energy, j.at("estimate").at("energy").get<double>()));
    }
  }
}

// surface_gap answers for the solver's last solve only: another mu, or a u_hat of the wrong
// size, is refused; the same mu gives the same numbers again (a pure function of the solution).
TEST_F(OnlineOnly, SurfaceGapIsForTheLastSolve) {
  const contactrb::model::ReducedModel model = contactrb::io::read_reduced_model_file(model_);
  contactrb::online::OnlineSolver solver(model);
  const contactrb::cases::Mu mu = contactrb::cases::Mu::Constant(1, 0.26);
  EXPECT_THROW((void)solver.surface_gap(mu, {}), contactrb::Error);  // no solve yet
  const contactrb::online::OnlineSolution s = solver.solve(mu);
  ASSERT_TRUE(s.converged()) << s.message;
  const auto gap = solver.surface_gap(mu, s);
  EXPECT_GT(gap.max, gap.min);
  EXPECT_TRUE(same(gap.max, solver.surface_gap(mu, s).max));
  EXPECT_THROW((void)solver.surface_gap(contactrb::cases::Mu::Constant(1, 0.41), s), contactrb::Error);
  contactrb::online::OnlineSolution shorter = s;
  shorter.u_hat.conservativeResize(s.u_hat.size() - 1);
  EXPECT_THROW((void)solver.surface_gap(mu, shorter), contactrb::Error);
}

// --format csv: one row per line with the JSON line's numbers, the same doubles to the last bit;
// a bad line is a row with status "error" (its message on stderr).
TEST_F(OnlineOnly, CsvRowsHoldTheJsonNumbers) {
  const std::string batch = dir_->file("batch.txt");
  std::ofstream(batch) << "0.2\n0.33\nnot-a-number\n0.44\n";
  const std::string base = "online --model " + quote(model_) + " --batch " + quote(batch);
  const Result j = run(CONTACTRB_CLI, base);
  const std::string err = dir_->file("csv.err");
  const Result c = run(CONTACTRB_CLI, base + " --format csv", err);
  EXPECT_EQ(j.exit_code, 1);  // one bad line
  EXPECT_EQ(c.exit_code, 1);
  const std::vector<std::string> jl = lines_of(j.out), cl = lines_of(c.out);
  ASSERT_EQ(jl.size(), 4u);
  ASSERT_EQ(cl.size(), 5u);
  EXPECT_EQ(cl[0], "line,imposed displacement,status,iterations,energy,contact_force,estimate");
  for (std::size_t k = 0; k < jl.size(); ++k) {
    SCOPED_TRACE(jl[k]);
    const json a = json::parse(jl[k]);
    const std::vector<std::string> f = split(cl[k + 1], ',');
    ASSERT_EQ(f.size(), 7u);
    EXPECT_EQ(std::stoi(f[0]), a.at("line").get<int>());
    if (a.contains("error")) {
      EXPECT_EQ(f[2], "error");
      EXPECT_TRUE(f[1].empty() && f[4].empty());
      continue;
    }
    EXPECT_TRUE(same(number(f[1]), a.at("mu").get<double>()));
    EXPECT_EQ(f[2], a.at("status").get<std::string>());
    EXPECT_EQ(std::stoi(f[3]), a.at("iterations").get<int>());
    EXPECT_TRUE(same(number(f[4]), a.at("energy").get<double>()));
    EXPECT_TRUE(same(number(f[5]), a.at("contact_force").get<double>()));
    EXPECT_TRUE(same(number(f[6]), a.at("estimate").at("energy").get<double>()));
  }
  std::ifstream in(err);
  std::stringstream msg;
  msg << in.rdbuf();
  EXPECT_NE(msg.str().find("batch line 3:"), std::string::npos) << msg.str();
}

// --format npy: read back by NumPy (an independent reader), the same numbers as the JSON lines;
// status as its code (0 converged), -1 and NaN for a bad line.
TEST_F(OnlineOnly, NpyReadByNumpyHoldsTheJsonNumbers) {
  if (std::system("/usr/bin/python3 -c 'import numpy' >/dev/null 2>&1") != 0) GTEST_SKIP() << "no python3 numpy";
  const std::string batch = dir_->file("batch_npy.txt");
  std::ofstream(batch) << "0.18\n1e9\n0.39\n";
  const std::string npy = dir_->file("rows.npy");
  const std::string base = "online --model " + quote(model_) + " --batch " + quote(batch);
  const Result j = run(CONTACTRB_CLI, base);
  const Result n = run(CONTACTRB_CLI, base + " --format npy > " + quote(npy));
  EXPECT_EQ(n.exit_code, 1);  // 1e9 is outside the domain
  const Result py = run("/usr/bin/python3",  // Debian's python3-numpy
                        "-c " + quote("import numpy as np, sys\n"
                                                "a = np.load(sys.argv[1])\n"
                                                "print(a.dtype, a.shape[0], a.shape[1])\n"
                                                "for r in a: print(','.join(repr(float(x)) for x in r))\n") +
                                    " " + quote(npy));
  ASSERT_EQ(py.exit_code, 0) << py.out;
  const std::vector<std::string> pl = lines_of(py.out), jl = lines_of(j.out);
  ASSERT_EQ(pl.size(), 4u) << py.out;
  EXPECT_EQ(pl[0], "float64 3 7");
  ASSERT_EQ(jl.size(), 3u);
  for (std::size_t k = 0; k < jl.size(); ++k) {
    SCOPED_TRACE(jl[k]);
    const json a = json::parse(jl[k]);
    const std::vector<std::string> f = split(pl[k + 1], ',');
    ASSERT_EQ(f.size(), 7u);
    EXPECT_EQ(number(f[0]), a.at("line").get<double>());
    if (a.contains("error")) {
      EXPECT_EQ(number(f[2]), -1.0);
      EXPECT_TRUE(std::isnan(number(f[1])) && std::isnan(number(f[4])));
      continue;
    }
    EXPECT_TRUE(same(number(f[1]), a.at("mu").get<double>()));
    const std::vector<std::string> codes{"converged", "max_iterations", "step_failed", "non_finite"};  // KacanovStatus
    const auto code = std::find(codes.begin(), codes.end(), a.at("status").get<std::string>()) - codes.begin();
    EXPECT_EQ(number(f[2]), static_cast<double>(code));
    EXPECT_EQ(number(f[3]), a.at("iterations").get<double>());
    EXPECT_TRUE(same(number(f[4]), a.at("energy").get<double>()));
    EXPECT_TRUE(same(number(f[5]), a.at("contact_force").get<double>()));
    EXPECT_TRUE(same(number(f[6]), a.at("estimate").at("energy").get<double>()));
  }
}

TEST_F(OnlineOnly, CompactFormatsAreForBatchOnly) {
  const Result r = run(CONTACTRB_CLI, "online --model " + quote(model_) + " --mu 0.3 --format csv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(r.out.empty());
}

// The light front answers `sample` itself (no contactrb-full start): the same files as
// contactrb-full's, bit for bit, on one and two threads.
TEST_F(OnlineOnly, FrontSamplesAsTheFullExecutable) {
  const auto text = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  const std::string m = quote(model_);
  for (const std::string jobs : {"1", "2"}) {
    SCOPED_TRACE(jobs);
    const std::string args = "sample --model " + m + " --n 700 --seed 5 --gaps --no-plot --jobs " + jobs + " --out ";
    const std::string a = dir_->file("front" + jobs + ".csv"), b = dir_->file("full" + jobs + ".csv");
    const Result front = run(CONTACTRB_CLI, args + quote(a) + " --points " + quote(dir_->file("front_points.csv")));
    const Result full = run(CONTACTRB_FULL_CLI, args + quote(b) + " --points " + quote(dir_->file("full_points.csv")));
    ASSERT_EQ(front.exit_code, 0) << front.out;
    ASSERT_EQ(full.exit_code, 0) << full.out;
    EXPECT_EQ(text(a), text(b));
    EXPECT_EQ(text(dir_->file("front" + jobs + "_histograms.csv")), text(dir_->file("full" + jobs + "_histograms.csv")));
    EXPECT_EQ(text(dir_->file("front_points.csv")), text(dir_->file("full_points.csv")));
    EXPECT_EQ(lines_of(text(a)).size(), 1u + 5u + 2u);  // header, 5 outputs, max_gap and min_gap
  }
}

// The front hands everything but a plain `online` or `sample` to contactrb-full: help, version,
// usage errors and other commands print and exit as contactrb-full does (argv[0] aside, both
// named the same); the errors of its own `online` and `sample` are contactrb-full's too.
TEST_F(OnlineOnly, FrontAndFullExecutableAgree) {
  const std::string m = quote(model_);
  for (const std::string& args : std::vector<std::string>{"--help", "--version", "online --help", "online --model " + m + " --mu 0.3 --bogus",
                                 "online --model " + m, "online --model " + m + " --mu 0.3 --format xml",
                                 "online --model " + m + " --mu 7", "cases", "nonsense", "sample --help",
                                 "sample --model " + m + " --n 3 --bogus --out " + quote(dir_->file("b.csv")),
                                 "sample --model " + m + " --n 0 --out " + quote(dir_->file("z.csv")),
                                 "sample --model " + quote(dir_->file("none.h5")) + " --n 3 --out " + quote(dir_->file("n.csv"))}) {
    SCOPED_TRACE(args);
    const std::string err_front = dir_->file("front.err"), err_full = dir_->file("full.err");
    const Result front = run(CONTACTRB_CLI, args, err_front), full = run(CONTACTRB_FULL_CLI, args, err_full);
    EXPECT_EQ(front.exit_code, full.exit_code);
    std::ifstream ef(err_front), eu(err_full);
    std::stringstream sf, su;
    sf << ef.rdbuf();
    su << eu.rdbuf();
    // Usage lines name the program by argv[0]: compare with the paths replaced.
    auto strip = [](std::string t, const std::string& exe) {
      for (std::size_t at = t.find(exe); at != std::string::npos; at = t.find(exe)) t.replace(at, exe.size(), "EXE");
      return t;
    };
    EXPECT_EQ(strip(front.out, CONTACTRB_CLI), strip(full.out, CONTACTRB_FULL_CLI));
    EXPECT_EQ(strip(sf.str(), CONTACTRB_CLI), strip(su.str(), CONTACTRB_FULL_CLI));
  }
}

}  // namespace
