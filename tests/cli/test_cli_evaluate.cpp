// contactrb evaluate and online --out (docs/offline-online.md, "Reconstruction and error indicators") on a tiny hertz-a model: the
// evaluation CSV (header, one line per value), JSON summary and multiplier profiles; --set as a
// named set or a file; a bad set name; online --out writes a VTU with as many points as the HF
// mesh of `contactrb solve`, contact.vtu and one multipliers.csv line per constraint row; --out
// with --batch writes one directory per answered line, byte for byte the files of online --mu,
// and the .pvd collections. The snapshot file and the model are made once for the suite.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "csv_text.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using contactrb::test::CliResult;
using contactrb::test::file_text;
using contactrb::test::read_csv;
using contactrb::test::run_cli;
using contactrb::test::shell_quote;
using nlohmann::json;

namespace {

std::vector<std::string> file_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

// NumberOfPoints of the (single) piece of a VTU file, -1 when absent.
long vtu_points(const std::string& path) {
  // A plain search, not <regex>: g++ 12 warns (-Wmaybe-uninitialized) inside std::regex under
  // the sanitizer build.
  const std::string text = file_text(path);
  const std::string key = "NumberOfPoints=\"";
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return -1;
  const std::size_t begin = at + key.size();
  const std::size_t end = text.find('"', begin);
  if (end == std::string::npos || end == begin ||
      text.find_first_not_of("0123456789", begin) != end) {
    return -1;
  }
  return std::stol(text.substr(begin, end - begin));
}


constexpr const char* kHeader =
    "mu,hf_solver,hf_converged,hf_iterations,hf_time_s,rb_converged,rb_status,rb_iterations,online_time_s,speedup,e_ener,"
    "e_displ,e_inter,e_press,e_force,e_peak,e_press_cone,force_hf,force_rb,peak_hf,peak_rb,energy_hf,energy_rb,"
    "e_energy_norm,estimate,effectivity";

class CliEvaluate : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<contactrb::test::TempDir>("cli_evaluate");
    model_ = dir_->file("model.h5");
    const CliResult s = run_cli("snapshots --case hertz-a --values 0.15,0.3,0.45 -j 2 -q --out " +
                                shell_quote(dir_->file("s.h5")));
    ASSERT_EQ(s.exit_code, 0) << s.out << s.err;
    const CliResult o = run_cli("offline --snapshots " + shell_quote(dir_->file("s.h5")) + " --out " +
                                shell_quote(model_));
    ASSERT_EQ(o.exit_code, 0) << o.out << o.err;
  }
  static void TearDownTestSuite() { dir_.reset(); }
  static std::unique_ptr<contactrb::test::TempDir> dir_;
  static std::string model_;
};
std::unique_ptr<contactrb::test::TempDir> CliEvaluate::dir_;
std::string CliEvaluate::model_;

}  // namespace

TEST_F(CliEvaluate, SetFileGivesOneCsvLinePerValueAndASummary) {
  const std::string values = dir_->file("values.txt");
  {
    std::ofstream out(values);
    out << "0.2\n 0.3 \n\n0.4\n";
  }
  const std::string out = dir_->file("eval_file");
  const CliResult r = run_cli("evaluate -q --model " + shell_quote(model_) + " --set " + shell_quote(values) +
                              " --repeats 2 --multipliers 0.3 --out " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto lines = file_lines(out + "/evaluation.csv");
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], kHeader);
  EXPECT_EQ(lines[1].rfind("0.2,newton,1,", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("0.3,newton,1,", 0), 0u) << lines[2];
  EXPECT_EQ(lines[3].rfind("0.4,newton,1,", 0), 0u) << lines[3];

  std::ifstream in(out + "/evaluation.json");
  const json j = json::parse(in);
  EXPECT_EQ(j.at("summary").at("count"), 3);
  EXPECT_EQ(j.at("summary").at("hf_failures"), 0);
  EXPECT_EQ(j.at("values").size(), 3u);
  EXPECT_EQ(j.at("model"), model_);
  EXPECT_EQ(j.at("set"), values);
  // The HF reference is the Newton solver (the fastest), unsequenced on level 0 (cases::default_sequence).
  EXPECT_EQ(j.at("hf_solver"), "newton");
  EXPECT_EQ(j.at("hf_sequence"), json::array());
  EXPECT_NE(r.out.find("HF reference newton (speed-ups against it)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("speed-up against newton"), std::string::npos) << r.out;
  const double e = j.at("summary").at("e_displ").at("max").get<double>();
  EXPECT_GT(e, 0.0);
  EXPECT_LT(e, 0.1);  // three training values span the Hertz family well
  // The table: errors beside every speed-up.
  EXPECT_NE(r.out.find("e_ener"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("speed-up"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("e_displ max"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("e_press max"), std::string::npos) << r.out;
  const double ep = j.at("summary").at("e_press").at("max").get<double>();
  EXPECT_GE(ep, j.at("summary").at("e_press_cone").at("max").get<double>() * (1.0 - 1e-12));
  EXPECT_GT(ep, 0.0);
  EXPECT_LT(ep, 1.0);  // three training values: the pressure is coarse (0.29), but not unrelated

  // One multiplier line per constraint row (offline.json: compression.constraints).
  std::ifstream off(dir_->file("offline.json"));
  const int rows = json::parse(off).at("compression").at("constraints").get<int>();
  const auto m = file_lines(out + "/multipliers_mu0.3.csv");
  ASSERT_EQ(m.size(), static_cast<std::size_t>(rows + 1));
  EXPECT_EQ(m[0], "abscissa,lambda_hf,lambda_rb");
  EXPECT_FALSE(fs::exists(out + "/multipliers_mu0.2.csv"));
}

TEST_F(CliEvaluate, NamedSetAndUserErrors) {
  const std::string out = dir_->file("eval_named");
  const CliResult r = run_cli("evaluate -q --model " + shell_quote(model_) + " --set training --repeats 1 -j 2 --out " +
                              shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(file_lines(out + "/evaluation.csv").size(), 32u);  // header + hertz-a's 31 training values

  const std::string m = " --model " + shell_quote(model_) + " --out " + shell_quote(dir_->file("bad"));
  expect_user_error(run_cli("evaluate" + m + " --set nosuch"), "neither a parameter set of case 'hertz-a'");
  const std::string bad_values = dir_->file("bad.txt");
  {
    std::ofstream o(bad_values);
    o << "0.2\nabc\n";
  }
  expect_user_error(run_cli("evaluate" + m + " --set " + shell_quote(bad_values)), "line 2: 'abc' is not a number");
  expect_user_error(run_cli("evaluate" + m + " --set training --multipliers 0.155"), "not an evaluated value");
  expect_user_error(run_cli("evaluate" + m + " --n 100"), "--n = 100 is above the maximum");
  expect_user_error(run_cli("evaluate --model " + shell_quote(dir_->file("none.h5")) + " --out " +
                            shell_quote(dir_->file("bad"))),
                    "none.h5");
}

TEST_F(CliEvaluate, OnlineOutWritesTheFieldsOnTheHFMesh) {
  const std::string out = dir_->file("online_out");
  const CliResult r = run_cli("online --model " + shell_quote(model_) + " --mu 0.3 --out " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j.at("files").at("vtu"), out + "/solution.vtu");
  // The HF mesh of the case, from `contactrb solve`.
  const std::string hf = dir_->file("hf");
  ASSERT_EQ(run_cli("solve --case hertz-a --mu 0.3 --out " + shell_quote(hf)).exit_code, 0);
  const long points = vtu_points(hf + "/solution.vtu");
  ASSERT_GT(points, 100);
  for (const char* f : {"/solution.vtu", "/solution_deformed.vtu"}) {
    EXPECT_EQ(file_text(out + f).rfind("<?xml", 0), 0u) << f;
    EXPECT_EQ(vtu_points(out + f), points) << f;
    EXPECT_NE(file_text(out + f).find("Name=\"contact_pressure\""), std::string::npos) << f;
  }
  std::ifstream off(dir_->file("offline.json"));
  const int rows = json::parse(off).at("compression").at("constraints").get<int>();
  const auto m = file_lines(out + "/multipliers.csv");
  ASSERT_EQ(m.size(), static_cast<std::size_t>(rows + 1));
  EXPECT_EQ(m[0], "r,x,y,lambda");
  EXPECT_EQ(m[1].rfind("0,", 0), 0u) << m[1];

  EXPECT_EQ(j.at("files").at("contact_vtu"), out + "/contact.vtu");
  EXPECT_NE(file_text(out + "/solution.vtu").find("Name=\"von_mises\""), std::string::npos);
  EXPECT_NE(file_text(out + "/contact.vtu").find("Name=\"gap\""), std::string::npos);
}

TEST_F(CliEvaluate, OnlineBatchOutWritesOneDirectoryPerLineAndCollections) {
  const std::string out = dir_->file("batch_out");
  const std::string batch = dir_->file("batch_out.txt");
  {
    std::ofstream o(batch);
    o << "0.35\nabc\n0.2\n";
  }
  const CliResult r = run_cli("online --model " + shell_quote(model_) + " --batch " + shell_quote(batch) +
                              " --out " + shell_quote(out));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // line 2 is bad; the others are answered
  std::vector<json> lines;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) lines.push_back(json::parse(line));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].at("files").at("vtu"), out + "/000001/solution.vtu");
  EXPECT_EQ(lines[0].at("files").at("contact_vtu"), out + "/000001/contact.vtu");
  EXPECT_FALSE(lines[1].contains("files"));
  EXPECT_FALSE(fs::exists(out + "/000002"));
  EXPECT_EQ(lines[2].at("files").at("multipliers"), out + "/000003/multipliers.csv");

  // Line k's files are those of `online --mu` at the same value, byte for byte.
  const std::string single = dir_->file("batch_single");
  ASSERT_EQ(run_cli("online --model " + shell_quote(model_) + " --mu 0.2 --out " + shell_quote(single)).exit_code, 0);
  for (const char* f : {"/solution.vtu", "/solution_deformed.vtu", "/contact.vtu", "/multipliers.csv"}) {
    EXPECT_EQ(file_text(out + "/000003" + f), file_text(single + f)) << f;
  }

  // The collections: one data set per answered line, mu as the time step (p = 1, distinct).
  EXPECT_EQ(file_text(out + "/solutions.pvd"),
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0.35\" group=\"\" part=\"0\" file=\"000001/solution.vtu\"/>\n"
            "    <DataSet timestep=\"0.2\" group=\"\" part=\"0\" file=\"000003/solution.vtu\"/>\n"
            "  </Collection>\n"
            "</VTKFile>\n");
  EXPECT_NE(file_text(out + "/solutions_deformed.pvd").find("file=\"000003/solution_deformed.vtu\""),
            std::string::npos);
  EXPECT_NE(file_text(out + "/contact.pvd").find("file=\"000001/contact.vtu\""), std::string::npos);

  // A repeated value: the line numbers are the time steps (ParaView would merge equal steps).
  const std::string repeated = dir_->file("batch_repeated");
  {
    std::ofstream o(dir_->file("repeated.txt"));
    o << "0.3\n0.3\n";
  }
  const CliResult rr = run_cli("online --model " + shell_quote(model_) + " --batch - --out " +
                               shell_quote(repeated) + " < " + shell_quote(dir_->file("repeated.txt")));
  ASSERT_EQ(rr.exit_code, 0) << rr.out << rr.err;
  const std::string pvd = file_text(repeated + "/solutions.pvd");
  EXPECT_NE(pvd.find("timestep=\"1\" group=\"\" part=\"0\" file=\"000001/solution.vtu\""), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("timestep=\"2\" group=\"\" part=\"0\" file=\"000002/solution.vtu\""), std::string::npos) << pvd;

  // Output safety: the batch file cannot be an output of the run.
  expect_user_error(run_cli("online --model " + shell_quote(model_) + " --batch " +
                            shell_quote(out + "/solutions.pvd") + " --out " + shell_quote(out)),
                    "is the input --batch");
}
