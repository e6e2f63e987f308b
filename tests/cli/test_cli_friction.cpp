// contactrb solve on the frictional built-in case cattaneo: the files read back against the
// solver's own totals and Coulomb's law, and every command without friction refusing the case.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli_runner.hpp"
#include "csv_text.hpp"
#include "json_text.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::read_json;
using contactrb::test::numbers;
using contactrb::test::read_csv;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

TEST(CliFriction, CattaneoFilesAgreeWithTheReportedForcesAndCoulombsLaw) {
  contactrb::test::TempDir dir("friction_solve");
  const double f = 0.3;
  const CliResult r = run_cli("solve --case cattaneo --mu f=0.3 --level 2 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = read_json(dir.path() / "solution.json");
  EXPECT_EQ(j["case"], "cattaneo");
  EXPECT_EQ(j["law"], "coulomb");
  EXPECT_EQ(j["status"], "converged");
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_EQ(j["friction_coefficient"].get<double>(), f);
  // The path: normal approach, then the tangential displacement; each step converged.
  ASSERT_EQ(j["steps"].size(), 2u);
  EXPECT_EQ(j["load_steps"].get<int>(), 2);
  for (const nlohmann::json& step : j["steps"]) {
    EXPECT_EQ(step["status"], "converged");
    EXPECT_LE(step["iterations"].get<int>(), 15);
  }
  EXPECT_LT(j["kkt"]["friction"].get<double>(), 1e-9);

  const auto csv = read_csv((dir.path() / "multipliers.csv").string());
  const std::vector<double> p = numbers(csv.at("pressure")), t = numbers(csv.at("tangential")),
                            w = numbers(csv.at("weight"));
  const std::vector<std::string>& state = csv.at("state");
  ASSERT_EQ(t.size(), p.size());
  ASSERT_EQ(state.size(), p.size());
  double normal = 0.0, tangential = 0.0, p_max = 0.0;
  int stick = 0, slip = 0, open = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    normal += p[i] * w[i];
    tangential += t[i] * w[i];
    p_max = std::max(p_max, p[i]);
    stick += state[i] == "stick";
    slip += state[i] == "slip";
    open += state[i] == "open";
  }
  EXPECT_EQ(stick + slip + open, static_cast<int>(p.size()));  // no other state
  EXPECT_EQ(stick, j["stick_nodes"].get<int>());
  EXPECT_EQ(slip, j["slip_nodes"].get<int>());
  EXPECT_EQ(open, j["steps"].back()["open_nodes"].get<int>());
  EXPECT_GT(stick, 0);
  EXPECT_GT(slip, 0);  // Q / (f P) about 0.6: a stick zone inside slip zones
  EXPECT_NEAR(normal, j["contact_force"].get<double>(), 1e-12 * normal);
  EXPECT_NEAR(tangential, j["tangential_force"].get<double>(), 1e-12 * normal);
  EXPECT_GT(std::abs(tangential), 0.3 * f * normal);
  EXPECT_LT(std::abs(tangential), f * normal);
  // Coulomb's cone at every row, equality on the slip rows, nothing on the open ones (the CSV
  // holds 17 significant digits).
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_LE(std::abs(t[i]), f * p[i] + 1e-12 * p_max) << "row " << i;
    if (state[i] == "slip") {
      EXPECT_NEAR(std::abs(t[i]), f * p[i], 1e-12 * p_max) << "row " << i;
    } else if (state[i] == "open") {
      EXPECT_EQ(t[i], 0.0) << "row " << i;
    }
  }
  for (const char* vtu : {"solution.vtu", "solution_deformed.vtu", "contact.vtu"}) {
    EXPECT_GT(fs::file_size(dir.path() / vtu), 1000u) << vtu;
  }
  const std::string contact = contactrb::test::file_text((dir.path() / "contact.vtu").string());
  EXPECT_NE(contact.find("Name=\"tangential_traction\""), std::string::npos);
  EXPECT_NE(contact.find("Name=\"state\""), std::string::npos);
}

TEST(CliFriction, ZeroCoefficientGivesNoTangentialForce) {
  contactrb::test::TempDir dir("friction_zero");
  const CliResult r = run_cli("solve --case cattaneo --mu 0 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = read_json(dir.path() / "solution.json");
  EXPECT_EQ(j["tangential_force"].get<double>(), 0.0);
  EXPECT_EQ(j["stick_nodes"].get<int>(), 0);
  const auto csv = read_csv((dir.path() / "multipliers.csv").string());
  for (const std::string& t : csv.at("tangential")) EXPECT_EQ(std::stod(t), 0.0);
}

TEST(CliFriction, CasesListsTheFrictionalCasesWithTheirDimension) {
  const CliResult r = run_cli("cases");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const auto& [name, kind] : {std::pair{"\ncattaneo ", "2D  frictional"}, std::pair{"\ncattaneo-3d ", "3D  frictional"}}) {
    const std::size_t at = r.out.find(name);
    ASSERT_NE(at, std::string::npos) << r.out;
    EXPECT_NE(r.out.find(kind, at), std::string::npos) << r.out;
  }
}

TEST(CliFriction, BadSolveInputsGiveOneClearError) {
  contactrb::test::TempDir dir("friction_bad");
  const std::string out = " --out " + shell_quote(dir.path().string());
  using contactrb::test::expect_user_error;
  expect_user_error(run_cli("solve --case cattaneo --mu -0.1" + out), "outside the domain");
  expect_user_error(run_cli("solve --case cattaneo --mu nan" + out), "is not a number");
  expect_user_error(run_cli("solve --case cattaneo --mu 0.3 --constraint lac" + out), "collocation only");
  expect_user_error(run_cli("solve --case cattaneo --mu 0.3 --solver kacanov" + out), "semi-smooth Newton");
  expect_user_error(run_cli("solve --case cattaneo --mu 0.3 --level -1" + out), "--level must be >= 0");
  expect_user_error(run_cli("solve --case cattaneo --mu 0.3 --sequence 1" + out), "no grid sequencing");
  expect_user_error(run_cli("solve --case cattaneo --mu 0.3 --newton-max-iterations 0" + out),
                    "friction max_iterations must be >= 1 (got 0)");
  EXPECT_FALSE(fs::exists(dir.path() / "solution.json"));
}

// Every command without friction refuses the frictional case in one line (never a frictionless
// answer in its place).
class CliFrictionRefusal : public ::testing::TestWithParam<const char*> {};

TEST_P(CliFrictionRefusal, RefusesTheFrictionalCase) {
  contactrb::test::TempDir dir("friction_refusal");
  const std::string command = std::string(GetParam()) + " --out " + shell_quote((dir.path() / "out").string());
  const CliResult r = run_cli(command);
  contactrb::test::expect_user_error(r, "case 'cattaneo' is frictional: only `contactrb solve` handles friction");
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

INSTANTIATE_TEST_SUITE_P(Commands, CliFrictionRefusal,
                         ::testing::Values("snapshots --case cattaneo --set training", "offline --case cattaneo",
                                           "offline --greedy --case cattaneo --greedy-tol 1e-3",
                                           "report --case cattaneo", "mesh --case cattaneo"));

namespace {

std::string example_case() { return std::string(CONTACTRB_SOURCE_DIR) + "/examples/cattaneo/case.toml"; }

// The example case file with `from` replaced by `to` (the first occurrence), written to dir/name.
std::string edited_case(const fs::path& dir, const std::string& name, const std::string& from, const std::string& to) {
  std::string text = contactrb::test::file_text(example_case());
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace

// examples/cattaneo/case.toml is the built-in cattaneo as a case file: the same files, byte for byte.
TEST(CliFriction, CaseFileGivesTheBuiltInAnswer) {
  contactrb::test::TempDir dir("friction_file");
  const fs::path a = dir.path() / "builtin", b = dir.path() / "file";
  ASSERT_EQ(run_cli("solve --case cattaneo --mu 0.3 --level 1 --out " + shell_quote(a.string())).exit_code, 0);
  const CliResult r =
      run_cli("solve --case-file " + shell_quote(example_case()) + " --mu 0.13 --level 1 --out " + shell_quote(b.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(contactrb::test::file_text((a / "multipliers.csv").string()),
            contactrb::test::file_text((b / "multipliers.csv").string()));
  const nlohmann::json ja = read_json(a / "solution.json"), jb = read_json(b / "solution.json");
  EXPECT_EQ(ja["tangential_force"], jb["tangential_force"]);
  EXPECT_EQ(jb["case"], "cattaneo-file");
  EXPECT_EQ(jb["mu"].get<double>(), 0.13);
}

// Tresca with a threshold below the traction the stick state would need: every row in contact
// slips at |t| = s, so the tangential force is -s times the contact length (the edge moves +x).
TEST(CliFriction, TrescaCaseFileSlipsAtTheThreshold) {
  contactrb::test::TempDir dir("friction_tresca");
  const std::string file = edited_case(dir.path(), "tresca.toml", "law = \"coulomb\"", "law = \"tresca\"");
  std::string text = contactrb::test::file_text(file);
  text.replace(text.find("coefficient = 0.3"), std::string("coefficient = 0.3").size(), "threshold = 0.05");
  std::ofstream(file) << text;
  const CliResult r =
      run_cli("solve --case-file " + shell_quote(file) + " --mu 0.13 --level 2 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = read_json(dir.path() / "solution.json");
  EXPECT_EQ(j["law"], "tresca");
  EXPECT_EQ(j["slip_threshold"].get<double>(), 0.05);
  const auto csv = read_csv((dir.path() / "multipliers.csv").string());
  const std::vector<double> p = numbers(csv.at("pressure")), t = numbers(csv.at("tangential")),
                            w = numbers(csv.at("weight"));
  double length = 0.0;
  int slip = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_LE(std::abs(t[i]), 0.05 + 1e-15) << "row " << i;
    if (csv.at("state")[i] == "open") continue;
    EXPECT_EQ(csv.at("state")[i], "slip") << "row " << i;
    EXPECT_NEAR(t[i], -0.05, 1e-15) << "row " << i;
    length += w[i];
    ++slip;
  }
  EXPECT_GT(slip, 3);
  EXPECT_EQ(slip, j["slip_nodes"].get<int>());
  EXPECT_NEAR(j["tangential_force"].get<double>(), -0.05 * length, 1e-14);
}

TEST(CliFriction, CaseFileFrictionKeysGiveOneClearError) {
  contactrb::test::TempDir dir("friction_toml_bad");
  const std::string out = " --mu 0.13 --out " + shell_quote((dir.path() / "out").string());
  using contactrb::test::expect_user_error;
  auto solve = [&](const std::string& name, const std::string& from, const std::string& to) {
    return run_cli("solve --case-file " + shell_quote(edited_case(dir.path(), name, from, to)) + out);
  };
  expect_user_error(solve("neg.toml", "coefficient = 0.3", "coefficient = -0.1"),
                    ":38: key 'friction.coefficient' must be a finite number >= 0, got -0.1");
  expect_user_error(solve("nan.toml", "coefficient = 0.3", "coefficient = nan"),
                    "key 'friction.coefficient' must be a finite number >= 0, got nan");
  expect_user_error(solve("law.toml", "law = \"coulomb\"", "law = \"amontons\""),
                    ":37: key 'friction.law' must be coulomb or tresca, got 'amontons'");
  expect_user_error(solve("other.toml", "coefficient = 0.3", "coefficient = 0.3\nthreshold = 1.0"),
                    "key 'friction.threshold' does not apply to law = coulomb");
  expect_user_error(solve("missing.toml", "coefficient = 0.3", ""), "missing key 'friction.coefficient'");
  // Without the steps (the text up to the first [[load_steps]]), then with an empty list.
  const std::string full = contactrb::test::file_text(example_case());
  const std::string head = full.substr(0, full.find("[[load_steps]]"));
  const std::string no_steps = edited_case(dir.path(), "nosteps.toml", full, head);
  expect_user_error(run_cli("solve --case-file " + shell_quote(no_steps) + out),
                    ":36: [friction] needs [[load_steps]] (at least one load step)");
  const std::string empty = edited_case(dir.path(), "empty.toml", full, "load_steps = []\n" + head);
  expect_user_error(run_cli("solve --case-file " + shell_quote(empty) + out), "key 'load_steps' has no step");
  expect_user_error(solve("group.toml", "[[load_steps.dirichlet]]\ngroup = \"top\"",
                          "[[load_steps.dirichlet]]\ngroup = \"rollers\""),
                    "[[load_steps[1].dirichlet]] must prescribe the components of [[dirichlet]]");
  expect_user_error(solve("lac.toml", "name = \"cattaneo-file\"", "name = \"cattaneo-file\"\nconstraint = \"lac\""),
                    "a frictional case needs constraint = collocation");
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

// The frictionless readers (snapshots, offline, report) refuse a case file with friction keys
// at the line of [friction].
TEST(CliFriction, CommandsWithoutFrictionRefuseAFrictionalCaseFile) {
  contactrb::test::TempDir dir("friction_file_refusal");
  for (const std::string command : {"snapshots --set training", "offline", "report"}) {
    const CliResult r = run_cli(command + " --case-file " + shell_quote(example_case()) + " --out " +
                                shell_quote((dir.path() / "out").string()));
    contactrb::test::expect_user_error(
        r, "case.toml:36: the case is frictional (key 'friction'): only `contactrb solve` handles friction");
    EXPECT_FALSE(fs::exists(dir.path() / "out")) << command;
  }
}

// A friction-coefficient parameter gives f on the command line (here cattaneo's constant approach
// 0.13 as numbers): the built-in cattaneo's files, byte for byte; the frictionless readers refuse it.
TEST(CliFriction, FrictionCoefficientParameterSetsF) {
  contactrb::test::TempDir dir("friction_parameter");
  std::string text = contactrb::test::file_text(example_case());
  auto replace_all = [&text](const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
      text.replace(at, from.size(), to);
    }
  };
  replace_all("uy = { b = -0.5 }", "uy = -0.065");
  replace_all("uy = { b = 0.5 }", "uy = 0.065");
  replace_all("name = \"approach\"\nkind = \"dirichlet-scale\"\ndomain = [0.11, 0.45]\nreference = 0.13",
              "name = \"f\"\nkind = \"friction-coefficient\"\ndomain = [0.0, 1.0]\nreference = 0.3");
  replace_all("training = [0.12, 0.14]", "training = [0.2, 0.4]");
  const std::size_t c = text.find("coefficient = 0.3");
  ASSERT_NE(c, std::string::npos);
  const std::string with_key = text;
  text.erase(c, text.find('\n', c) - c);
  const fs::path file = dir.path() / "f.toml";
  std::ofstream(file) << text;
  const fs::path a = dir.path() / "builtin", b = dir.path() / "file";
  ASSERT_EQ(run_cli("solve --case cattaneo --mu 0.2 --level 1 --out " + shell_quote(a.string())).exit_code, 0);
  const CliResult r =
      run_cli("solve --case-file " + shell_quote(file.string()) + " --mu f=0.2 --level 1 --out " + shell_quote(b.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(read_json(b / "solution.json")["friction_coefficient"].get<double>(), 0.2);
  EXPECT_EQ(contactrb::test::file_text((a / "multipliers.csv").string()),
            contactrb::test::file_text((b / "multipliers.csv").string()));
  using contactrb::test::expect_user_error;
  expect_user_error(run_cli("solve --case-file " + shell_quote(file.string()) + " --mu 1.5 --out " +
                            shell_quote((dir.path() / "out").string())),
                    "outside the domain [0, 1]");
  // Both the key and the parameter give f; the parameter without [friction].
  const fs::path both = dir.path() / "both.toml", plain = dir.path() / "plain.toml";
  std::ofstream(both) << with_key;
  std::ofstream(plain) << text.substr(0, text.find("[friction]"));
  expect_user_error(run_cli("solve --case-file " + shell_quote(both.string()) + " --mu 0.2 --out " +
                            shell_quote((dir.path() / "out").string())),
                    "key 'friction.coefficient' and parameter 'f' (friction-coefficient) both give f");
  expect_user_error(run_cli("snapshots --case-file " + shell_quote(plain.string()) + " --set training --out " +
                            shell_quote((dir.path() / "out.h5").string())),
                    "parameter 'f' of kind friction-coefficient needs a [friction] table with law = coulomb");
}

// The same free upper body without friction: nothing holds it along x, whatever the solver and
// whether or not a sparse factorization of the singular A_00 passes at round-off (it does at
// level 1 on some machines, and the Newton then ran out of iterations): one error naming the body.
TEST(CliFriction, AFloatingBodyWithoutFrictionIsOneClearError) {
  contactrb::test::TempDir dir("friction_floating");
  const std::string free_top = edited_case(dir.path(), "free.toml", "group = \"top\"\nux = 0.0\n", "group = \"top\"\n");
  std::string text = contactrb::test::file_text(free_top);
  std::ofstream(free_top) << text.substr(0, text.find("[friction]"));
  for (const char* solver : {"newton", "kacanov"}) {
    for (const char* level : {"0", "1"}) {
      expect_user_error(run_cli("solve --case-file " + shell_quote(free_top) + " --mu 0.13 --level " + level +
                                " --solver " + solver + " --out " + shell_quote((dir.path() / "out").string())),
                        "body 0 (slave) is not held by the Dirichlet conditions");
    }
  }
}

// The upper body free along x, held by nothing but friction once in contact: the path has no
// equilibrium. solution.json says so (status full-sliding, converged false), no field file is
// left, one error line, exit code 3 (as a frictionless solve that fails).
TEST(CliFriction, FullSlidingIsAStatusAndExitCodeThree) {
  contactrb::test::TempDir dir("friction_sliding");
  const std::string free_top = edited_case(dir.path(), "free.toml", "group = \"top\"\nux = 0.0\n", "group = \"top\"\n");
  std::string text = contactrb::test::file_text(free_top);
  text = text.substr(0, text.find("[[load_steps]]")) +
         "[[load_steps]]\n[[load_steps.dirichlet]]\ngroup = \"top\"\nuy = { b = -0.5 }\n"
         "[[load_steps.dirichlet]]\ngroup = \"bottom\"\nux = 0.0\nuy = { b = 0.5 }\n";
  std::ofstream(free_top) << text;
  const fs::path out = dir.path() / "out";
  fs::create_directories(out);
  std::ofstream(out / "multipliers.csv") << "an earlier run's file\n";
  const CliResult r =
      run_cli("solve --case-file " + shell_quote(free_top) + " --mu 0.13 --level 1 --out " + shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_EQ(r.err.rfind("contactrb: error: full-sliding: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const nlohmann::json j = read_json(out / "solution.json");
  EXPECT_EQ(j["status"], "full-sliding");
  EXPECT_FALSE(j["converged"].get<bool>());
  EXPECT_EQ(j["steps"].back()["status"], "full-sliding");
  EXPECT_FALSE(fs::exists(out / "multipliers.csv"));
}
