// `contactrb report`: the paper's Section 6 study of one case in one command
// (docs/cli.md, "`contactrb report`"): training snapshots, offline stages with CPG, angle-greedy,
// NMF and truncated NMF, evaluation on the training and verification sets (study/study.hpp);
// writes the CSV data and study.json, plots the figures with scripts/plot_report.py and
// writes report.md (tables and links to the figures).
//
// The plotting script and its interpreter: plot_script.hpp (as `sample`'s).
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "hf_solver_option.hpp"
#include "plot_script.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/io/atomic_file.hpp"
#include "contactrb/study/study.hpp"

namespace contactrb::app {

namespace {

namespace fs = std::filesystem;

struct ReportOptions {
  std::string case_name;
  std::string case_file;
  int level = 0;
  std::string constraint;
  std::string out;
  int jobs = 1;
  bool quiet = false;
  bool no_plots = false;
  int max_training = -1;
  int max_verification = -1;
  std::vector<std::string> training_values;  // parse_values_option
  std::vector<std::string> verification_values;
  std::optional<double> eps_pod, eps_du, eps_eim_k, eps_eim_g;
  std::optional<std::string> solver;  // --solver (nullopt: offline::default_snapshot_method)
  int sequence = -1;                  // --sequence (study::StudySettings::sequence; -1: automatic)
  int history_r = study::StudySettings{}.history_max_R;
  int profiles = study::StudySettings{}.multiplier_profiles;
  int deformed = study::StudySettings{}.deformed_configurations;
  int comparisons = study::StudySettings{}.constraint_comparisons;
  int repeats = study::StudySettings{}.online_repeats;
};

void write_text(const std::string& path, const std::string& text) {
  io::write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

std::string g3(double v) {
  std::ostringstream os;
  os << std::setprecision(3) << v;
  return os.str();
}

// Every figure the plotting script can write (PNG, and a PDF of the same stem).
const std::vector<std::string>& all_figures() {
  static const std::vector<std::string> names{"pod_singular_values.png", "dual_cone_error.png", "eim_error.png",
                                              "errors_training.png",     "errors_verification.png",
                                              "multipliers.png",         "deformed_configuration.png",
                                              "constraint_comparison.png"};
  return names;
}

std::string pdf_of(const std::string& png) { return png.substr(0, png.size() - 4) + ".pdf"; }

// Runs scripts/plot_report.py on the staging directory and returns the figures it must have
// written there (each as PNG and PDF); throws contactrb::Error when one is missing.
std::vector<std::string> plot_figures(const std::string& script, const fs::path& staging, const study::StudyResult& r,
                                      const std::string& out, bool quiet) {
  run_python_script(script, {staging.string()},
                    "use --no-plots to skip the figures; the CSV files and report.md (without figures) are in " + out,
                    quiet);
  std::vector<std::string> figures{"pod_singular_values.png", "dual_cone_error.png", "eim_error.png",
                                   "errors_training.png"};
  if (!r.verification_mus.empty()) figures.push_back("errors_verification.png");
  figures.push_back("multipliers.png");
  if (!r.configurations.empty()) figures.push_back("deformed_configuration.png");
  if (!r.comparisons.empty()) figures.push_back("constraint_comparison.png");
  for (const std::string& f : figures) {
    require(fs::is_regular_file(staging / f), "the plotting script did not write " + f);
    require(fs::is_regular_file(staging / pdf_of(f)), "the plotting script did not write " + pdf_of(f));
  }
  return figures;
}

// Renames the staged `files` and `figures` (PNG and PDF) into `out` together (OutputSet), then
// removes the figures of an earlier run that this one did not draw.
void commit_report(const fs::path& staging, const std::string& out, const std::vector<std::string>& files,
                   const std::vector<std::string>& figures) {
  OutputSet outputs;
  for (const std::string& f : files) outputs.add(staging / f, fs::path(out) / f);
  for (const std::string& f : figures) {
    outputs.add(staging / f, fs::path(out) / f);
    outputs.add(staging / pdf_of(f), fs::path(out) / pdf_of(f));
  }
  outputs.commit();
  for (const std::string& f : all_figures()) {
    if (std::find(figures.begin(), figures.end(), f) != figures.end()) continue;
    std::error_code ignored;
    fs::remove(fs::path(out) / f, ignored);
    fs::remove(fs::path(out) / pdf_of(f), ignored);
  }
}

int run_report(const ReportOptions& opt) {
  const cases::CaseSpec spec =
      read_case_2d(opt.case_name, opt.case_file, "report");
  study::StudySettings s;
  s.level = opt.level;
  if (!opt.constraint.empty()) s.constraint = contact::discretization_from_string(opt.constraint);
  s.snapshot_method = snapshot_solver_option(opt.solver);
  check_sequence_option(opt.sequence);
  s.sequence = opt.sequence;
  // A case file gets `contactrb offline`'s defaults whatever its name (a user case named like a
  // built-in one is not that case).
  s.tolerances = opt.case_file.empty() ? study::default_study_tolerances(spec.name) : study::StudyTolerances{};
  if (opt.eps_pod) s.tolerances.eps_pod = *opt.eps_pod;
  if (opt.eps_du) s.tolerances.eps_du = *opt.eps_du;
  if (opt.eps_eim_k) s.tolerances.eps_eim_k = *opt.eps_eim_k;
  if (opt.eps_eim_g) s.tolerances.eps_eim_g = *opt.eps_eim_g;
  s.max_training = opt.max_training;
  s.max_verification = opt.max_verification;
  if (!opt.training_values.empty()) s.training_values = parse_values_option(opt.training_values, "--training-values");
  if (!opt.verification_values.empty()) {
    s.verification_values = parse_values_option(opt.verification_values, "--verification-values");
  }
  s.history_max_R = opt.history_r;
  s.multiplier_profiles = opt.profiles;
  s.deformed_configurations = opt.deformed;
  s.constraint_comparisons = opt.comparisons;
  s.online_repeats = opt.repeats;
  s.jobs = opt.jobs;
  s.progress = opt.quiet ? offline::ProgressMode::None : offline::ProgressMode::Automatic;
  study::check_settings(s);
  const std::string out = opt.out.empty() ? "out/report-" + spec.name : opt.out;
  check_file_roles({{"--case-file", opt.case_file}, {"the case's mesh file", spec.mesh.msh_file}},
                   {{"report.md in --out", (fs::path(out) / "report.md").string()},
                    {"study.json in --out", (fs::path(out) / "study.json").string()}});
  ensure_output_directory(out);
  require(::access(out.c_str(), W_OK) == 0, "output directory '" + out + "' is not writable");
  // Find the plotter before the long work, so that a broken installation fails at once.
  std::string script;
  if (!opt.no_plots) script = find_script("plot_report.py", "use --no-plots");

  const study::StudyResult r = study::run_study(spec, s);
  // Held to the end (figures included): one run's files, never mixed with another's. Every file
  // is written in a staging directory inside `out`, the plotting script included, and renamed
  // into `out` at the end (common/output_file.hpp, OutputSet).
  const OutputLock lock(out);
  const StagingDirectory staging(fs::path(out) / "report");
  std::vector<std::string> files = study::write_study_files(r, staging.path().string());
  write_text((staging.path() / "report.md").string(), study::study_markdown(r, {}));  // without figures
  files.push_back("report.md");

  std::vector<std::string> figures;
  if (!opt.no_plots) {
    try {
      figures = plot_figures(script, staging.path(), r, out, opt.quiet);
    } catch (const Error&) {
      // The tables are kept (the message says where); no figure of this run is written, and
      // those of an earlier run would be taken for this run's.
      commit_report(staging.path(), out, files, {});
      throw;
    }
    write_text((staging.path() / "report.md").string(), study::study_markdown(r, figures));
  }
  commit_report(staging.path(), out, files, figures);

  std::cout << "case " << r.case_name << ": " << r.training_mus.size() << " training values, "
            << r.verification_mus.size() << " verification values, " << r.constraint << "\n"
            << "| method | N | R | Mk | Mg | max e_displ (train) | max e_inter (train) | max e_displ (verif) | "
               "median speed-up against "
            << (r.models.empty() ? std::string("HF") : r.models.front().training.hf_solver) << " |\n";
  for (const study::StudyModel& m : r.models) {
    const study::EvaluationSummary& t = m.training.summary;
    std::cout << "| " << m.label << " | " << m.N << " | " << m.R << " | " << m.Mk << " | " << m.Mg << " | "
              << g3(t.max_e_displ) << " | " << g3(t.max_e_inter) << " | "
              << (m.verification ? g3(m.verification->summary.max_e_displ) : std::string("-")) << " | "
              << g3(t.median_speedup) << " |\n";
  }
  for (const std::string& f : files) {
    std::cout << "wrote " << (fs::path(out) / f).string() << (f == "report.md" && opt.no_plots ? " (no figures: --no-plots)" : "") << "\n";
  }
  for (const std::string& w : study::study_warnings(r)) std::cerr << "contactrb: warning: " << w << "\n";
  return 0;
}

}  // namespace

Command add_report_command(CLI::App& app) {
  auto opt = std::make_shared<ReportOptions>();
  CLI::App* sub = app.add_subcommand(
      "report", "The paper's Section 6 study of one case: CPG / angle-greedy / NMF models and the row cone, errors, "
                "speed-ups, figures (PNG via scripts/plot_report.py) and report.md");
  CLI::Option_group* input = sub->add_option_group("case", "Case (exactly one)");
  input->add_option("--case", opt->case_name, "Built-in case (see `contactrb cases`)");
  input->add_option("--case-file", opt->case_file, "TOML case file (docs/cases.md)");
  input->require_option(1);
  sub->add_option("--level", opt->level, "Mesh refinement level (0: the paper's mesh)")->capture_default_str();
  sub->add_option("--constraint", opt->constraint, "collocation | lac | lac-simpson (default: the case's)");
  sub->add_option("--out", opt->out, "Output directory (default: out/report-<case>)");
  sub->add_option("--jobs,-j", opt->jobs, "Worker threads for the HF solves")->capture_default_str();
  add_snapshot_solver_option(sub, opt->solver);
  add_sequence_option(sub, opt->sequence, "", " of the training snapshots' cold solves and of the HF reference solves");
  sub->add_flag("--quiet,-q", opt->quiet, "No progress report on stderr, no plotting messages");
  sub->add_flag("--no-plots", opt->no_plots, "Write the CSV files and report.md only (no Python needed)");
  sub->add_option("--max-training", opt->max_training,
                  "Use at most this many training values, evenly spaced (>= 2; default: the whole set)");
  sub->add_option("--max-verification", opt->max_verification,
                  "Use at most this many verification values, evenly spaced (0: none; default: the whole set)");
  sub->add_option("--training-values", opt->training_values, "Explicit training values (comma-separated)")
      ->delimiter(',');
  sub->add_option("--verification-values", opt->verification_values,
                  "Explicit verification values (comma-separated)")
      ->delimiter(',');
  sub->add_option("--eps-pod", opt->eps_pod, "POD tolerance (default: the case's, docs/cli.md)");
  sub->add_option("--eps-du", opt->eps_du, "Dual cone tolerance eps_DU (default: the case's)");
  sub->add_option("--eps-eim-k", opt->eps_eim_k, "EIM tolerance of kappa (default: the case's)");
  sub->add_option("--eps-eim-g", opt->eps_eim_g, "EIM tolerance of gamma (default: the case's)");
  sub->add_option("--history-r", opt->history_r, "Dual cone histories up to this R (capped at P and the rows)")
      ->capture_default_str();
  sub->add_option("--profiles", opt->profiles, "Multiplier profiles for this many mu (0: none)")
      ->capture_default_str();
  sub->add_option("--deformed", opt->deformed,
                  "Deformed configurations (HF) at this many training values, evenly spaced (0: none)")
      ->capture_default_str();
  sub->add_option("--comparisons", opt->comparisons,
                  "LAC against collocation (HF pressures) at this many training values (0: none)")
      ->capture_default_str();
  sub->add_option("--repeats", opt->repeats, "Online solves per mu (the time is their median)")
      ->capture_default_str();
  return {sub, [opt] { return run_report(*opt); }};
}

}  // namespace contactrb::app
