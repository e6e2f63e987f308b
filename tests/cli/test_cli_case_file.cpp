// contactrb solve --case-file: a TOML case runs end to end; the errors a user can make in
// the file end in exit code 1 and one message naming the key and the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;

namespace {

const fs::path kPatchDir = fs::path(CONTACTRB_SOURCE_DIR) / "examples" / "two-block-patch";

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The patch example with one edit, written next to a copy of its .msh in `dir`.
fs::path edited_case(const fs::path& dir, const std::string& from, const std::string& to) {
  std::string text = read_text(kPatchDir / "case.toml");
  if (!from.empty()) {
    const auto pos = text.find(from);
    if (pos == std::string::npos) throw std::runtime_error("test bug: '" + from + "' not in case.toml");
    text.replace(pos, from.size(), to);
  }
  fs::copy_file(kPatchDir / "two-block-patch.msh", dir / "two-block-patch.msh", fs::copy_options::overwrite_existing);
  const fs::path path = dir / "bad-case.toml";
  std::ofstream(path) << text;
  return path;
}

CliResult solve(const fs::path& case_file, const fs::path& out, const std::string& extra = "") {
  return run_cli("solve --case-file " + shell_quote(case_file.string()) + " --mu 0.02 --out " +
                 shell_quote(out.string()) + extra);
}

void expect_user_error(const CliResult& r, std::initializer_list<std::string> words) {
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(r.err.rfind("contactrb: error: ", 0), 0u) << r.err;
  for (const std::string& w : words) EXPECT_NE(r.err.find(w), std::string::npos) << "'" << w << "' not in: " << r.err;
}

}  // namespace

TEST(CliCaseFile, PatchExampleSolvesAndWritesBothVtus) {
  contactrb::test::TempDir dir("case_file_ok");
  const CliResult r = run_cli("solve --case-file " + shell_quote((kPatchDir / "case.toml").string()) +
                              " --mu 0.02 --alpha 1 --tol 1e-12 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  std::ifstream in(dir.path() / "solution.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["case"], "two-block-patch");
  EXPECT_EQ(j["constraint"], "lac");
  EXPECT_TRUE(j["converged"].get<bool>());
  const double p = 10.0 / (1.0 - 0.09) * 0.02 / 2.0;  // uniform pressure of the patch test
  EXPECT_NEAR(j["contact_force"].get<double>(), p, 1e-9 * p);
  EXPECT_NE(j["case_file"].get<std::string>().find("case.toml"), std::string::npos);
  for (const char* f : {"solution.vtu", "solution_deformed.vtu", "multipliers.csv"}) {
    EXPECT_TRUE(fs::exists(dir.path() / f)) << f;
  }
  // Same fields, different points: the deformed file has X + u.
  const std::string ref = read_text(dir.path() / "solution.vtu");
  const std::string def = read_text(dir.path() / "solution_deformed.vtu");
  EXPECT_NE(ref, def);
  EXPECT_NE(def.find("displacement"), std::string::npos);
  EXPECT_NE(r.out.find("solution_deformed.vtu"), std::string::npos) << r.out;
}

TEST(CliCaseFile, BuiltinCaseAlsoWritesTheDeformedVtu) {
  contactrb::test::TempDir dir("case_builtin_deformed");
  const CliResult r = run_cli("solve --case hertz-b --mu 1.1 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(fs::exists(dir.path() / "solution_deformed.vtu"));
}

TEST(CliCaseFile, UnknownKeyIsNamedWithTheFile) {
  contactrb::test::TempDir dir("case_file_unknown");
  const fs::path f = edited_case(dir.path(), "E = 10.0\nnu = 0.3\n\n[master]", "E = 10.0\nnu = 0.3\npoisson = 0.3\n\n[master]");
  expect_user_error(solve(f, dir.path() / "out"), {"unknown key 'slave.poisson'", "bad-case.toml:"});
  EXPECT_FALSE(fs::exists(dir.path() / "out" / "solution.json"));
}

TEST(CliCaseFile, MissingKeyIsNamedWithTheFile) {
  contactrb::test::TempDir dir("case_file_missing");
  const fs::path f = edited_case(dir.path(), "domain = [0.01, 0.03]\n", "");
  expect_user_error(solve(f, dir.path() / "out"), {"missing key 'parameter.domain'", "bad-case.toml"});
}

TEST(CliCaseFile, WrongTypeIsNamedWithTheFile) {
  contactrb::test::TempDir dir("case_file_type");
  const fs::path f = edited_case(dir.path(), "E = 10.0", "E = \"ten\"");
  expect_user_error(solve(f, dir.path() / "out"), {"key 'slave.E' must be a number, got a string", "bad-case.toml:"});
}

TEST(CliCaseFile, MissingMshIsNamedWithTheFile) {
  contactrb::test::TempDir dir("case_file_msh");
  const fs::path f = edited_case(dir.path(), "file = \"two-block-patch.msh\"", "file = \"gone.msh\"");
  expect_user_error(solve(f, dir.path() / "out"), {"mesh.file", "gone.msh", "does not exist", "bad-case.toml:"});
}

TEST(CliCaseFile, MissingCaseFileAndMuOutsideTheDomain) {
  contactrb::test::TempDir dir("case_file_other");
  expect_user_error(solve(dir.path() / "nope.toml", dir.path() / "out"), {"case file", "nope.toml", "does not exist"});
  const fs::path f = edited_case(dir.path(), "", "");
  const CliResult r = run_cli("solve --case-file " + shell_quote(f.string()) + " --mu 0.5 --out " +
                              shell_quote((dir.path() / "out").string()));
  expect_user_error(r, {"outside the domain [0.01, 0.03]", "two-block-patch", "bad-case.toml"});
}

TEST(CliCaseFile, ExactlyOneCaseSource) {
  contactrb::test::TempDir dir("case_file_usage");
  const std::string out = " --mu 0.3 --out " + shell_quote(dir.path().string());
  const CliResult both = run_cli("solve --case hertz-a --case-file " +
                                 shell_quote((kPatchDir / "case.toml").string()) + out);
  EXPECT_NE(both.exit_code, 0);
  EXPECT_NE(both.exit_code, -1);
  const CliResult none = run_cli("solve" + out);
  EXPECT_NE(none.exit_code, 0);
  EXPECT_NE(none.exit_code, -1);
}

// A case file with a relative mesh.file, read from one working directory: the snapshot file
// and the model made from it (each in its own subdirectory, so neither lies next to the
// case's .msh) are used from another working directory by offline, online --out and
// evaluate (they record the mesh path resolved against the case file, absolute). The case is
// examples/hertz-a (its mesh.file is "hertz-a.msh"), three training values, an untruncated
// model: at the training values it reproduces the HF solution.
TEST(CliCaseFile, RelativeMeshPathWorksFromAnyWorkingDirectory) {
  const fs::path example = fs::path(CONTACTRB_SOURCE_DIR) / "examples" / "hertz-a";
  contactrb::test::TempDir dir("case_file_cwd");
  const fs::path work = dir.path() / "work";
  const fs::path elsewhere = dir.path() / "elsewhere";
  for (const fs::path& d : {work / "case", work / "snaps", work / "model", elsewhere / "m2"}) fs::create_directories(d);
  fs::copy_file(example / "case.toml", work / "case" / "case.toml");
  fs::copy_file(example / "hertz-a.msh", work / "case" / "hertz-a.msh");
  ASSERT_NE(read_text(work / "case" / "case.toml").find("file = \"hertz-a.msh\""), std::string::npos);
  const std::string tight = " --alpha 1 --tol 1e-10";

  const CliResult s = run_cli("snapshots --case-file case/case.toml --values 0.15,0.3,0.45 -q" + tight +
                                  " --out snaps/s.h5",
                              work.string());
  ASSERT_EQ(s.exit_code, 0) << s.out << s.err;
  const std::string untruncated = " --n 100 --eps-du 0 --eps-eim-k 0 --eps-eim-g 0";
  const CliResult m = run_cli("offline --snapshots snaps/s.h5" + untruncated + " --out model/model.h5", work.string());
  ASSERT_EQ(m.exit_code, 0) << m.out << m.err;
  const CliResult m2 = run_cli("offline --snapshots ../work/snaps/s.h5 --out m2/model.h5", elsewhere.string());
  ASSERT_EQ(m2.exit_code, 0) << m2.out << m2.err;

  const CliResult hf = run_cli("solve --case-file case/case.toml --mu 0.3" + tight + " --out hf", work.string());
  ASSERT_EQ(hf.exit_code, 0) << hf.out << hf.err;
  std::ifstream hf_json(work / "hf" / "solution.json");
  const double force = nlohmann::json::parse(hf_json).at("contact_force").get<double>();

  const CliResult on = run_cli("online --model ../work/model/model.h5 --mu 0.3 --out online", elsewhere.string());
  ASSERT_EQ(on.exit_code, 0) << on.out << on.err;
  EXPECT_TRUE(fs::exists(elsewhere / "online" / "solution.vtu"));
  EXPECT_NEAR(nlohmann::json::parse(on.out).at("contact_force").get<double>(), force, 1e-6 * force);

  std::ofstream(elsewhere / "mus.txt") << "0.15\n0.3\n0.45\n";
  const CliResult ev = run_cli("evaluate --model ../work/model/model.h5 --set mus.txt -q --out eval", elsewhere.string());
  ASSERT_EQ(ev.exit_code, 0) << ev.out << ev.err;
  std::ifstream in(elsewhere / "eval" / "evaluation.json");
  const nlohmann::json e = nlohmann::json::parse(in);
  EXPECT_EQ(e.at("summary").at("count").get<int>(), 3);
  // The evaluation's HF solves use the model's Kacanov settings (tight): training values are
  // reproduced to solver tolerance.
  EXPECT_LT(e.at("summary").at("e_displ").at("max").get<double>(), 1e-6);
}
