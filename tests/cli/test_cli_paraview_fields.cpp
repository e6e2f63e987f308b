// The ParaView fields of `contactrb solve` (docs/file-formats.md, "VTU files (ParaView)") against the exact
// solution of the contact patch test (examples/two-block-patch: uniaxial stress, uniform
// pressure p = E / (1 - nu^2) * mu / 2, recovered to round-off by LAC), read back with an
// independent reader (meshio, support/meshio_reader.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"
#include "support/meshio_reader.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;
using nlohmann::json;

namespace {

constexpr double kE = 10.0;
constexpr double kNu = 0.3;
constexpr double kMu = 0.02;

}  // namespace

TEST(CliParaViewFields, PatchTestStressPressureAndGapAreExact) {
  SKIP_WITHOUT_MESHIO();
  contactrb::test::TempDir dir("paraview_patch");
  const std::string toml = std::string(CONTACTRB_SOURCE_DIR) + "/examples/two-block-patch/case.toml";
  const auto r =
      run_cli("solve --case-file " + shell_quote(toml) + " --mu 0.02 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("wrote " + dir.file("contact.vtu")), std::string::npos) << r.out;

  const double p = kE / (1.0 - kNu * kNu) * kMu / 2.0;
  const double tol = 1e-9 * p;
  const json s = contactrb::test::read_vtu_with_meshio(dir.path() / "solution.vtu");
  ASSERT_FALSE(s.is_null());
  // The parameter point as field data, named as in the case file.
  EXPECT_EQ(s["field_data"], json::parse(R"({"imposed displacement": [0.02]})"));
  const json& c = s["cell_data"];
  const std::size_t triangles = s["cells"][0]["data"].size();
  ASSERT_GT(triangles, 10u);
  for (const char* name : {"stress_xx", "stress_yy", "stress_xy", "stress_zz", "von_mises"}) {
    ASSERT_TRUE(c.contains(name)) << name;
    ASSERT_EQ(c[name][0].size(), triangles) << name;
  }
  for (std::size_t t = 0; t < triangles; ++t) {
    // Uniaxial stress in plane strain: sxx = sxy = 0, syy = -p, szz = nu syy,
    // von Mises = p sqrt(1 - nu + nu^2).
    EXPECT_NEAR(c["stress_xx"][0][t].get<double>(), 0.0, tol) << t;
    EXPECT_NEAR(c["stress_xy"][0][t].get<double>(), 0.0, tol) << t;
    EXPECT_NEAR(c["stress_yy"][0][t].get<double>(), -p, tol) << t;
    EXPECT_NEAR(c["stress_zz"][0][t].get<double>(), -kNu * p, tol) << t;
    EXPECT_NEAR(c["von_mises"][0][t].get<double>(), p * std::sqrt(1.0 - kNu + kNu * kNu), tol) << t;
  }

  // The deformed file: the same fields, points moved by the displacement.
  const json d = contactrb::test::read_vtu_with_meshio(dir.path() / "solution_deformed.vtu");
  ASSERT_EQ(d["points"].size(), s["points"].size());
  for (std::size_t i = 0; i < s["points"].size(); ++i) {
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_NEAR(d["points"][i][k].get<double>(),
                  s["points"][i][k].get<double>() + s["point_data"]["displacement"][i][k].get<double>(), 1e-15);
    }
  }
  EXPECT_EQ(d["cell_data"]["von_mises"], c["von_mises"]);

  // contact.vtu: the slave face (the upper block's 8 edges) as line cells, uniform pressure,
  // closed gap.
  const json f = contactrb::test::read_vtu_with_meshio(dir.path() / "contact.vtu");
  ASSERT_FALSE(f.is_null());
  ASSERT_EQ(f["cells"].size(), 1u);
  EXPECT_EQ(f["cells"][0]["type"], "line");
  const std::size_t nodes = f["points"].size();
  EXPECT_EQ(nodes, 9u);
  EXPECT_EQ(f["cells"][0]["data"].size(), nodes - 1);
  EXPECT_EQ(f["field_data"], s["field_data"]);
  for (std::size_t i = 0; i < nodes; ++i) {
    EXPECT_NEAR(f["point_data"]["contact_pressure"][i].get<double>(), p, tol) << i;
    EXPECT_NEAR(f["point_data"]["gap"][i].get<double>(), 0.0, 1e-12) << i;
    EXPECT_EQ(f["points"][i][1].get<double>(), 0.0) << i;  // the interface y = 0
    EXPECT_NEAR(f["point_data"]["displacement"][i][1].get<double>(), -kMu / 2.0, 1e-12) << i;
  }
  for (std::size_t e = 0; e + 1 < nodes; ++e) {  // consecutive chain nodes
    EXPECT_EQ(f["cells"][0]["data"][e], json::array({e, e + 1}));
  }
}
