// `contactrb evaluate`: errors and speed-ups of a reduced model against the HF solver over a
// parameter set (paper Section 6.2.3, (64)-(66); study/evaluation.hpp; docs/cli.md,
// "`contactrb evaluate`"). Writes DIR/evaluation.csv (one line per mu), DIR/evaluation.json (summary, sizes,
// model, set) and DIR/multipliers_mu<value>.csv for the --multipliers values, and prints a
// table in which every speed-up has the errors of the same solve beside it.
// Exit codes: 0 every solve converged; 1 a user error; 3 some HF or online solve did not
// converge (the outputs are still written).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "hf_solver_option.hpp"
#include "contactrb/cases/case_record.hpp"
#include "contactrb/cases/recorded_mesh.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/common/printable.hpp"
#include "contactrb/io/json_file.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/study/evaluation.hpp"
#include "contactrb/study/evaluation_json.hpp"

namespace contactrb::app {

namespace {

constexpr int kExitNotConverged = 3;

struct EvaluateOptions {
  std::string model;
  std::string set = "verification";
  std::string out;
  SizeFlags sizes;  // --n, --r, --mk, --mg
  int jobs = 1;
  int repeats = 5;
  std::string solver = "newton";
  int sequence = -1;  // --sequence (study::EvaluationOptions::sequence; -1: automatic)
  std::string iteration = "automatic";  // --iteration: the reduced iteration, as `online`'s
  std::vector<double> multipliers;
  bool quiet = false;
};

// A named set of the case, or else a file with one point per line (parse_mu_line; blank lines
// skipped).
std::vector<cases::Mu> parameter_values(const cases::CaseSpec& spec, const std::string& set) {
  if (spec.has_set(set)) return spec.set(set);
  std::string names;
  for (const cases::ParameterSet& s : spec.sets) names += (names.empty() ? "" : ", ") + s.name;
  std::error_code ec;
  require(std::filesystem::exists(set, ec),
          "--set '" + printable(set) + "' is neither a parameter set of case '" + spec.name + "' (" + names +
              ") nor a file of parameter values");
  // A regular file below the size limit (a device or FIFO would be read without end).
  std::istringstream in(read_text_input(set, "parameter file"));
  std::vector<cases::Mu> values;
  std::string line;
  int k = 0;
  while (std::getline(in, line)) {
    ++k;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      values.push_back(parse_mu_line(line, spec.parameters));
    } catch (const Error& e) {
      throw Error("parameter file '" + set + "', line " + std::to_string(k) + ": " + e.what());
    }
  }
  require(!values.empty(), "the parameter file '" + set + "' holds no value");
  return values;
}

// The file-name form of a parameter value: the shortest decimal that reads back (0.925).
std::string value_text(double mu) {
  for (int p = 6; p <= 17; ++p) {
    std::ostringstream os;
    os << std::setprecision(p) << mu;
    if (std::stod(os.str()) == mu) return os.str();
  }
  std::ostringstream os;
  os << std::setprecision(17) << mu;
  return os.str();
}

// ", grid sequencing from levels 0, 2" (empty: none).
std::string sequence_text(const std::vector<int>& levels) {
  std::string text;
  for (std::size_t k = 0; k < levels.size(); ++k) text += (k == 0 ? ", grid sequencing from levels " : ", ") + std::to_string(levels[k]);
  return text;
}

void print_table(const study::Evaluation& e) {
  if (e.parameter_names.size() > 1) {
    for (const std::string& name : e.parameter_names) std::cout << std::setw(std::max<int>(10, static_cast<int>(name.size()) + 1)) << name;
  } else {
    std::cout << std::setw(10) << "mu";
  }
  std::cout << std::setw(12) << "e_ener" << std::setw(12) << "e_displ" << std::setw(12)
            << "e_inter" << std::setw(12) << "e_press" << std::setw(12) << "e_force" << std::setw(10) << "HF ms"
            << std::setw(12) << "online us" << std::setw(10) << "speed-up" << std::setw(12) << "|e|_A" << std::setw(12)
            << "estimate" << std::setw(10) << "eff." << "\n";
  for (const study::EvaluationRow& r : e.rows) {
    for (Eigen::Index k = 0; k < r.mu.size(); ++k) {
      const int width = e.parameter_names.size() > 1
                            ? std::max<int>(10, static_cast<int>(e.parameter_names[static_cast<std::size_t>(k)].size()) + 1)
                            : 10;
      std::cout << std::setw(width) << std::setprecision(6) << r.mu(k);
    }
    std::cout << std::scientific << std::setprecision(3)
              << std::setw(12) << r.e_ener << std::setw(12) << r.e_displ << std::setw(12) << r.e_inter << std::setw(12)
              << r.e_press << std::setw(12) << r.e_force << std::fixed
              << std::setprecision(1) << std::setw(10) << r.hf_time_s * 1e3 << std::setw(12) << r.online_time_s * 1e6
              << std::setprecision(0) << std::setw(10) << r.speedup << std::scientific << std::setprecision(3)
              << std::setw(12) << r.e_energy_norm << std::setw(12) << r.estimate << std::defaultfloat << std::setprecision(3)
              << std::setw(10) << r.effectivity;
    if (!r.hf_converged) std::cout << "  HF " << r.hf_status;
    if (!r.rb_converged) std::cout << "  online " << r.rb_status;
    std::cout << "\n";
  }
  const study::EvaluationSummary& s = e.summary;
  std::cout << std::setprecision(3) << std::scientific << "summary over " << s.count << " values"
            << (s.hf_failures + s.rb_failures > 0 ? " (errors and times over the rows where both solves converged)"
                                                  : "")
            << ":\n"
            << "  e_ener  max " << s.max_e_ener << ", mean " << s.mean_e_ener << "\n"
            << "  e_displ max " << s.max_e_displ << ", mean " << s.mean_e_displ << "\n"
            << "  e_inter max " << s.max_e_inter << ", mean " << s.mean_e_inter << "\n"
            << "  e_press max " << s.max_e_press << ", mean " << s.mean_e_press << " (contact pressure, relative L2)\n"
            << "  e_force max " << s.max_e_force << ", mean " << s.mean_e_force << " (total contact force, relative)\n"
            << "  e_peak  max " << s.max_e_peak << ", mean " << s.mean_e_peak << " (peak pressure, relative)\n"
            << "  best pressure in the model's cone: max " << s.max_e_press_cone << " (e_press cannot go below it)\n"
            << "  estimate / |u_rb - u_hf|_A effectivity over " << s.effectivity_count << " values: min "
            << s.min_effectivity << ", median " << s.median_effectivity << ", max " << s.max_effectivity << "\n"
            << std::fixed << std::setprecision(1) << "  median HF (" << e.hf_solver << ") " << s.median_hf_time_s * 1e3
            << " ms, online " << s.median_online_time_s * 1e6 << " us, speed-up against " << e.hf_solver << " "
            << std::setprecision(0) << s.median_speedup
            << std::defaultfloat << std::setprecision(6) << "\n";
}

int run_evaluate(const EvaluateOptions& opt) {
  const online::OnlineSizes sizes = checked_size_flags(opt.sizes);
  require(opt.jobs >= 1, "--jobs must be >= 1 (got " + std::to_string(opt.jobs) + ")");
  require(opt.repeats >= 1, "--repeats must be >= 1 (got " + std::to_string(opt.repeats) + ")");
  check_sequence_option(opt.sequence);
  const contactrb::model::ReducedModel model = io::read_reduced_model_file(opt.model);
  check_sizes_against(sizes, model, opt.model);
  const online::OnlineIteration iteration = checked_iteration_flag(opt.iteration, model);
  const contactrb::model::ReducedReconstruction rec = io::read_reconstruction(opt.model);
  // The mesh stored in the model file (format 5) is used: the case's .msh file may be gone.
  const cases::CaseSpec spec = cases::case_from_record(
      model.case_kind, model.case_spec, opt.model,
      rec.mesh.nodes.empty() ? cases::MeshFile::Required : cases::MeshFile::Optional);
  cases::recorded_reference_mesh(spec, {model.level, rec.num_dofs, &rec.mesh}, opt.model);
  const std::vector<cases::Mu> mus = parameter_values(spec, opt.set);
  {
    const std::filesystem::path d(opt.out);
    check_file_roles({{"--model", opt.model}, {"--set", spec.has_set(opt.set) ? std::string() : opt.set}},
                     {{"evaluation.csv in --out", (d / "evaluation.csv").string()},
                      {"evaluation.json in --out", (d / "evaluation.json").string()}});
  }
  ensure_output_directory(opt.out);

  study::EvaluationOptions options;
  options.sizes = sizes;
  options.online.iteration = iteration;
  options.online_repeats = opt.repeats;
  options.jobs = opt.jobs;
  options.hf_method = hf::hf_method_from_string(opt.solver);
  options.sequence = opt.sequence;
  options.progress = opt.quiet ? offline::ProgressMode::None : offline::ProgressMode::Automatic;
  require(opt.multipliers.empty() || spec.num_parameters() == 1,
          "--multipliers is for one-parameter models (this one has " + std::to_string(spec.num_parameters()) + ")");
  options.multiplier_mus = cases::points_1d(opt.multipliers);
  const study::Evaluation e = study::evaluate_model(model, rec, spec, mus, options);

  const std::filesystem::path dir(opt.out);
  const OutputLock lock(dir);  // one run's files, never mixed with another's
  const std::string csv_path = (dir / "evaluation.csv").string();
  const std::string json_path = (dir / "evaluation.json").string();
  study::write_evaluation_csv(e, csv_path);
  std::vector<std::string> written{csv_path, json_path};
  nlohmann::json multiplier_files = nlohmann::json::array();
  for (const study::EvaluationRow& r : e.rows) {
    if (r.multipliers.abscissa.empty()) continue;
    const std::string path = (dir / ("multipliers_mu" + value_text(r.mu(0)) + ".csv")).string();
    study::write_multiplier_csv(r.multipliers, path);
    multiplier_files.push_back({{"mu", r.mu(0)}, {"file", path}});
    written.push_back(path);
  }
  nlohmann::json j = study::evaluation_json(e, model, mus, options);
  j["model"] = opt.model;
  j["set"] = opt.set;
  j["multipliers"] = multiplier_files;
  io::write_json(j, json_path);

  std::cout << "case " << model.case_name << ", set " << opt.set << " (" << mus.size() << " values), sizes N "
            << e.N << ", R " << e.R << ", Mk " << e.Mk << ", Mg " << e.Mg << ", HF reference " << e.hf_solver
            << sequence_text(e.hf_sequence) << " (speed-ups against it)\n";
  print_table(e);
  for (const std::string& p : written) std::cout << "wrote " << p << "\n";
  if (e.summary.hf_failures + e.summary.rb_failures > 0) {
    std::cerr << "contactrb: error: " << e.summary.hf_failures << " HF and " << e.summary.rb_failures << " online of "
              << e.summary.count << " solves did not converge (see " << csv_path << ")\n";
    return kExitNotConverged;
  }
  return 0;
}

}  // namespace

Command add_evaluate_command(CLI::App& app) {
  auto opt = std::make_shared<EvaluateOptions>();
  CLI::App* sub = app.add_subcommand(
      "evaluate", "Errors (64)-(66) and speed-ups of a reduced model against HF solves over a parameter set");
  sub->add_option("--model", opt->model, "Reduced model file written by `contactrb offline`")->required();
  sub->add_option("--set", opt->set, "training | verification (the case's sets) | FILE (one value per line)")
      ->capture_default_str();
  sub->add_option("--out", opt->out, "Output directory (evaluation.csv, evaluation.json, multipliers_mu*.csv)")
      ->required();
  sub->add_option("--n", opt->sizes.n, "Primal size N (default: the model's N_max)");
  sub->add_option("--r", opt->sizes.r, "Dual size R (default: R_max)");
  sub->add_option("--mk", opt->sizes.mk, "EIM size of kappa (default: Mk_max)");
  sub->add_option("--mg", opt->sizes.mg, "EIM size of gamma (default: Mg_max)");
  sub->add_option("--jobs,-j", opt->jobs, "Worker threads for the HF solves")->capture_default_str();
  sub->add_option("--solver", opt->solver, "HF reference solver: newton (KKT residual 1e-10) | kacanov (the snapshots' eps_KA)")
      ->capture_default_str();
  add_sequence_option(sub, opt->sequence, "", " of the HF reference solves (timed with them)");
  sub->add_option("--repeats", opt->repeats, "Online solves per value (the time is their median)")
      ->capture_default_str();
  sub->add_option("--iteration", opt->iteration,
                  "Reduced iteration: automatic | relaxed (the paper's) | accelerated | newton (row-cone models: "
                  "the exact contact rows)")
      ->capture_default_str();
  sub->add_option("--multipliers", opt->multipliers,
                  "Values of the set whose HF and RB multipliers are written (comma-separated)")
      ->delimiter(',');
  sub->add_flag("--quiet,-q", opt->quiet, "No progress report on stderr");
  return {sub, [opt] { return run_evaluate(*opt); }};
}

}  // namespace contactrb::app
