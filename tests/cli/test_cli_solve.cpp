// contactrb solve: outputs, their contents, and the errors a user can cause.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "json_text.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::read_json;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

TEST(CliSolve, HertzAWritesJsonCsvAndVtu) {
  contactrb::test::TempDir dir("solve_ok");
  const CliResult r = run_cli("solve --case hertz-a --mu 0.3 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = read_json(dir.path() / "solution.json");
  for (const char* key : {"case", "mu", "constraint", "converged", "iterations", "energy", "contact_force",
                          "active_constraints", "kkt", "time_s", "n_dofs", "n_constraints"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["case"], "hertz-a");
  EXPECT_EQ(j["constraint"], "collocation");
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_EQ(j["n_constraints"].get<int>(), 51);
  EXPECT_GT(j["contact_force"].get<double>(), 0.0);
  EXPECT_LT(j["kkt"]["stationarity"].get<double>(), 1e-8);
  // multipliers.csv: a header and one row per constraint; pressures >= 0 and the weighted
  // sum equals the reported contact force.
  std::ifstream csv(dir.path() / "multipliers.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "r,abscissa,x,y,gap,pressure,weight");
  int rows = 0;
  double force = 0.0;
  while (std::getline(csv, line)) {
    double v[7];
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                          &v[6]),
              7)
        << line;
    EXPECT_GE(v[5], 0.0);
    EXPECT_GT(v[6], 0.0);
    force += v[5] * v[6];
    ++rows;
  }
  EXPECT_EQ(rows, 51);
  EXPECT_NEAR(force, j["contact_force"].get<double>(), 1e-9 * force);
  EXPECT_GT(fs::file_size(dir.path() / "solution.vtu"), 1000u);
}

TEST(CliSolve, LacHasHalfTheConstraints) {
  contactrb::test::TempDir dir("solve_lac");
  const CliResult r =
      run_cli("solve --case hertz-a --mu 0.2 --constraint lac --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = read_json(dir.path() / "solution.json");
  EXPECT_EQ(j["constraint"], "lac");
  EXPECT_EQ(j["n_constraints"].get<int>(), 25);
}

TEST(CliSolve, BadInputsGiveOneClearError) {
  contactrb::test::TempDir dir("solve_bad");
  const std::string out = " --out " + shell_quote(dir.path().string());
  expect_user_error(run_cli("solve --case hertz-a --mu 0.5" + out), "outside the domain");
  expect_user_error(run_cli("solve --case hertz-a --mu 0.1" + out), "[0.15, 0.45]");
  expect_user_error(run_cli("solve --case hertz-a --mu nan" + out), "--mu: 'nan' is not a number (NaN)");
  expect_user_error(run_cli("solve --case hertz-a --mu 0.3 --alpha 0" + out), "alpha");
  expect_user_error(run_cli("solve --case hertz-a --mu 0.3 --alpha 1.5" + out), "alpha");
  expect_user_error(run_cli("solve --case hertz-a --mu 0.3 --tol 0" + out), "tolerance");
  expect_user_error(run_cli("solve --case hertz-a --mu 0.3 --tol -1" + out), "tolerance");
  expect_user_error(run_cli("solve --case hertz-a --mu 0.3 --constraint mortar" + out), "mortar");
  expect_user_error(run_cli("solve --case nocase --mu 0.3" + out), "nocase");
  EXPECT_FALSE(fs::exists(dir.path() / "solution.json"));
}

TEST(CliSolve, NonConvergenceExitsThreeAndStillWritesTheJson) {
  contactrb::test::TempDir dir("solve_noconv");
  const CliResult r = run_cli("solve --case hertz-a --mu 0.3 --max-iterations 3 --out " +
                              shell_quote(dir.path().string()));
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.err.find("did not converge in 3 iterations"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("increments"), std::string::npos) << r.err;
  const nlohmann::json j = read_json(dir.path() / "solution.json");
  EXPECT_FALSE(j["converged"].get<bool>());
  EXPECT_EQ(j["iterations"].get<int>(), 3);
}

// The semi-smooth Newton solver's non-convergence is exit 3 too, with the
// iterations and the KKT residuals in the message.
TEST(CliSolve, NewtonNonConvergenceExitsThreeWithTheResiduals) {
  contactrb::test::TempDir dir("solve_newton_noconv");
  const CliResult r = run_cli("solve --case hertz-a --mu 0.45 --solver newton --newton-max-iterations 2 --out " +
                              shell_quote(dir.path().string()));
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.err.find("did not converge in 2 iterations"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("stationarity"), std::string::npos) << r.err;
  const nlohmann::json j = read_json(dir.path() / "solution.json");
  EXPECT_FALSE(j["converged"].get<bool>());
  EXPECT_EQ(j["solver"].get<std::string>(), "newton");
  EXPECT_EQ(j["newton_residuals"].size(), 2u);
}

// Grid sequencing (docs/solvers.md): --sequence 1 on level 3 solves level 1 first and starts
// from it; the answer is the cold solve's, in fewer fine Newton iterations, and the coarse solve
// is reported in the JSON (not in "iterations").
TEST(CliSolve, GridSequencingGivesTheColdAnswerInFewerNewtonIterations) {
  contactrb::test::TempDir dir("solve_sequence");
  const std::string cold_dir = (dir.path() / "cold").string(), seq_dir = (dir.path() / "seq").string();
  const std::string base = "solve --case hertz-a --mu 0.45 --level 3 --solver newton ";
  const CliResult cold = run_cli(base + "--out " + shell_quote(cold_dir));
  const CliResult seq = run_cli(base + "--sequence 1 --out " + shell_quote(seq_dir));
  ASSERT_EQ(cold.exit_code, 0) << cold.out << cold.err;
  ASSERT_EQ(seq.exit_code, 0) << seq.out << seq.err;
  const nlohmann::json c = read_json(fs::path(cold_dir) / "solution.json");
  const nlohmann::json s = read_json(fs::path(seq_dir) / "solution.json");
  EXPECT_TRUE(c["sequence"].empty());
  ASSERT_EQ(s["sequence"].size(), 1u);
  EXPECT_EQ(s["sequence"][0]["level"].get<int>(), 1);
  EXPECT_TRUE(s["sequence"][0]["converged"].get<bool>());
  EXPECT_GT(s["sequence"][0]["iterations"].get<int>(), 0);
  EXPECT_LT(s["iterations"].get<int>(), c["iterations"].get<int>());
  EXPECT_EQ(s["n_dofs"], c["n_dofs"]);
  EXPECT_NEAR(s["contact_force"].get<double>(), c["contact_force"].get<double>(), 1e-8 * c["contact_force"].get<double>());
  EXPECT_NEAR(s["energy"].get<double>(), c["energy"].get<double>(), 1e-8 * c["energy"].get<double>());
  EXPECT_EQ(s["active_constraints"], c["active_constraints"]);
  for (const char* k : {"stationarity", "primal", "dual", "complementarity"}) EXPECT_LE(s["kkt"][k].get<double>(), 1e-10) << k;
  EXPECT_NE(seq.out.find("grid sequencing: level 1"), std::string::npos) << seq.out;
  const CliResult bad = run_cli(base + "--sequence -2 --out " + shell_quote(seq_dir));
  EXPECT_EQ(bad.exit_code, 1) << bad.out << bad.err;
  EXPECT_NE(bad.err.find("--sequence must be >= 0"), std::string::npos) << bad.err;
}

// The automatic default (-1): two coarse stages with Newton from level 4 on, none below or with
// Kacanov.
TEST(CliSolve, GridSequencingIsAutomaticWithNewtonFromLevelFour) {
  contactrb::test::TempDir dir("solve_sequence_auto");
  auto stages = [&](const std::string& args) {
    const std::string out = (dir.path() / "run").string();
    const CliResult r = run_cli("solve --case hertz-a --mu 0.3 " + args + " --out " + shell_quote(out));
    EXPECT_EQ(r.exit_code, 0) << args << r.out << r.err;
    std::vector<int> levels;
    const nlohmann::json j = read_json(fs::path(out) / "solution.json");
    for (const auto& st : j["sequence"]) levels.push_back(st["level"].get<int>());
    return levels;
  };
  EXPECT_EQ(stages("--level 4 --solver newton"), (std::vector<int>{0, 2}));
  EXPECT_TRUE(stages("--level 4 --solver newton --sequence 0").empty());
  EXPECT_TRUE(stages("--level 3 --solver newton").empty());
  EXPECT_TRUE(stages("--level 2").empty());  // Kacanov
  EXPECT_EQ(stages("--level 2 --sequence 1"), (std::vector<int>{0}));  // Kacanov, asked for
}

// The command of the report at alpha = 1e-4: (63) on the relaxed increment would stop after one
// iteration with force 1.398 instead of 1.4726. The stopping test reads the unrelaxed step
// (docs/theory.md, "Kacanov (12)"): 500 iterations at alpha = 1e-4 do not reach eps_KA, and that is a status.
TEST(CliSolve, TinyRelaxationIsNotConvergedAfterOneIteration) {
  contactrb::test::TempDir dir("solve_tiny_alpha");
  const CliResult r =
      run_cli("solve --case hertz-a --mu 0.3 --alpha 1e-4 --out " + shell_quote(dir.path().string()));
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.err.find("did not converge in 500 iterations"), std::string::npos) << r.err;
  const nlohmann::json j = read_json(dir.path() / "solution.json");
  EXPECT_FALSE(j["converged"].get<bool>());
  EXPECT_EQ(j["iterations"].get<int>(), 500);
  // The first multiplier increment is from lambda^0 = 0: infinite, written as null.
  EXPECT_TRUE(j["increments"]["multipliers"][0].is_null());
  EXPECT_GT(j["increments"]["displacement"][499].get<double>(), 1e-3);
}
