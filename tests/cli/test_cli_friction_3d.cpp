// contactrb solve on the 3D frictional cases (the built-in cattaneo-3d, the case file
// examples/block-on-block-3d), the per-step ParaView series of every frictional solve (2D and 3D),
// and the commands without friction refusing them. The files are read back against
// Cattaneo-Mindlin, Coulomb's law and the solver's own totals; the VTU files by meshio, the .pvd
// collections by their XML text.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "csv_text.hpp"
#include "json_text.hpp"
#include "support/meshio_reader.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::numbers;
using contactrb::test::read_csv;
using contactrb::test::read_json;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

namespace {

// The rows of a 3D frictional multipliers.csv.
struct Rows3 {
  std::vector<double> x, y, p, t1, t2, w;
  std::vector<std::string> state;
  std::size_t size() const { return p.size(); }
  double t(std::size_t i) const { return std::hypot(t1[i], t2[i]); }
};

Rows3 read_rows3(const fs::path& csv_path) {
  const auto csv = read_csv(csv_path.string());
  Rows3 r{numbers(csv.at("x")),  numbers(csv.at("y")),          numbers(csv.at("pressure")),
          numbers(csv.at("tangential_1")), numbers(csv.at("tangential_2")), numbers(csv.at("weight")),
          csv.at("state")};
  EXPECT_EQ(r.state.size(), r.p.size());
  return r;
}

// The radius sqrt(-alpha / beta) of the least-squares line v = alpha + beta r^2 over the rows
// `select` keeps (r: the distance to `centre` in the plane z = const).
template <class Select, class Value>
double fitted_radius(const Rows3& rows, double cx, double cy, Select select, Value value) {
  double n = 0, s1 = 0, s2 = 0, sv = 0, s1v = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!select(i)) continue;
    const double r2 = std::pow(rows.x[i] - cx, 2) + std::pow(rows.y[i] - cy, 2);
    n += 1;
    s1 += r2;
    s2 += r2 * r2;
    sv += value(i);
    s1v += r2 * value(i);
  }
  const double beta = (n * s1v - s1 * sv) / (n * s2 - s1 * s1), alpha = (sv - beta * s1) / n;
  return std::sqrt(-alpha / beta);
}

// Counts of the CSV's states against solution.json; Coulomb's cone at every row, |t| = f p on
// the slip rows, t = 0 on the open ones; the sums of the tractions times the weights against the
// reported forces.
void expect_coulomb_files(const fs::path& dir, double f) {
  const nlohmann::json j = read_json(dir / "solution.json");
  const Rows3 rows = read_rows3(dir / "multipliers.csv");
  ASSERT_GT(rows.size(), 0u);
  const double p_max = *std::max_element(rows.p.begin(), rows.p.end());
  int stick = 0, slip = 0, open = 0;
  double P = 0.0, F1 = 0.0, F2 = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    stick += rows.state[i] == "stick";
    slip += rows.state[i] == "slip";
    open += rows.state[i] == "open";
    P += rows.p[i] * rows.w[i];
    F1 += rows.t1[i] * rows.w[i];
    F2 += rows.t2[i] * rows.w[i];
    // the solver's tolerance 1e-10 on the friction residual relative to max p, and 17 digits
    EXPECT_LE(rows.t(i), f * rows.p[i] + 1e-9 * p_max) << "row " << i;
    if (rows.state[i] == "slip") {
      EXPECT_NEAR(rows.t(i), f * rows.p[i], 1e-9 * p_max) << "row " << i;
    } else if (rows.state[i] == "open") {
      EXPECT_EQ(rows.t(i), 0.0) << "row " << i;
    }
  }
  EXPECT_EQ(stick + slip + open, static_cast<int>(rows.size()));
  EXPECT_EQ(stick, j["stick_nodes"].get<int>());
  EXPECT_EQ(slip, j["slip_nodes"].get<int>());
  EXPECT_EQ(open, j["steps"].back()["open_nodes"].get<int>());
  EXPECT_NEAR(P, j["contact_force"].get<double>(), 1e-12 * P);
  ASSERT_EQ(j["tangential_force"].size(), 2u);
  EXPECT_NEAR(F1, j["tangential_force"][0].get<double>(), 1e-12 * P);
  EXPECT_NEAR(F2, j["tangential_force"][1].get<double>(), 1e-12 * P);
}

}  // namespace

// Cattaneo-Mindlin for spheres (Johnson 7.2): c / a = (1 - Q / (f P))^(1/3), c and a fitted as in
// tests/hf/test_friction3d.cpp (a from p^2, c from (f p - |t|)^2, linear in r^2) on the rows of
// multipliers.csv, r the distance to the centre of pressure in the reference plane; the bound
// of the C++ test at the same level (5 % on level 1).
TEST(CliFriction3d, Cattaneo3dStickRadiusAndCoulombsLaw) {
  contactrb::test::TempDir dir("friction3d_cattaneo");
  const double f = 0.3;
  const CliResult r = run_cli("solve --case cattaneo-3d --mu f=0.3 --level 1 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("case cattaneo-3d (3D, frictional: coulomb f = 0.3)"), std::string::npos) << r.out;
  const nlohmann::json j = read_json(dir.path() / "solution.json");
  EXPECT_EQ(j["case"], "cattaneo-3d");
  EXPECT_EQ(j["dimension"].get<int>(), 3);
  EXPECT_EQ(j["friction_coefficient"].get<double>(), f);
  ASSERT_EQ(j["steps"].size(), 2u);
  for (const nlohmann::json& step : j["steps"]) {
    EXPECT_EQ(step["status"], "converged");
    EXPECT_LE(step["iterations"].get<int>(), 15);
  }
  expect_coulomb_files(dir.path(), f);

  const Rows3 rows = read_rows3(dir.path() / "multipliers.csv");
  double P = 0.0, cx = 0.0, cy = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    P += rows.p[i] * rows.w[i];
    cx += rows.p[i] * rows.w[i] * rows.x[i];
    cy += rows.p[i] * rows.w[i] * rows.y[i];
  }
  cx /= P;
  cy /= P;
  const double a = fitted_radius(rows, cx, cy, [&](std::size_t i) { return rows.p[i] > 0.0; },
                                 [&](std::size_t i) { return rows.p[i] * rows.p[i]; });
  const double c = fitted_radius(
      rows, cx, cy, [&](std::size_t i) { return rows.state[i] == "stick" && rows.p[i] > 0.0; },
      [&](std::size_t i) { return std::pow(f * rows.p[i] - rows.t(i), 2); });
  // The top moves along +x: the traction on the slave along -x, none along y (symmetry y -> -y).
  const double Q = -j["tangential_force"][0].get<double>();
  EXPECT_GT(Q, 0.0);
  EXPECT_LT(std::abs(j["tangential_force"][1].get<double>()), 1e-9 * Q);
  const double ratio = Q / (f * j["contact_force"].get<double>());
  EXPECT_GT(ratio, 0.4);
  EXPECT_LT(ratio, 0.6);
  EXPECT_GT(a, 0.13);  // Hertz at this approach: about 0.14
  EXPECT_LT(a, 0.17);
  EXPECT_NEAR((c / a) / std::cbrt(1.0 - ratio), 1.0, 0.05) << "c = " << c << ", a = " << a << ", Q/(fP) = " << ratio;
}

// contact.vtu in 3D: the slave triangles, one point per row, the tangential traction as the
// vector t_1 tau_1 + t_2 tau_2 (its length that of the CSV's two columns; tau_1, tau_2 the
// tangents of the deformed master, close to x and y) and the state as in the CSV.
TEST(CliFriction3d, ContactVtuCarriesTheTractionVectorAndState) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("friction3d_vtu");
  const CliResult r = run_cli("solve --case cattaneo-3d --mu 0.3 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const Rows3 rows = read_rows3(dir.path() / "multipliers.csv");
  const nlohmann::json surface = contactrb::test::read_vtu_with_meshio(dir.path() / "contact.vtu");
  EXPECT_EQ(surface["cells"][0]["type"], "triangle");
  ASSERT_EQ(surface["points"].size(), rows.size());
  const nlohmann::json& t = surface["point_data"]["tangential_traction"];
  const nlohmann::json& state = surface["point_data"]["state"];
  ASSERT_EQ(t.size(), rows.size());
  const double p_max = *std::max_element(rows.p.begin(), rows.p.end());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(surface["points"][i][0].get<double>(), rows.x[i]);
    const double tx = t[i][0].get<double>(), ty = t[i][1].get<double>(), tz = t[i][2].get<double>();
    // tau_1, tau_2: orthonormal, close to x and y (the deformed master's normal is near +z)
    EXPECT_NEAR(std::sqrt(tx * tx + ty * ty + tz * tz), rows.t(i), 1e-12 * p_max) << "row " << i;
    EXPECT_NEAR(tx, rows.t1[i], 0.05 * rows.t(i)) << "row " << i;
    EXPECT_NEAR(ty, rows.t2[i], 0.05 * rows.t(i)) << "row " << i;
    const double code = rows.state[i] == "open" ? 0.0 : rows.state[i] == "stick" ? 1.0 : 2.0;
    EXPECT_EQ(state[i].get<double>(), code) << "row " << i;
  }
}

// The 3D example case file: its three load steps, Coulomb's law, the tangential force opposite
// to the top's motion (0.0006, 0.0003) and below f P.
TEST(CliFriction3d, CaseFileSolvesItsLoadPath) {
  contactrb::test::TempDir dir("friction3d_file");
  const std::string file = std::string(CONTACTRB_SOURCE_DIR) + "/examples/block-on-block-3d/case.toml";
  const CliResult r = run_cli("solve --case-file " + shell_quote(file) + " --mu 0.004 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = read_json(dir.path() / "solution.json");
  EXPECT_EQ(j["dimension"].get<int>(), 3);
  EXPECT_EQ(j["load_steps"].get<int>(), 3);
  ASSERT_EQ(j["steps"].size(), 3u);
  for (const nlohmann::json& step : j["steps"]) EXPECT_EQ(step["status"], "converged");
  expect_coulomb_files(dir.path(), 0.3);
  const double F1 = j["tangential_force"][0].get<double>(), F2 = j["tangential_force"][1].get<double>();
  EXPECT_LT(F1, 0.0);
  EXPECT_LT(F2, 0.0);
  EXPECT_LT(std::hypot(F1, F2), 0.3 * j["contact_force"].get<double>());
  EXPECT_GT(j["stick_nodes"].get<int>(), 0);
  EXPECT_GT(j["slip_nodes"].get<int>(), 0);
}

namespace {

struct PvdEntry {
  double timestep;
  std::string file;
};

// The DataSet entries of a .pvd, from its XML text.
std::vector<PvdEntry> pvd_entries(const fs::path& path) {
  const std::string text = contactrb::test::file_text(path.string());
  EXPECT_NE(text.find("<VTKFile type=\"Collection\""), std::string::npos) << text;
  std::vector<PvdEntry> entries;
  // A plain search, not <regex>: g++ 12 warns (-Wmaybe-uninitialized) inside std::regex under
  // the sanitizer build.
  const auto attribute = [](const std::string& element, const std::string& name) {
    const std::string key = " " + name + "=\"";
    const std::size_t at = element.find(key);
    if (at == std::string::npos) return std::string();
    const std::size_t from = at + key.size();
    return element.substr(from, element.find('"', from) - from);
  };
  for (std::size_t at = text.find("<DataSet"); at != std::string::npos; at = text.find("<DataSet", at + 1)) {
    const std::string element = text.substr(at, text.find("/>", at) - at);
    const std::string timestep = attribute(element, "timestep"), file = attribute(element, "file");
    EXPECT_FALSE(timestep.empty() || file.empty()) << element;
    if (!timestep.empty()) entries.push_back({std::stod(timestep), file});
  }
  return entries;
}

// One ParaView series per frictional solve: solution_steps.pvd and contact_steps.pvd list one
// VTU per load step (timestep = its number), each read by meshio: the step's stick and slip
// counts of solution.json in its "state" array, no tangential traction after the normal
// approach, and the last step's arrays those of contact.vtu.
void expect_step_series(const fs::path& dir, int components) {
  const nlohmann::json j = read_json(dir / "solution.json");
  const std::size_t steps = j["steps"].size();
  const std::vector<PvdEntry> solution = pvd_entries(dir / "solution_steps.pvd");
  const std::vector<PvdEntry> contact = pvd_entries(dir / "contact_steps.pvd");
  ASSERT_EQ(solution.size(), steps);
  ASSERT_EQ(contact.size(), steps);
  const nlohmann::json final_surface = contactrb::test::read_vtu_with_meshio(dir / "contact.vtu");
  for (std::size_t k = 0; k < steps; ++k) {
    EXPECT_EQ(solution[k].timestep, static_cast<double>(k + 1));
    EXPECT_EQ(contact[k].timestep, static_cast<double>(k + 1));
    const nlohmann::json omega = contactrb::test::read_vtu_with_meshio(dir / solution[k].file);
    EXPECT_TRUE(omega["point_data"].contains("displacement")) << solution[k].file;
    const nlohmann::json surface = contactrb::test::read_vtu_with_meshio(dir / contact[k].file);
    const nlohmann::json& state = surface["point_data"]["state"];
    const nlohmann::json& t = surface["point_data"]["tangential_traction"];
    int stick = 0, slip = 0;
    double t_max = 0.0;
    for (std::size_t i = 0; i < state.size(); ++i) {
      stick += state[i].get<double>() == 1.0;
      slip += state[i].get<double>() == 2.0;
      for (int c = 0; c < components; ++c) {
        t_max = std::max(t_max, std::abs(components == 1 ? t[i].get<double>() : t[i][c].get<double>()));
      }
    }
    EXPECT_EQ(stick, j["steps"][k]["stick_nodes"].get<int>()) << contact[k].file;
    EXPECT_EQ(slip, j["steps"][k]["slip_nodes"].get<int>()) << contact[k].file;
    if (k == 0) {
      EXPECT_EQ(t_max, 0.0);  // the normal approach of two bodies of one material
    }
    if (k + 1 == steps) {
      EXPECT_GT(t_max, 0.0);
      EXPECT_EQ(surface["point_data"], final_surface["point_data"]);
    }
  }
}

}  // namespace

TEST(CliFrictionSteps, ParaViewSeriesOverTheLoadSteps2d) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("friction_steps_2d");
  const CliResult r = run_cli("solve --case cattaneo --mu 0.3 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  expect_step_series(dir.path(), 1);
}

TEST(CliFrictionSteps, ParaViewSeriesOverTheLoadSteps3d) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("friction_steps_3d");
  const CliResult r = run_cli("solve --case cattaneo-3d --mu 0.3 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  expect_step_series(dir.path(), 3);
}

// Every command without friction refuses the 3D frictional cases in one line, exit code 1,
// nothing written.
class CliFriction3dRefusal : public ::testing::TestWithParam<const char*> {};

TEST_P(CliFriction3dRefusal, RefusesTheFrictionalCase) {
  contactrb::test::TempDir dir("friction3d_refusal");
  const CliResult r = run_cli(std::string(GetParam()) + " --out " + shell_quote((dir.path() / "out").string()));
  contactrb::test::expect_user_error(r, "case 'cattaneo-3d' is frictional: only `contactrb solve` handles friction");
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

INSTANTIATE_TEST_SUITE_P(Commands, CliFriction3dRefusal,
                         ::testing::Values("snapshots --case cattaneo-3d --set training", "offline --case cattaneo-3d",
                                           "report --case cattaneo-3d", "mesh --case cattaneo-3d"));

TEST(CliFriction3d, CommandsWithoutFrictionRefuseThe3dCaseFile) {
  contactrb::test::TempDir dir("friction3d_file_refusal");
  const std::string file = std::string(CONTACTRB_SOURCE_DIR) + "/examples/block-on-block-3d/case.toml";
  for (const std::string command : {"snapshots --set training", "offline"}) {
    const CliResult r =
        run_cli(command + " --case-file " + shell_quote(file) + " --out " + shell_quote((dir.path() / "out").string()));
    contactrb::test::expect_user_error(
        r, "case.toml:41: the case is frictional (key 'friction'): only `contactrb solve` handles friction");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "out")) << command;
  }
}

TEST(CliFriction3d, BadInputsGiveOneClearError) {
  contactrb::test::TempDir dir("friction3d_bad");
  const std::string out = " --out " + shell_quote((dir.path() / "out").string());
  using contactrb::test::expect_user_error;
  expect_user_error(run_cli("solve --case cattaneo-3d --mu 0.3 --level 3" + out), "cattaneo-3d: level must be in [0, 2] (got 3)");
  expect_user_error(run_cli("solve --case cattaneo-3d --mu 1.5" + out), "outside the domain");
  expect_user_error(run_cli("solve --case cattaneo-3d --mu 0.3 --constraint lac" + out), "collocation only");
  // A 3D case has Dirichlet data only: a load step with a traction is refused.
  const fs::path example = fs::path(CONTACTRB_SOURCE_DIR) / "examples/block-on-block-3d";
  fs::copy_file(example / "block-on-block-3d.msh", dir.path() / "block-on-block-3d.msh");
  std::string text = contactrb::test::file_text((example / "case.toml").string());
  const std::string step3 = "[[load_steps]]           # 3: all of it\n";
  ASSERT_NE(text.find(step3), std::string::npos);
  text.replace(text.find(step3), step3.size(), step3 + "[[load_steps.traction]]\ngroup = \"top\"\nvector = [0.0, -1.0]\n");
  const fs::path traction = dir.path() / "traction.toml";
  std::ofstream(traction) << text;
  expect_user_error(run_cli("solve --case-file " + shell_quote(traction.string()) + " --mu 0.004" + out),
                    "is three-dimensional: its load steps are Dirichlet data only (no [[load_steps.traction]] in 3D)");
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}
