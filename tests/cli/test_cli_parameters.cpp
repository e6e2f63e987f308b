// p parameters on the command line (docs/concepts.md, "Parameter points"): --mu as positional values
// or name=value pairs, batch lines with p values or JSON objects, and one clear error for each
// mistake (unknown name, missing value, wrong count).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "json_text.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::read_json;
using contactrb::test::expect_user_error;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

namespace {

std::vector<nlohmann::json> json_lines(const std::string& text) {
  std::vector<nlohmann::json> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty()) out.push_back(nlohmann::json::parse(line));
  }
  return out;
}

std::string traction_case() { return std::string(CONTACTRB_SOURCE_DIR) + "/examples/two-block-traction/case.toml"; }

}  // namespace

// Positional and named forms give the same solve; at R2 = 1, E2 = 15 it is hertz-a's.
TEST(CliParameters, SolveAcceptsPositionalAndNamedPoints) {
  contactrb::test::TempDir dir("cli_params_solve");
  const fs::path a = dir.path() / "a", b = dir.path() / "b", c = dir.path() / "c";
  ASSERT_EQ(run_cli("solve --case hertz-3p --mu 0.3,1,15 --out " + shell_quote(a.string())).exit_code, 0);
  ASSERT_EQ(run_cli("solve --case hertz-3p --mu 'E2=15, delta=0.3,R2=1' --out " + shell_quote(b.string())).exit_code, 0);
  ASSERT_EQ(run_cli("solve --case hertz-a --mu 0.3 --out " + shell_quote(c.string())).exit_code, 0);
  const nlohmann::json ja = read_json(a / "solution.json"), jb = read_json(b / "solution.json"),
                       jc = read_json(c / "solution.json");
  EXPECT_EQ(ja["energy"], jb["energy"]);
  EXPECT_NEAR(ja["energy"].get<double>(), jc["energy"].get<double>(), 1e-12);
  EXPECT_DOUBLE_EQ(ja["mu"]["delta"].get<double>(), 0.3);
  EXPECT_DOUBLE_EQ(ja["mu"]["E2"].get<double>(), 15.0);
  EXPECT_TRUE(jc["mu"].is_number());  // one parameter: a number, as before
}

TEST(CliParameters, BadPointsGiveOneClearError) {
  contactrb::test::TempDir dir("cli_params_bad");
  const std::string out = " --out " + shell_quote((dir.path() / "o").string());
  expect_user_error(run_cli("solve --case hertz-3p --mu delta=0.3,R2=1" + out), "missing value for parameter 'E2'");
  expect_user_error(run_cli("solve --case hertz-3p --mu delta=0.3,R2=1,E2=15,G=2" + out),
                    "unknown parameter 'G' (parameters: delta, R2, E2)");
  expect_user_error(run_cli("solve --case hertz-3p --mu delta=0.3,delta=0.2,E2=15" + out), "'delta' is given twice");
  expect_user_error(run_cli("solve --case hertz-3p --mu 0.3,1" + out), "expected 3 values (delta, R2, E2), got 2");
  expect_user_error(run_cli("solve --case hertz-3p --mu 0.3,1,nan" + out), "E2: 'nan' is not a number");
  expect_user_error(run_cli("solve --case hertz-3p --mu 0.3,1,45" + out), "(E2) is outside the domain [7.5, 30]");
  expect_user_error(run_cli("solve --case hertz-3p --mu delta=0.3,1,15" + out), "is not name=value");
  expect_user_error(run_cli("snapshots --case hertz-3p --values 0.2,0.3 --out " +
                            shell_quote((dir.path() / "s.h5").string())),
                    "--values lists values of one parameter, but the case has 3");
  EXPECT_FALSE(fs::exists(dir.path() / "o" / "solution.json"));
}

// A two-parameter TOML case through snapshots, offline, online (batch forms) and evaluate.
TEST(CliParameters, TwoParameterCaseEndToEnd) {
  contactrb::test::TempDir dir("cli_params_e2e");
  const fs::path model = dir.path() / "m.h5";
  const CliResult off =
      run_cli("offline --case-file " + shell_quote(traction_case()) + " -q --out " + shell_quote(model.string()));
  ASSERT_EQ(off.exit_code, 0) << off.err;
  const nlohmann::json offline = read_json(dir.path() / "offline.json");
  ASSERT_EQ(offline["parameters"].size(), 2u);
  EXPECT_EQ(offline["parameters"][1]["name"], "q");
  EXPECT_EQ(offline["parameters"][1]["kind"], "traction");
  EXPECT_EQ(offline["training"]["count"], 25);

  const fs::path batch = dir.path() / "batch.txt";
  {
    std::ofstream b(batch);
    b << "0.02 0.1\n0.02,0.1\nq=0.1,delta=0.02\n{\"delta\": 0.02, \"q\": 0.1}\n0.02\n{\"delta\": 0.02}\n0.02 0.1 7\n";
  }
  const CliResult on = run_cli("online --model " + shell_quote(model.string()) + " --batch " + shell_quote(batch.string()));
  EXPECT_EQ(on.exit_code, 1) << on.err;  // three bad lines
  const std::vector<nlohmann::json> lines = json_lines(on.out);
  ASSERT_EQ(lines.size(), 7u);
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(lines[static_cast<std::size_t>(i)]["converged"].get<bool>()) << lines[static_cast<std::size_t>(i)];
    EXPECT_EQ(lines[static_cast<std::size_t>(i)]["energy"], lines[0]["energy"]);
    EXPECT_DOUBLE_EQ(lines[static_cast<std::size_t>(i)]["mu"]["q"].get<double>(), 0.1);
  }
  EXPECT_NE(lines[4]["error"].get<std::string>().find("expected 2 values (delta, q), got 1"), std::string::npos)
      << lines[4];
  EXPECT_NE(lines[5]["error"].get<std::string>().find("missing value for parameter 'q'"), std::string::npos)
      << lines[5];
  EXPECT_NE(lines[6]["error"].get<std::string>().find("got 3"), std::string::npos) << lines[6];

  const fs::path ev = dir.path() / "ev";
  const CliResult e = run_cli("evaluate --model " + shell_quote(model.string()) + " -q --out " + shell_quote(ev.string()));
  ASSERT_EQ(e.exit_code, 0) << e.err;
  std::ifstream csv(ev / "evaluation.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("delta,q,hf_solver,hf_converged", 0), 0u) << header;
  const nlohmann::json j = read_json(ev / "evaluation.json");
  EXPECT_EQ(j["summary"]["count"], 10);
  // The patch test's solution is in the span of the training solutions: the model is exact
  // to round-off.
  EXPECT_LT(j["summary"]["e_displ"]["max"].get<double>(), 1e-10);
  EXPECT_LT(j["summary"]["e_press"]["max"].get<double>(), 1e-10);
}
