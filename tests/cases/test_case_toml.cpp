// TOML cases: round trip of the built-in specs, the format's options, and the errors a
// user can make (each naming the key and the file, with the line when toml++ knows it).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/common/error.hpp"

using namespace contactrb;
namespace fs = std::filesystem;

namespace {

const std::string kOrigin = "/nowhere/my-case.toml";

// A valid case on a built-in mesh; tests edit it with replace_in.
std::string good_case() {
  return R"(name = "mine"
constraint = "lac"

[mesh]
generator = "hertz"

[slave]
E = 15
nu = 0.35

[master]
E = 15.0
nu = 0.35
load = [0.0, -0.1]

[[dirichlet]]
group = "top"
ux = 0.0
uy = { a = 0.0, b = -0.5 }

[[dirichlet]]
group = "bottom"
ux = 0.0
uy = { b = 0.5 }

[parameter]
name = "imposed displacement"
kind = "dirichlet-scale"
domain = [0.15, 0.45]
training = { start = 0.15, step = 0.05, count = 7 }
)";
}

std::string replace_in(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  if (pos == std::string::npos) throw std::runtime_error("test bug: '" + from + "' not in the text");
  return text.replace(pos, from.size(), to);
}

// The message of the Error thrown by case_from_toml_string.
std::string error_of(const std::string& text) {
  try {
    cases::case_from_toml_string(text, kOrigin);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

void expect_mentions(const std::string& message, std::initializer_list<const char*> words) {
  for (const char* w : words) EXPECT_NE(message.find(w), std::string::npos) << "'" << w << "' not in: " << message;
}

}  // namespace

TEST(CaseToml, BuiltinSpecsRoundTrip) {
  for (const char* name : {"hertz-a", "hertz-b", "ring-block"}) {
    const cases::CaseSpec spec = cases::builtin_case_spec(name);
    const std::string text = cases::to_toml(spec);
    const cases::CaseSpec back = cases::case_from_toml_string(text, "stored.toml");
    EXPECT_TRUE(cases::same_case(spec, back)) << text;
    EXPECT_EQ(back.origin, "stored.toml");
    EXPECT_EQ(cases::to_toml(back), text);
  }
}

TEST(CaseToml, ReadsAllOptions) {
  const cases::CaseSpec c = cases::case_from_toml_string(good_case(), kOrigin);
  EXPECT_EQ(c.name, "mine");
  EXPECT_EQ(c.origin, kOrigin);
  EXPECT_EQ(c.constraint, contact::Discretization::LAC);
  EXPECT_EQ(c.mesh.generator, "hertz");
  EXPECT_EQ(c.bodies[0].E, 15.0);  // an integer is a number
  EXPECT_EQ(c.bodies[1].load, Eigen::Vector2d(0.0, -0.1));
  ASSERT_EQ(c.dirichlet.size(), 2u);
  EXPECT_EQ(c.dirichlet[0].uy->b, -0.5);
  EXPECT_EQ(c.dirichlet[1].uy->a, 0.0);  // a defaults to 0
  EXPECT_EQ(c.dirichlet[1].uy->b, 0.5);
  EXPECT_EQ(c.parameters.front().kind, cases::ParameterKind::DirichletScale);
  EXPECT_EQ(c.parameters.front().reference, 0.15);  // default: the domain's lower end
  ASSERT_EQ(cases::values_1d(c.set("training")).size(), 7u);
  EXPECT_EQ(cases::values_1d(c.set("training")).back(), 0.45);  // 0.15 + 6 * 0.05 snapped onto the bound
  // No verification key: the midpoints of the training set.
  ASSERT_EQ(cases::values_1d(c.set("verification")).size(), 6u);
  EXPECT_NEAR(cases::values_1d(c.set("verification")).front(), 0.175, 1e-15);
}

TEST(CaseToml, BodyScalingNeedsBodyCenterAndReference) {
  std::string text = replace_in(good_case(), R"(kind = "dirichlet-scale")",
                                R"(kind = "body-scaling"
body = "master"
center = [0.0, -0.05]
reference = 0.3)");
  const cases::CaseSpec c = cases::case_from_toml_string(text, kOrigin);
  EXPECT_EQ(c.parameters.front().body, 1);
  EXPECT_EQ(c.parameters.front().center, Eigen::Vector2d(0.0, -0.05));
  const std::string no_center = replace_in(text, "center = [0.0, -0.05]\n", "");
  expect_mentions(error_of(no_center), {"missing key 'parameter.center'", kOrigin.c_str()});
  expect_mentions(error_of(replace_in(text, R"(body = "master")", R"(body = "upper")")),
                  {"parameter.body", "slave or master", kOrigin.c_str()});
}

TEST(CaseToml, UnknownKeysAreNamedWithFileAndLine) {
  const std::string m1 = error_of(replace_in(good_case(), "domain = [0.15, 0.45]", "domian = [0.15, 0.45]"));
  expect_mentions(m1, {"unknown key 'parameter.domian'", "my-case.toml:", "domain"});
  const std::string m2 = error_of("colour = 3\n" + good_case());
  expect_mentions(m2, {"unknown key 'colour'", "my-case.toml:1:"});
  const std::string m3 = error_of(replace_in(good_case(), "ux = 0.0\nuy = { a", "ux = 0.0\nuw = 1.0\nuy = { a"));
  expect_mentions(m3, {"unknown key 'dirichlet[1].uw'", "my-case.toml:"});
  const std::string m4 = error_of(replace_in(good_case(), "{ b = 0.5 }", "{ b = 0.5, c = 1 }"));
  expect_mentions(m4, {"unknown key 'dirichlet[2].uy.c'"});
}

TEST(CaseToml, MissingKeysAreNamed) {
  expect_mentions(error_of(replace_in(good_case(), "name = \"mine\"\n", "")), {"missing key 'name'", kOrigin.c_str()});
  expect_mentions(error_of(replace_in(good_case(), "nu = 0.35\nload", "load")),
                  {"missing key 'master.nu'", kOrigin.c_str()});
  expect_mentions(error_of(replace_in(good_case(), "training = { start = 0.15, step = 0.05, count = 7 }\n", "")),
                  {"missing key 'parameter.training'", "my-case.toml:"});
  expect_mentions(error_of(replace_in(good_case(), "step = 0.05, ", "")), {"missing key 'parameter.training.step'"});
  expect_mentions(error_of(replace_in(good_case(), "generator = \"hertz\"", "")),
                  {"mesh.file", "mesh.generator", kOrigin.c_str()});
}

TEST(CaseToml, WrongTypesAreNamed) {
  expect_mentions(error_of(replace_in(good_case(), "E = 15\n", "E = \"15\"\n")),
                  {"key 'slave.E' must be a number, got a string", "my-case.toml:"});
  expect_mentions(error_of(replace_in(good_case(), "domain = [0.15, 0.45]", "domain = [0.15]")),
                  {"parameter.domain", "array of 2 numbers"});
  expect_mentions(error_of(replace_in(good_case(), "domain = [0.15, 0.45]", "domain = [0.15, \"x\"]")),
                  {"parameter.domain", "element 2 is a string"});
  expect_mentions(error_of(replace_in(good_case(), "count = 7", "count = 7.5")),
                  {"parameter.training.count", "an integer"});
  expect_mentions(error_of(replace_in(good_case(), "uy = { a = 0.0, b = -0.5 }", "uy = \"-mu/2\"")),
                  {"dirichlet[1].uy", "a number or a table"});
  expect_mentions(error_of(replace_in(good_case(), "constraint = \"lac\"", "constraint = \"mortar\"")),
                  {"constraint", "mortar"});
  expect_mentions(error_of(replace_in(good_case(), "[mesh]\ngenerator = \"hertz\"", "mesh = \"hertz\"")),
                  {"key 'mesh' must be a table, got a string"});
}

TEST(CaseToml, InvalidValuesAreNamed) {
  expect_mentions(error_of(replace_in(good_case(), "nu = 0.35\n\n[master]", "nu = 0.5\n\n[master]")),
                  {"Poisson", kOrigin.c_str()});
  expect_mentions(error_of(replace_in(good_case(), "count = 7", "count = 8")), {"outside the domain", "training"});
  // No Dirichlet value depends on mu although the kind says so.
  const std::string frozen = replace_in(replace_in(good_case(), "b = -0.5", "b = 0.0"), "{ b = 0.5 }", "0.5");
  expect_mentions(error_of(frozen), {"dirichlet-scale", "depends on it"});
  expect_mentions(error_of(replace_in(good_case(), "generator = \"hertz\"", "generator = \"cube\"")),
                  {"mesh.generator", "cube"});
}

TEST(CaseToml, SyntaxErrorGivesFileLineAndColumn) {
  const std::string m = error_of(replace_in(good_case(), "nu = 0.35\n\n[master]", "nu = = 0.35\n\n[master]"));
  expect_mentions(m, {"my-case.toml:9:", "TOML syntax error"});
}

TEST(CaseToml, MeshFileIsResolvedAgainstTheTomlDirectory) {
  const fs::path dir = fs::temp_directory_path() / ("contactrb_case_toml_" + std::to_string(::getpid()));
  fs::create_directories(dir / "meshes");
  { std::ofstream(dir / "meshes" / "m.msh") << "not read here\n"; }
  const std::string text = replace_in(good_case(), "generator = \"hertz\"", "file = \"meshes/m.msh\"");
  const std::string path = (dir / "case.toml").string();
  { std::ofstream(path) << text; }
  const cases::CaseSpec c = cases::case_from_toml_file(path);
  EXPECT_EQ(c.mesh.msh_file, (dir / "meshes" / "m.msh").string());
  EXPECT_EQ(c.mesh.slave_group, "slave");
  // to_toml keeps the resolved path, so the text can be read from anywhere.
  EXPECT_TRUE(cases::same_case(c, cases::case_from_toml_string(cases::to_toml(c), "elsewhere.toml")));
  // A missing .msh is named.
  fs::remove(dir / "meshes" / "m.msh");
  try {
    cases::case_from_toml_file(path);
    ADD_FAILURE();
  } catch (const Error& e) {
    expect_mentions(e.what(), {"mesh.file", "m.msh", "does not exist", "case.toml:5"});
  }
  // A directory in its place, and a device, are named as such.
  fs::create_directories(dir / "meshes" / "m.msh");
  try {
    cases::case_from_toml_file(path);
    ADD_FAILURE();
  } catch (const Error& e) {
    expect_mentions(e.what(), {"mesh.file", "m.msh", "is a directory, not a file", "case.toml:5"});
  }
  {
    std::string device = text;
    const std::size_t at = device.find("meshes/m.msh");
    ASSERT_NE(at, std::string::npos) << device;
    device.replace(at, std::string("meshes/m.msh").size(), "/dev/zero");
    try {
      cases::case_from_toml_string(device, path);
      ADD_FAILURE();
    } catch (const Error& e) {
      expect_mentions(e.what(), {"mesh.file", "/dev/zero", "is not a regular file"});
    }
  }
  fs::remove_all(dir);
  try {
    cases::case_from_toml_file(path);
    ADD_FAILURE();
  } catch (const Error& e) {
    expect_mentions(e.what(), {"case file", "case.toml", "does not exist"});
  }
}

TEST(CaseToml, GroupKeysNeedAMeshFile) {
  expect_mentions(error_of(replace_in(good_case(), "E = 15\n", "E = 15\nboundary = \"arc\"\n")),
                  {"slave.boundary", "mesh.generator"});
}
