// contactrb offline / online: a small hertz-a snapshot file made with the CLI, an untruncated
// model, online answers against `contactrb solve` at a training value, batch mode (n lines in,
// n JSON lines out, bad lines answered by error lines) and the user errors. The snapshot file
// and the model are made once for the suite.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::field_value;
using contactrb::test::lines_of;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;
using nlohmann::json;

namespace {



// Training values: 0.3 is one of them. Tight Kacanov settings so that the untruncated model
// reproduces the HF solutions to solver tolerance.
constexpr const char* kValues = "0.15,0.225,0.3,0.375,0.45";
constexpr const char* kTight = " --alpha 1 --tol 1e-10";

class CliOfflineOnline : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<contactrb::test::TempDir>("offline_online");
    snapshots_ = dir_->file("s.h5");
    model_ = dir_->file("model.h5");
    const CliResult s = run_cli(std::string("snapshots --case hertz-a --values ") + kValues + kTight +
                                " -j 2 -q --out " + shell_quote(snapshots_));
    ASSERT_EQ(s.exit_code, 0) << s.out << s.err;
    offline_ = run_cli("offline --snapshots " + shell_quote(snapshots_) +
                       " --dual cpg --n 100 --eps-du 0 --eps-eim-k 0 --eps-eim-g 0 --out " + shell_quote(model_));
    ASSERT_EQ(offline_.exit_code, 0) << offline_.out << offline_.err;
  }
  static void TearDownTestSuite() { dir_.reset(); }

  // contact_force of the HF solve at mu (with extra options).
  static double hf_contact_force(double mu, const std::string& extra) {
    const std::string out = dir_->file("hf");
    const CliResult r =
        run_cli("solve --case hertz-a --mu " + std::to_string(mu) + extra + " --out " + shell_quote(out));
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    std::ifstream in(out + "/solution.json");
    return json::parse(in).at("contact_force").get<double>();
  }

  static std::unique_ptr<contactrb::test::TempDir> dir_;
  static std::string snapshots_, model_;
  static CliResult offline_;
};
std::unique_ptr<contactrb::test::TempDir> CliOfflineOnline::dir_;
std::string CliOfflineOnline::snapshots_, CliOfflineOnline::model_;
CliResult CliOfflineOnline::offline_;

}  // namespace

TEST_F(CliOfflineOnline, OfflineWritesTheModelTheReportAndASummary) {
  EXPECT_NE(offline_.out.find("wrote " + model_), std::string::npos) << offline_.out;
  ASSERT_TRUE(fs::exists(dir_->file("offline.json")));
  std::ifstream in(dir_->file("offline.json"));
  const json j = json::parse(in);
  EXPECT_EQ(j.at("case"), "hertz-a");
  // Every POD mode of the 5 snapshots, then one supremizer per dual generator (those that add a
  // direction): N = 5 + supremizers, R of them at most.
  EXPECT_EQ(j.at("pod").at("N"), 5);
  EXPECT_TRUE(j.at("supremizers").at("enabled").get<bool>());
  const int sup = j.at("supremizers").at("count").get<int>();
  EXPECT_GE(sup, 1);
  EXPECT_LE(sup, j.at("sizes").at("R").get<int>());
  EXPECT_EQ(j.at("sizes").at("N"), 5 + sup);
  EXPECT_EQ(field_value(offline_.out, "sizes").rfind("N " + std::to_string(5 + sup) + ", R ", 0), 0u) << offline_.out;
  EXPECT_NE(field_value(offline_.out, "pod").find("+ " + std::to_string(sup) + " supremizers"), std::string::npos)
      << offline_.out;
  EXPECT_EQ(j.at("pod").at("singular_values").size(), 5u);
  const int R = j.at("sizes").at("R").get<int>();
  EXPECT_GE(R, 1);
  EXPECT_EQ(j.at("dual").at("errors").size(), static_cast<std::size_t>(R + 1));
  EXPECT_EQ(j.at("eim_kappa").at("M"), j.at("sizes").at("Mk"));
  EXPECT_GE(j.at("eim_gamma").at("errors").size(), 1u);
  EXPECT_LT(j.at("compression").at("kept").get<int>(), j.at("compression").at("constraints").get<int>());
  for (const char* key : {"read", "pod", "dual", "eim_kappa", "eim_gamma", "reduction", "write", "total"}) {
    EXPECT_GE(j.at("times_s").at(key).get<double>(), 0.0) << key;
  }
}

// --eps-du-relative: CPG stops at the first R whose largest relative error (each mu's (58)
// divided by its |lambda(mu)|) is within eps_DU; the absolute history is not what stops it.
// At the command line: an eps_DU that no cone reaches is said so (an exhausted NMF reports
// the error of the rank it keeps), and
// an EIM tolerance above every value (M^k = 0 or M^g = 0) is refused before a model is written.
TEST_F(CliOfflineOnline, UnreachedDualToleranceAndEmptyEIMAreReported) {
  contactrb::test::TempDir own("offline_unreached");  // its own offline.json
  const std::string m = own.file("unreached.h5");
  // (The angle-greedy's case needs more snapshots than these 5, which it selects all:
  // AngleGreedy.StopsOnTheTrueConeErrorNotTheLinearOne in tests/offline.)
  for (const char* dual : {"nmf"}) {
    const CliResult r = run_cli("offline --snapshots " + shell_quote(snapshots_) + " --dual " + dual +
                                " --eps-du 1e-9 --out " + shell_quote(m));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    const std::string line = field_value(r.out, "dual");
    EXPECT_NE(line.find("training set exhausted: eps_du NOT reached"), std::string::npos) << dual << ": " << r.out;
    std::ifstream in(own.file("offline.json"));
    const json j = json::parse(in);
    const int R = j.at("sizes").at("R").get<int>();
    EXPECT_GT(j.at("dual").at("errors").at(static_cast<std::size_t>(R)).get<double>(), 1e-9) << dual;
  }
  const std::string refused = own.file("refused.h5");
  for (const char* option : {" --eps-eim-k 1e9", " --eps-eim-g 1e9"}) {
    const CliResult r =
        run_cli("offline --snapshots " + shell_quote(snapshots_) + " --dual cpg" + option + " --out " + shell_quote(refused));
    EXPECT_EQ(r.exit_code, 1) << option << ": " << r.out << r.err;
    EXPECT_NE(r.err.find(std::string(option).find("-k") != std::string::npos ? "M^k = 0" : "M^g = 0"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(refused)) << option;
  }
}

TEST_F(CliOfflineOnline, RelativeDualToleranceStopsOnTheRelativeHistory) {
  const std::string out = dir_->file("relative");
  fs::create_directories(out);
  const double eps = 0.05;
  const CliResult r = run_cli("offline --snapshots " + shell_quote(snapshots_) +
                              " --n 100 --eps-du 0.05 --eps-du-relative --out " + shell_quote(out + "/model.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(field_value(r.out, "dual").find("relative"), std::string::npos) << r.out;
  std::ifstream in(out + "/offline.json");
  const json j = json::parse(in);
  EXPECT_TRUE(j.at("settings").at("eps_du_relative").get<bool>());
  const auto rel = j.at("dual").at("relative_errors").get<std::vector<double>>();
  const auto abs = j.at("dual").at("errors").get<std::vector<double>>();
  const int R = j.at("sizes").at("R").get<int>();
  ASSERT_EQ(rel.size(), static_cast<std::size_t>(R + 1));
  ASSERT_GE(R, 2);
  EXPECT_LE(rel[static_cast<std::size_t>(R)], eps);
  EXPECT_GT(rel[static_cast<std::size_t>(R - 1)], eps);
  EXPECT_NEAR(rel[0], 1.0, 1e-12);  // nothing selected: every multiplier is its own error
  EXPECT_GT(abs[0], 1.0);           // the absolute history is on another scale (pressures ~ 1-10)
}

// The tolerances are relative by default (POD: sigma_i / sigma_1 > eps; EIM: to max |f| over
// the training set, the first entry of the EIM error history), absolute with
// --absolute-tolerances or per tolerance; offline.json records each mode and the threshold.
TEST_F(CliOfflineOnline, TolerancesAreRelativeByDefaultAndAbsoluteOnRequest) {
  const auto offline = [&](const std::string& name, const std::string& options) {
    const std::string out = dir_->file(name);
    fs::create_directories(out);
    const CliResult r = run_cli("offline --snapshots " + shell_quote(snapshots_) + " --dual cpg --eps-pod 1e-2 --eps-eim-k 1e-3" +
                                options + " --out " + shell_quote(out + "/model.h5"));
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    std::ifstream in(out + "/offline.json");
    return json::parse(in);
  };
  const auto count_above = [](const std::vector<double>& v, double t) {
    int n = 0;
    for (double x : v) n += x > t ? 1 : 0;
    return n;
  };
  const json rel = offline("tol_relative", "");
  const auto sigma = rel.at("pod").at("singular_values").get<std::vector<double>>();
  ASSERT_GT(sigma[0], 1.0);  // the energy norm of these snapshots is far from 1: the modes differ
  for (const char* key : {"eps_pod_relative", "eps_du_relative", "eps_eim_k_relative", "eps_eim_g_relative"}) {
    EXPECT_TRUE(rel.at("settings").at(key).get<bool>()) << key;
  }
  const double pod_threshold = rel.at("thresholds").at("pod").get<double>();
  EXPECT_NEAR(pod_threshold, 1e-2 * sigma[0], 1e-15 * sigma[0]);
  EXPECT_EQ(rel.at("pod").at("N").get<int>(), count_above(sigma, pod_threshold));
  const auto k_errors = rel.at("eim_kappa").at("errors").get<std::vector<double>>();
  ASSERT_GE(k_errors.size(), 2u);
  EXPECT_NEAR(rel.at("thresholds").at("eim_kappa").get<double>(), 1e-3 * k_errors[0], 1e-15 * k_errors[0]);
  EXPECT_LE(k_errors.back(), 1e-3 * k_errors[0]);
  EXPECT_GT(k_errors[k_errors.size() - 2], 1e-3 * k_errors[0]);  // one function fewer is not enough

  const json abs = offline("tol_absolute", " --absolute-tolerances");
  for (const char* key : {"eps_pod_relative", "eps_du_relative", "eps_eim_k_relative", "eps_eim_g_relative"}) {
    EXPECT_FALSE(abs.at("settings").at(key).get<bool>()) << key;
  }
  EXPECT_EQ(abs.at("thresholds").at("pod").get<double>(), 1e-2);
  EXPECT_EQ(abs.at("pod").at("N").get<int>(), count_above(sigma, 1e-2));
  EXPECT_GT(abs.at("pod").at("N").get<int>(), rel.at("pod").at("N").get<int>());
  EXPECT_EQ(abs.at("thresholds").at("eim_kappa").get<double>(), 1e-3);

  const json pod_only = offline("tol_pod_absolute", " --eps-pod-absolute");
  EXPECT_FALSE(pod_only.at("settings").at("eps_pod_relative").get<bool>());
  EXPECT_TRUE(pod_only.at("settings").at("eps_du_relative").get<bool>());
  EXPECT_TRUE(pod_only.at("settings").at("eps_eim_k_relative").get<bool>());
  EXPECT_EQ(pod_only.at("pod").at("N"), abs.at("pod").at("N"));
  EXPECT_EQ(pod_only.at("sizes").at("Mk"), rel.at("sizes").at("Mk"));

  expect_user_error(run_cli("offline --snapshots " + shell_quote(snapshots_) +
                            " --eps-du-relative --absolute-tolerances --out " + shell_quote(dir_->file("x.h5"))),
                    "contradicts");
}

TEST_F(CliOfflineOnline, OnlineAtATrainingValueMatchesTheHFSolve) {
  // Default online tolerances (those of the snapshots: tight here) against the default HF solve.
  const CliResult r = run_cli("online --model " + shell_quote(model_) + " --mu 0.3");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json j = json::parse(r.out);
  EXPECT_TRUE(j.at("converged").get<bool>());
  std::ifstream in(dir_->file("offline.json"));
  EXPECT_EQ(j.at("u_hat").size(), json::parse(in).at("sizes").at("N").get<std::size_t>());
  EXPECT_GE(j.at("iterations").get<int>(), 1);
  for (const char* key : {"lambda_hat", "energy", "time_s"}) EXPECT_TRUE(j.contains(key)) << key;
  // The a posteriori estimate: at a training value of an untruncated model, zero to solver
  // tolerance (Delta^2 against |u|_A^2 = 2 energy, no body load in hertz-a).
  const json& est = j.at("estimate");
  for (const char* key : {"energy", "residual", "coercivity", "violation", "complementarity", "multiplier_norm"}) {
    EXPECT_TRUE(est.contains(key)) << key;
  }
  EXPECT_GE(est.at("energy").get<double>(), 0.0);
  EXPECT_LT(std::pow(est.at("energy").get<double>(), 2), 1e-10 * 2.0 * j.at("energy").get<double>()) << r.out;
  EXPECT_DOUBLE_EQ(est.at("coercivity").get<double>(), 1.0);
  const double hf_default = hf_contact_force(0.3, "");
  EXPECT_NEAR(j.at("contact_force").get<double>(), hf_default, 1e-3 * std::abs(hf_default));
  // Tight on both sides.
  const double hf_tight = hf_contact_force(0.3, kTight);
  const CliResult t = run_cli("online --model " + shell_quote(model_) + " --mu 0.3" + kTight);
  ASSERT_EQ(t.exit_code, 0) << t.out << t.err;
  EXPECT_NEAR(json::parse(t.out).at("contact_force").get<double>(), hf_tight, 1e-6 * std::abs(hf_tight));
  // The paper's zero start: the same answer, and no fewer steps than the interpolated start.
  const CliResult z = run_cli("online --model " + shell_quote(model_) + " --mu 0.3 --start zero" + kTight);
  ASSERT_EQ(z.exit_code, 0) << z.out << z.err;
  EXPECT_NEAR(json::parse(z.out).at("contact_force").get<double>(), hf_tight, 1e-6 * std::abs(hf_tight));
  EXPECT_GE(json::parse(z.out).at("iterations").get<int>(), json::parse(t.out).at("iterations").get<int>());
  // Leading sub-blocks.
  const CliResult small = run_cli("online --model " + shell_quote(model_) + " --mu 0.3 --n 2 --r 1 --mk 1 --mg 1");
  ASSERT_EQ(small.exit_code, 0) << small.out << small.err;
  EXPECT_EQ(json::parse(small.out).at("u_hat").size(), 2u);
  EXPECT_EQ(json::parse(small.out).at("lambda_hat").size(), 1u);
}

TEST_F(CliOfflineOnline, RowConeModelAnswersWithTheReducedNewton) {
  // `--dual rows`, then `online --iteration newton`: at a training value the contact force of the
  // HF solve, in a few Newton steps, and the same answer as the accelerated iteration.
  const std::string rows = dir_->file("rows.h5");
  const CliResult off = run_cli("offline --snapshots " + shell_quote(snapshots_) + " --dual rows --out " + shell_quote(rows));
  ASSERT_EQ(off.exit_code, 0) << off.out << off.err;
  EXPECT_NE(off.out.find("dual: rows"), std::string::npos) << off.out;
  const double hf = hf_contact_force(0.3, kTight);
  const CliResult n = run_cli("online --model " + shell_quote(rows) + " --mu 0.3 --iteration newton --tol 1e-10");
  ASSERT_EQ(n.exit_code, 0) << n.out << n.err;
  const json jn = json::parse(n.out);
  EXPECT_TRUE(jn.at("converged").get<bool>());
  EXPECT_LE(jn.at("iterations").get<int>(), 10);
  EXPECT_NEAR(jn.at("contact_force").get<double>(), hf, 1e-6 * std::abs(hf));
  const CliResult a = run_cli("online --model " + shell_quote(rows) + " --mu 0.3 --iteration accelerated --tol 1e-10");
  ASSERT_EQ(a.exit_code, 0) << a.out << a.err;
  EXPECT_NEAR(json::parse(a.out).at("contact_force").get<double>(), jn.at("contact_force").get<double>(), 1e-8 * std::abs(hf));
}

TEST_F(CliOfflineOnline, OfflineFromACaseEqualsSnapshotsThenOffline) {
  // The same values and settings through `offline --case`: the snapshots are deterministic, so
  // the model answers exactly as the one built from the snapshot file.
  const std::string sub = dir_->file("from_case");
  fs::create_directories(sub);
  const std::string model = sub + "/model.h5";
  const CliResult r = run_cli(std::string("offline --case hertz-a --values ") + kValues + kTight +
                              " -j 2 -q --dual cpg --n 100 --eps-du 0 --eps-eim-k 0 --eps-eim-g 0 --out " + shell_quote(model));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(fs::exists(sub + "/snapshots.h5"));
  EXPECT_NE(r.out.find("wrote " + sub + "/snapshots.h5"), std::string::npos) << r.out;
  EXPECT_EQ(field_value(r.out, "sizes"), field_value(offline_.out, "sizes"));
  std::ifstream in(sub + "/offline.json");
  const json j = json::parse(in);
  EXPECT_TRUE(j.at("snapshots_computed").get<bool>());
  EXPECT_EQ(j.at("training").at("count"), 5);
  EXPECT_GT(j.at("times_s").at("snapshots").get<double>(), 0.0);
  const CliResult a = run_cli("online --model " + shell_quote(model) + " --mu 0.33");
  const CliResult b = run_cli("online --model " + shell_quote(model_) + " --mu 0.33");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(json::parse(a.out).at("u_hat"), json::parse(b.out).at("u_hat"));
  // Snapshot options without --case, and two sources, are usage errors.
  const CliResult both = run_cli("offline --case hertz-a --snapshots " + shell_quote(snapshots_) + " --out " +
                                 shell_quote(model));
  EXPECT_NE(both.exit_code, 0);
  const CliResult jobs = run_cli("offline --snapshots " + shell_quote(snapshots_) + " -j 2 --out " + shell_quote(model));
  EXPECT_NE(jobs.exit_code, 0);
  // A value outside the domain: one clear error before any solve.
  expect_user_error(run_cli("offline --case hertz-a --values 0.1 --out " + shell_quote(model)), "outside the domain");
}

TEST_F(CliOfflineOnline, BatchAnswersEveryLineInOrder) {
  const std::string batch = dir_->file("batch.txt");
  {
    std::ofstream out(batch);
    out << "0.2\n  0.3 \nabc\n0.9\nnan\n0.4\n";
  }
  const CliResult r = run_cli("online --model " + shell_quote(model_) + " --batch " + shell_quote(batch));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("contactrb: error: 3 of 6 batch lines"), std::string::npos) << r.err;
  const auto lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 6u) << r.out;
  const std::vector<bool> good{true, true, false, false, false, true};
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const json j = json::parse(lines[k]);
    EXPECT_EQ(j.at("line").get<std::size_t>(), k + 1);
    EXPECT_EQ(j.contains("error"), !good[k]) << lines[k];
    if (good[k]) {
      EXPECT_TRUE(j.at("converged").get<bool>()) << lines[k];
      EXPECT_GE(j.at("estimate").at("energy").get<double>(), 0.0) << lines[k];  // every batch line has one
    } else {
      EXPECT_FALSE(j.contains("estimate")) << lines[k];
    }
  }
  EXPECT_NE(lines[2].find("not a number"), std::string::npos) << lines[2];
  EXPECT_NE(lines[3].find("outside the domain"), std::string::npos) << lines[3];
  EXPECT_DOUBLE_EQ(json::parse(lines[1]).at("mu").get<double>(), 0.3);

  // stdin, all good: exit 0.
  const std::string good_batch = dir_->file("good.txt");
  {
    std::ofstream out(good_batch);
    out << "0.25\n0.35\n";
  }
  const CliResult piped = run_cli("online --model " + shell_quote(model_) + " --batch - < " + shell_quote(good_batch));
  EXPECT_EQ(piped.exit_code, 0) << piped.out << piped.err;
  EXPECT_EQ(lines_of(piped.out).size(), 2u) << piped.out;
}

TEST_F(CliOfflineOnline, BadInputsGiveOneClearError) {
  const std::string m = " --model " + shell_quote(model_);
  expect_user_error(run_cli("online --model " + shell_quote(dir_->file("none.h5")) + " --mu 0.3"), "none.h5");
  expect_user_error(run_cli("online --model " + shell_quote(snapshots_) + " --mu 0.3"), "s.h5");
  expect_user_error(run_cli("online" + m + " --mu 0.9"), "outside the domain");
  expect_user_error(run_cli("online" + m + " --mu 0.3 --n 100"), "--n = 100 is above the maximum");
  expect_user_error(run_cli("online" + m + " --mu 0.3 --mk 1000"), "--mk = 1000");
  expect_user_error(run_cli("online" + m + " --mu 0.3 --start warm"),
                    "--start: unknown initial guess 'warm' (expected interpolated or zero)");
  expect_user_error(run_cli("online" + m + " --mu 0.3 --alpha 2"), "alpha");
  expect_user_error(run_cli("online" + m + " --mu 0.3 --iteration quick"), "--iteration: unknown online iteration 'quick'");
  expect_user_error(run_cli("online" + m + " --mu 0.3 --iteration newton"),
                    "--iteration newton needs a model built with `contactrb offline --dual rows` (its dual cone is 'cpg')");
  expect_user_error(run_cli("online" + m + " --batch " + shell_quote(dir_->file("none.txt"))), "none.txt");
  expect_user_error(run_cli("online" + m + " --batch ''"), "--batch needs a file name");
  // Usage errors (CLI11): neither or both of --mu and --batch.
  EXPECT_NE(run_cli("online" + m).exit_code, 0);
  EXPECT_NE(run_cli("online" + m + " --mu 0.3 --batch -").exit_code, 0);

  const std::string out = " --out " + shell_quote(dir_->file("bad.h5"));
  expect_user_error(run_cli("offline --snapshots " + shell_quote(model_) + out), "model.h5");
  expect_user_error(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --dual svd" + out), "--dual");
  expect_user_error(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --inner-product l2" + out),
                    "--inner-product");
  // A missing directory of --out is created (every missing parent); a file in its way is an error.
  EXPECT_EQ(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --out " + shell_quote(dir_->file("no/dir/m.h5")))
                .exit_code,
            0);
  EXPECT_TRUE(std::filesystem::is_regular_file(dir_->file("no/dir/m.h5")));
  expect_user_error(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --out " +
                            shell_quote(dir_->file("no/dir/m.h5/x.h5"))),
                    "is not a directory");
  EXPECT_NE(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --n 3 --eps-pod 1e-3" + out).exit_code, 0);
  // Numbers in messages have six significant digits (a fixed-point 1e300 has 300 digits).
  expect_user_error(run_cli("offline --snapshots " + shell_quote(snapshots_) + " --dual cpg --eps-eim-k 1e300" + out),
                    "eps_eim_k = 1e+300 is above max |kappa|");
  EXPECT_FALSE(fs::exists(dir_->file("bad.h5")));
}

// A model whose primal basis cannot see the contact (the patch test's single POD mode has no
// interface jump, so D = 0 without supremizers) must fail with a clear message, never answer
// with undetermined multipliers. With the supremizers (the default) the basis sees the contact and
// the reduced model reproduces the HF patch solution (uniform pressure) to round-off.
TEST(CliOnlineBlindBasis, PatchModelIsRefusedWithAClearMessage) {
  contactrb::test::TempDir dir("online_blind");
  const std::string d = contactrb::test::shell_quote(dir.path().string());
  const std::string toml = contactrb::test::shell_quote(std::string(CONTACTRB_SOURCE_DIR) +
                                                        "/examples/two-block-patch/case.toml");
  ASSERT_EQ(contactrb::test::run_cli("snapshots -q --case-file " + toml + " --set verification --out " + d + "/s.h5")
                .exit_code,
            0);
  ASSERT_EQ(
      contactrb::test::run_cli("offline --snapshots " + d + "/s.h5 --n 10 --no-supremizers --out " + d + "/m.h5")
          .exit_code,
      0);
  const contactrb::test::CliResult r = contactrb::test::run_cli("online --model " + d + "/m.h5 --mu 0.02");
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.err.find("does not see the contact"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("e+16"), std::string::npos) << r.out;

  ASSERT_EQ(contactrb::test::run_cli("offline --snapshots " + d + "/s.h5 --n 10 --out " + d + "/ms.h5").exit_code, 0);
  const contactrb::test::CliResult ok = contactrb::test::run_cli("online --model " + d + "/ms.h5 --mu 0.02");
  ASSERT_EQ(ok.exit_code, 0) << ok.out << ok.err;
  ASSERT_EQ(contactrb::test::run_cli("solve --case-file " + toml + " --mu 0.02 --out " + d + "/hf").exit_code, 0);
  std::ifstream in(dir.path() / "hf" / "solution.json");
  const json hf = json::parse(in);
  const json rb = json::parse(ok.out);
  // The POD mode and one supremizer per generator (the row cone: one per kept row).
  EXPECT_EQ(rb.at("sizes").at("N").get<int>(), 1 + rb.at("sizes").at("R").get<int>());
  EXPECT_NEAR(rb.at("contact_force").get<double>(), hf.at("contact_force").get<double>(),
              1e-10 * hf.at("contact_force").get<double>());
  EXPECT_NEAR(rb.at("energy").get<double>(), hf.at("energy").get<double>(), 1e-10 * hf.at("energy").get<double>());
}
