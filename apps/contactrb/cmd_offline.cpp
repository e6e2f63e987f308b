// `contactrb offline`: the offline stage from a snapshot file (docs/cli.md, "`contactrb offline`"):
// POD, compression, dual cone, EIM of kappa and gamma, the reduced arrays. Writes the reduced
// model (HDF5, io/reduced_model_file.hpp) and, in the same directory, offline.json (the
// histories of each step and their times). With --case/--case-file instead of --snapshots,
// the training snapshots are computed first (as `contactrb snapshots` would) and kept next to
// the model as snapshots.h5. With --greedy (and --case/--case-file), the weak greedy on the error
// estimate (offline/offline_greedy.hpp) solves HF only at the points it selects; it writes the model,
// the selected snapshots (snapshots.h5), greedy.csv and greedy.json next to the model.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "hf_solver_option.hpp"
#include "mpi_greedy.hpp"
#include "mpi_world.hpp"
#include "contactrb/cases/case_record.hpp"
#include "contactrb/cases/recorded_mesh.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/io/json_file.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/common/number_text.hpp"
#include "contactrb/offline/offline_greedy.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/offline/offline_greedy_json.hpp"
#include "contactrb/offline/offline_report_json.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "contactrb/offline/snapshot_parts.hpp"

namespace contactrb::app {

namespace {

// Exit code when some snapshot solve failed (as `contactrb snapshots`).
constexpr int kExitSolveFailed = 3;

struct OfflineOptions {
  std::string snapshots;
  // Snapshots computed here (--case / --case-file).
  std::string case_name;
  std::string case_file;
  std::string set_name = "training";
  std::vector<std::string> values;  // parse_values_option
  int level = 0;
  std::string constraint;
  int jobs = 1;
  double alpha = solve::KacanovSettings{}.alpha;
  double tolerance = solve::KacanovSettings{}.tolerance;
  int max_iterations = solve::KacanovSettings{}.max_iterations;
  std::optional<std::string> solver;  // --solver (nullopt: offline::default_snapshot_method)
  int sequence = -1;                  // --sequence (offline::set_snapshot_sequence; -1: automatic)
  bool quiet = false;
  double eps_pod = offline::OfflineSettings{}.eps_pod;
  std::optional<int> n;  // absent: --eps-pod decides
  std::string inner_product = "energy";
  std::string dual = to_string(offline::OfflineSettings{}.dual_method);
  double eps_du = offline::OfflineSettings{}.eps_du;
  bool eps_du_relative = false;  // the default anyway; kept for scripts that pass it
  std::optional<int> r;  // absent: --eps-du decides
  double eps_eim_k = offline::OfflineSettings{}.eps_eim_k;
  double eps_eim_g = offline::OfflineSettings{}.eps_eim_g;
  // Tolerances are relative by default; these make all of them, or one, absolute.
  bool absolute_tolerances = false;
  bool eps_pod_absolute = false;
  bool eps_du_absolute = false;
  bool eps_eim_k_absolute = false;
  bool eps_eim_g_absolute = false;
  bool no_compression = false;
  bool no_supremizers = false;
  // --greedy (offline::run_offline_greedy): tolerance on the max relative estimate, HF budget.
  bool greedy = false;
  double greedy_tol = offline::GreedyOfflineSettings{}.tolerance;
  int max_hf = offline::GreedyOfflineSettings{}.max_hf;
  int greedy_batch = offline::GreedyOfflineSettings{}.batch;
  double greedy_saturation = offline::GreedyOfflineSettings{}.saturation;
  bool greedy_rebuild = false;
  int greedy_preconditioner_points = offline::GreedyOfflineSettings{}.preconditioner_points;
  std::string out;
};

std::string sibling_path(const std::string& model_path, const char* name) {
  const std::filesystem::path dir = std::filesystem::path(model_path).parent_path();
  return (dir / name).string();
}

// The HF solves the options ask for: the case's set (or --values), level, constraint and the
// Kacanov settings, the HF method and the grid sequencing (both the POD path and the greedy).
offline::SnapshotRequest snapshot_request(const OfflineOptions& opt, const cases::CaseSpec& spec) {
  check_sequence_option(opt.sequence);
  std::optional<contact::Discretization> constraint;
  if (!opt.constraint.empty()) constraint = contact::discretization_from_string(opt.constraint);
  const std::optional<std::vector<cases::Mu>> values = parse_values_points(opt.values, "--values", spec.parameters);
  offline::SnapshotRequest request = offline::make_snapshot_request(spec, opt.set_name, opt.level, constraint, values);
  request.settings.kacanov.alpha = opt.alpha;
  request.settings.kacanov.tolerance = opt.tolerance;
  request.settings.kacanov.max_iterations = opt.max_iterations;
  solve::check_settings(request.settings.kacanov);
  request.settings.method = snapshot_solver_option(opt.solver).value_or(request.settings.method);
  offline::set_snapshot_sequence(request, opt.sequence);
  return request;
}

// --case/--case-file: the HF snapshots of the set, written to snapshots.h5 next to the model.
// `lock` is taken before the file is written and kept by the caller until the model and
// offline.json are written too (one run's three files, never mixed with another run's).
io::SnapshotSet compute_snapshots(const OfflineOptions& opt, const std::string& path, std::optional<OutputLock>& lock) {
  const cases::CaseSpec spec =
      read_case_2d(opt.case_name, opt.case_file, "offline");
  require(opt.jobs >= 1, "--jobs must be >= 1 (got " + std::to_string(opt.jobs) + ")");
  require(opt.level >= 0, "--level must be >= 0 (got " + std::to_string(opt.level) + ")");
  const offline::SnapshotRequest request = snapshot_request(opt, spec);
  offline::SnapshotRunOptions run;
  run.jobs = opt.jobs;
  run.progress = opt.quiet ? offline::ProgressMode::None : offline::ProgressMode::Automatic;
  io::SnapshotSet set = offline::generate_snapshots(request, run);
  if (!lock) lock.emplace(std::filesystem::path(path).parent_path());
  io::write_snapshot_file(set, path);
  return set;
}

// The failed solves of a set, one per line after a summary line.
std::string failure_report(const io::SnapshotSet& set, const std::string& path) {
  std::ostringstream os;
  os << set.num_failed() << " of " << set.snapshots.size() << " snapshot solves failed (recorded in " << path
     << "); no model written:";
  for (const io::Snapshot& snap : set.snapshots) {
    if (!snap.converged) os << "\n  mu = " << cases::mu_values_text(snap.mu) << ": " << snap.status << ": " << snap.message;
  }
  return os.str();
}

offline::OfflineSettings settings_from(const OfflineOptions& opt) {
  offline::OfflineSettings s;
  s.eps_pod = opt.eps_pod;
  s.pod_modes = opt.n.value_or(-1);
  s.inner_product = option_enum("--inner-product", opt.inner_product, offline::inner_product_from_string);
  s.dual_method = option_enum("--dual", opt.dual, offline::dual_cone_method_from_string);
  // Every value given is checked: -1 must not pass as "no fixed size" where -3 is refused.
  require(!opt.n || *opt.n >= 1, "--n must be >= 1 (got " + std::to_string(opt.n.value_or(0)) + ")");
  require(!opt.r || *opt.r >= 1, "--r must be >= 1 (got " + std::to_string(opt.r.value_or(0)) + ")");
  require(opt.eps_pod >= 0.0, "--eps-pod must be >= 0");
  require(opt.eps_du >= 0.0, "--eps-du must be >= 0");
  require(opt.eps_eim_k >= 0.0, "--eps-eim-k must be >= 0");
  require(opt.eps_eim_g >= 0.0, "--eps-eim-g must be >= 0");
  s.eps_du = opt.eps_du;
  require(!(opt.eps_du_relative && (opt.eps_du_absolute || opt.absolute_tolerances)),
          "--eps-du-relative contradicts --eps-du-absolute / --absolute-tolerances");
  s.eps_pod_relative = !(opt.absolute_tolerances || opt.eps_pod_absolute);
  s.eps_du_relative = !(opt.absolute_tolerances || opt.eps_du_absolute);
  s.eps_eim_k_relative = !(opt.absolute_tolerances || opt.eps_eim_k_absolute);
  s.eps_eim_g_relative = !(opt.absolute_tolerances || opt.eps_eim_g_absolute);
  s.dual_size = opt.r.value_or(-1);
  s.eps_eim_k = opt.eps_eim_k;
  s.eps_eim_g = opt.eps_eim_g;
  s.compression = !opt.no_compression;
  s.supremizers = !opt.no_supremizers;
  offline::check_settings(s);
  return s;
}

// The case the set records, checked against the set's mesh (cases/recorded_mesh.hpp).
cases::CaseSpec spec_of(const io::SnapshotSet& set, const std::string& path) {
  // A set that stores its mesh needs no .msh file (it may have been moved since).
  cases::CaseSpec spec = cases::case_from_record(set.case_kind, set.case_spec, path,
                                                 set.mesh.nodes.empty() ? cases::MeshFile::Required : cases::MeshFile::Optional);
  cases::recorded_reference_mesh(spec, {set.level, set.num_dofs, &set.mesh}, path);
  return spec;
}

// --greedy: the weak greedy over the set's points (or --values), then the same model file as
// the POD path; the per-step table goes to greedy.csv and greedy.json, the selected HF snapshots to
// snapshots.h5 (so that evaluate / report can rebuild or compare).
// Under mpirun (mpi_greedy.hpp): every rank does the setup and the greedy, rank 0 alone prints
// and writes the files.
int run_greedy(const OfflineOptions& opt) {
  const std::unique_ptr<MpiWorld> world = MpiWorld::start_if_launched();
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
  require(!opt.case_name.empty() || !opt.case_file.empty(), "--greedy needs --case or --case-file (it computes its own snapshots)");
  require(std::isfinite(opt.greedy_tol) && opt.greedy_tol > 0.0, "--greedy-tol must be a finite number > 0");
  require(opt.max_hf >= 1, "--max-hf must be >= 1 (got " + std::to_string(opt.max_hf) + ")");
  require(opt.greedy_batch >= 1, "--greedy-batch must be >= 1 (got " + std::to_string(opt.greedy_batch) + ")");
  require(opt.greedy_preconditioner_points >= 0, "--greedy-preconditioner-points must be >= 0 (got " +
                                                    std::to_string(opt.greedy_preconditioner_points) + ")");
  require(opt.greedy_saturation >= 1.0, "--greedy-saturation must be >= 1, or inf (got " +
                                            number_text(opt.greedy_saturation) + ")");
  require(opt.jobs >= 1, "--jobs must be >= 1 (got " + std::to_string(opt.jobs) + ")");
  require(opt.level >= 0, "--level must be >= 0 (got " + std::to_string(opt.level) + ")");
  offline::GreedyOfflineSettings gs;
  gs.offline = settings_from(opt);
  // Compression as in `offline` (on unless --no-compression): docs/offline-online.md, "Greedy
  // sampling", gives the measured trade-off.
  gs.tolerance = opt.greedy_tol;
  gs.max_hf = opt.max_hf;
  gs.batch = opt.greedy_batch;
  gs.saturation = opt.greedy_saturation;
  gs.incremental = !opt.greedy_rebuild;
  gs.preconditioner_points = opt.greedy_preconditioner_points;
  gs.jobs = opt.jobs;
  gs.progress = opt.quiet ? offline::ProgressMode::None : offline::ProgressMode::Automatic;
  offline::check_settings(gs);
  check_output_file(opt.out);
  const std::string snapshots_path = sibling_path(opt.out, "snapshots.h5");
  const std::string csv_path = sibling_path(opt.out, "greedy.csv");
  const std::string json_path = sibling_path(opt.out, "greedy.json");
  const cases::CaseSpec spec =
      read_case_2d(opt.case_name, opt.case_file, "offline");
  std::vector<FileRole> inputs{{"--case-file", opt.case_file}};
  if (!opt.case_file.empty()) inputs.push_back({"the case's mesh file", spec.mesh.msh_file});
  check_file_roles(inputs, {{"--out", opt.out},
                            {"snapshots.h5 next to --out", snapshots_path},
                            {"greedy.csv next to --out", csv_path},
                            {"greedy.json next to --out", json_path}});
  const offline::SnapshotRequest request = snapshot_request(opt, spec);
  if (world) {
    if (world->rank() != 0) gs.progress = offline::ProgressMode::None;
    gs.distribution = mpi_greedy_distribution(*world);
    if (!world->agree(true)) {
      if (world->rank() == 0) throw Error("an MPI rank could not start the run (its error is above)");
      return 1;
    }
  }

  const auto t0 = Clock::now();
  const offline::GreedyOfflineResult g = offline::run_offline_greedy(spec, request, gs);
  const auto t1 = Clock::now();
  if (world && world->rank() != 0) return 0;  // rank 0 holds the same result and writes it
  {
    // The four files appear together or not at all (common/output_file.hpp, OutputSet).
    const OutputLock lock(std::filesystem::path(opt.out).parent_path());
    OutputSet outputs;
    io::write_snapshot_file(g.snapshots, snapshots_path);
    io::write_reduced_model_file(g.offline.model, g.offline.reconstruction, opt.out);
    offline::write_greedy_csv(g, csv_path);
    nlohmann::json j = offline::greedy_json(g, request, gs);
    j["times_s"]["total"] = seconds(t0, Clock::now());
    io::write_json(j, json_path);
    outputs.commit();
  }
  const offline::GreedyStep& last = g.steps[static_cast<std::size_t>(g.model_step - 1)];  // the model written
  std::cout << "case " << spec.name << ", greedy over " << request.mu.size() << " points (set " << request.set_name
            << "), tolerance " << gs.tolerance << ", budget " << gs.max_hf << " HF solves\n"
            << "status: " << to_string(g.status) << " after " << g.steps.size() << " steps, " << g.hf_solves
            << " HF solves" << (g.excluded.empty() ? "" : " (" + std::to_string(g.excluded.size()) + " failed)")
            << "\nmodel: step " << last.step << " of " << g.steps.size() << " (" << last.snapshots << " of "
            << g.snapshots.snapshots.size() << " snapshots, the best model built)\nmax relative estimate: " << last.max_estimate
            << (last.online_failures > 0 ? ", " + std::to_string(last.online_failures) + " online failures" : "")
            << (g.status == offline::GreedyOfflineStatus::ToleranceReached ? "" : " (tolerance NOT reached)") << "\n"
            << "sizes: N " << last.N << ", R " << last.R << ", Mk " << last.Mk << ", Mg " << last.Mg << "\n"
            << std::fixed << std::setprecision(3) << "time: " << seconds(t0, Clock::now()) << " s (greedy "
            << seconds(t0, t1) << (world ? ", " + std::to_string(world->size()) + " MPI ranks" : std::string()) << ")\n"
            << std::defaultfloat << "wrote " << opt.out << "\nwrote " << snapshots_path << "\nwrote " << csv_path
            << "\nwrote " << json_path << "\n";
  return 0;
}

int run_offline(const OfflineOptions& opt) {
  if (opt.greedy) return run_greedy(opt);
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
  const offline::OfflineSettings settings = settings_from(opt);
  check_output_file(opt.out);
  const std::string json_path = sibling_path(opt.out, "offline.json");
  const bool compute = opt.snapshots.empty();
  const std::string snapshots_path = compute ? sibling_path(opt.out, "snapshots.h5") : opt.snapshots;

  const auto t0 = Clock::now();
  std::vector<FileRole> inputs{{"--snapshots", opt.snapshots}, {"--case-file", opt.case_file}};
  if (!opt.case_file.empty()) {
    inputs.push_back({"the case's mesh file", cases::case_from_toml_file(opt.case_file).mesh.msh_file});
  }
  std::vector<FileRole> outputs{{"--out", opt.out}, {"offline.json next to --out", json_path}};
  if (compute) outputs.push_back({"snapshots.h5 next to --out", snapshots_path});
  check_file_roles(inputs, outputs);
  std::optional<OutputLock> lock;

  const io::SnapshotSet set =
      compute ? compute_snapshots(opt, snapshots_path, lock) : io::read_snapshot_file(snapshots_path);
  require_2d_snapshots(set, snapshots_path, "offline");
  offline::refuse_snapshot_part(set, snapshots_path);
  if (set.num_failed() > 0) {
    std::cerr << "contactrb: error: " << failure_report(set, snapshots_path) << "\n";
    return kExitSolveFailed;
  }
  const auto t1 = Clock::now();
  // The model and offline.json appear together or not at all (OutputSet). The snapshots
  // computed here are already in their own complete, sealed file: a failure from here on keeps
  // them and says so (docs/cli.md, "`contactrb offline`").
  offline::OfflineResult result;
  Clock::time_point t2, t3;
  try {
    const cases::CaseSpec spec = spec_of(set, snapshots_path);
    result = offline::build_reduced_model(set, spec, settings);
    t2 = Clock::now();
    if (!lock) lock.emplace(std::filesystem::path(opt.out).parent_path());
    OutputSet outputs;
    io::write_reduced_model_file(result.model, result.reconstruction, opt.out);
    t3 = Clock::now();
    nlohmann::json j = offline::offline_json(set, settings, result);
    j["snapshots"] = snapshots_path;
    j["snapshots_computed"] = compute;
    j["model"] = opt.out;
    j["times_s"][compute ? "snapshots" : "read"] = seconds(t0, t1);
    j["times_s"]["write"] = seconds(t2, t3);
    j["times_s"]["total"] = seconds(t0, Clock::now());
    io::write_json(j, json_path);
    outputs.commit();
  } catch (const Error& e) {
    if (!compute) throw;
    throw Error(std::string(e.what()) + "; no model written; the snapshots of this run are kept in " + snapshots_path +
                " (complete: `contactrb offline --snapshots " + snapshots_path + "` resumes from them)");
  }
  const offline::OfflineReport& rep = result.report;
  const model::ReducedModel& m = result.model;

  const auto last = [](const std::vector<double>& v) { return v.empty() ? 0.0 : v.back(); };
  // The dual error of the cone kept (an exhausted NMF keeps its best rank, not its last).
  const auto at_R = [&](const std::vector<double>& v) {
    return static_cast<int>(v.size()) > rep.R ? v[static_cast<std::size_t>(rep.R)] : last(v);
  };
  const double dual_error = at_R(settings.eps_du_relative ? rep.dual_relative_errors : rep.dual_errors);
  const auto mode = [](bool relative) { return relative ? " relative" : " absolute"; };
  const auto pod_tolerance = [&](double eps, bool relative, double threshold) {
    std::ostringstream os;
    os << "eps_pod " << eps << mode(relative) << ", threshold " << threshold;
    return os.str();
  };
  std::cout << "case " << set.case_name << ", " << set.snapshots.size() << " snapshots (set " << set.set_name << "), "
            << set.constraint << "\n"
            << "sizes: N " << m.N_max << ", R " << m.online_R_max() << ", Mk " << m.Mk_max << ", Mg " << m.Mg_max << "\n"
            << "pod: " << to_string(settings.inner_product) << " product, N " << rep.N_pod << " of "
            << rep.singular_values.size() << " ("
            << (settings.pod_modes >= 1 ? "fixed N " + std::to_string(settings.pod_modes) + ", capped at the rank"
                                        : pod_tolerance(settings.eps_pod, settings.eps_pod_relative, rep.pod_threshold))
            << ")" << (settings.supremizers ? ", + " + std::to_string(rep.N_supremizers) + " supremizers" : std::string())
            << "\n"
            << "compression: " << rep.R_kept << " of " << rep.R_hf << " constraints kept"
            << (settings.compression ? "" : " (off)") << "\n"
            << "dual: " << opt.dual << ", R " << rep.R << ", error " << dual_error << " (eps_du "
            << settings.eps_du << mode(settings.eps_du_relative) << ", " << rep.dual_status
            << (dual_error > settings.eps_du ? ": eps_du NOT reached" : "") << ")\n"
            << "eim kappa: Mk " << rep.Mk << ", error " << last(rep.eim_kappa_errors) << " (eps_eim_k "
            << settings.eps_eim_k << mode(settings.eps_eim_k_relative) << ", threshold " << rep.eim_kappa_threshold
            << ", " << rep.eim_kappa_status << ")\n"
            << "eim gamma: Mg " << rep.Mg << ", error " << last(rep.eim_gamma_errors) << " (eps_eim_g "
            << settings.eps_eim_g << mode(settings.eps_eim_g_relative) << ", threshold " << rep.eim_gamma_threshold
            << ", " << rep.eim_gamma_status << ")\n"
            << std::fixed << std::setprecision(3) << "time: " << seconds(t0, Clock::now()) << " s (pod " << rep.pod_s
            << ", dual " << rep.dual_s << ", eim " << rep.eim_kappa_s + rep.eim_gamma_s << ", other "
            << rep.total_s - rep.pod_s - rep.dual_s - rep.eim_kappa_s - rep.eim_gamma_s << (compute ? ", snapshots " : ", read ")
            << seconds(t0, t1) << ", write " << seconds(t2, t3) << ")\n"
            << std::defaultfloat << (compute ? "wrote " + snapshots_path + "\n" : std::string()) << "wrote " << opt.out
            << "\nwrote " << json_path << "\n";
  return 0;
}

}  // namespace

Command add_offline_command(CLI::App& app) {
  auto opt = std::make_shared<OfflineOptions>();
  CLI::App* sub = app.add_subcommand(
      "offline",
      "Offline stage: a reduced model (HDF5) and offline.json from a snapshot file, or from a case whose training "
      "snapshots are computed first (kept as snapshots.h5 next to the model)");
  // Exactly one source of snapshots (a usage error otherwise).
  CLI::Option_group* input = sub->add_option_group("snapshots", "Snapshot source (exactly one)");
  CLI::Option* snapshots_opt =
      input->add_option("--snapshots", opt->snapshots, "Snapshot file written by `contactrb snapshots`");
  input->add_option("--case", opt->case_name, "Built-in case: compute its snapshots first (see `contactrb cases`)");
  input->add_option("--case-file", opt->case_file, "TOML case file: compute its snapshots first (docs/cases.md)");
  input->require_option(1);
  CLI::Option* set_opt = sub->add_option("--set", opt->set_name, "With --case: the parameter set of the snapshots")
                             ->capture_default_str();
  CLI::Option* values_opt =
      sub->add_option("--values", opt->values, "With --case: explicit parameter values (comma-separated)")
          ->delimiter(',');
  CLI::Option* level_opt =
      sub->add_option("--level", opt->level, "With --case: mesh refinement level (0: the paper's mesh)")
          ->capture_default_str();
  CLI::Option* constraint_opt =
      sub->add_option("--constraint", opt->constraint, "With --case: collocation | lac | lac-simpson");
  CLI::Option* jobs_opt =
      sub->add_option("--jobs,-j", opt->jobs, "With --case: worker threads for the snapshots")->capture_default_str();
  CLI::Option* alpha_opt =
      sub->add_option("--alpha", opt->alpha, "With --case: Kacanov relaxation in (0, 1]")->capture_default_str();
  CLI::Option* tol_opt =
      sub->add_option("--tol", opt->tolerance, "With --case: Kacanov tolerance eps_KA of (63)")->capture_default_str();
  CLI::Option* iterations_opt =
      sub->add_option("--max-iterations", opt->max_iterations, "With --case: Kacanov iteration limit")
          ->capture_default_str();
  CLI::Option* solver_opt = add_snapshot_solver_option(sub, opt->solver, "With --case: ");
  CLI::Option* sequence_opt =
      add_sequence_option(sub, opt->sequence, "With --case: ", " of the snapshot solves without a warm start");
  CLI::Option* quiet_opt = sub->add_flag("--quiet,-q", opt->quiet, "With --case: no progress report on stderr");
  for (CLI::Option* o :
       {set_opt, values_opt, level_opt, constraint_opt, jobs_opt, alpha_opt, tol_opt, iterations_opt, solver_opt, sequence_opt,
        quiet_opt}) {
    o->excludes(snapshots_opt);
  }
  CLI::Option* eps_pod =
      sub->add_option("--eps-pod", opt->eps_pod,
                      "POD: tolerance on the singular values, relative (keep sigma_i / sigma_1 > eps) unless absolute")
          ->capture_default_str();
  CLI::Option* n = sub->add_option("--n", opt->n, "POD: a fixed N instead of --eps-pod (capped at the rank)");
  eps_pod->excludes(n);
  sub->add_option("--inner-product", opt->inner_product, "POD inner product: energy | h1")->capture_default_str();
  sub->add_option("--dual", opt->dual, "Dual cone: cpg | angle | nmf | rows")->capture_default_str();
  sub->add_option("--eps-du", opt->eps_du,
                  "Dual cone: tolerance eps_DU on the L2(Gamma^c) error (58), relative (each mu's error divided by "
                  "|lambda(mu)|) unless absolute")
      ->capture_default_str();
  sub->add_flag("--eps-du-relative", opt->eps_du_relative, "Dual cone: --eps-du is relative (the default)");
  sub->add_option("--r", opt->r, "Dual cone: a fixed R (NMF rank, or a greedy size limit)");
  sub->add_option("--eps-eim-k", opt->eps_eim_k,
                  "EIM of the contact map kappa: ell-infinity tolerance, relative (to max |kappa| over the training "
                  "set) unless absolute")
      ->capture_default_str();
  sub->add_option("--eps-eim-g", opt->eps_eim_g,
                  "EIM of the gap gamma: ell-infinity tolerance, relative (to max |gamma| over the training set) "
                  "unless absolute")
      ->capture_default_str();
  sub->add_flag("--absolute-tolerances", opt->absolute_tolerances,
                "All four tolerances absolute (in the units of the case: M-norm of u, |lambda|, |kappa|, |gamma|)");
  sub->add_flag("--eps-pod-absolute", opt->eps_pod_absolute, "POD: --eps-pod absolute (keep sigma_i > eps)");
  sub->add_flag("--eps-du-absolute", opt->eps_du_absolute, "Dual cone: --eps-du absolute");
  sub->add_flag("--eps-eim-k-absolute", opt->eps_eim_k_absolute, "EIM of kappa: --eps-eim-k absolute");
  sub->add_flag("--eps-eim-g-absolute", opt->eps_eim_g_absolute, "EIM of gamma: --eps-eim-g absolute");
  sub->add_flag("--no-compression", opt->no_compression, "Keep the constraints never active on the training set");
  sub->add_flag("--no-supremizers", opt->no_supremizers,
                "Primal basis: the POD modes only (no supremizer per dual generator; lambda_hat may then be "
                "undetermined when R > N)");
  CLI::Option* greedy_opt = sub->add_flag(
      "--greedy", opt->greedy,
      "With --case/--case-file: weak greedy on the error estimate over the set's points, HF solves only at the "
      "selected ones (writes snapshots.h5, greedy.csv, greedy.json next to the model)");
  greedy_opt->excludes(snapshots_opt);
  sub->add_option("--greedy-tol", opt->greedy_tol,
                  "With --greedy: stop when the max over the set of estimate / |u_rb|_A is <= this")
      ->capture_default_str()
      ->needs(greedy_opt);
  sub->add_option("--max-hf", opt->max_hf, "With --greedy: budget of HF solves (the start point's included)")
      ->capture_default_str()
      ->needs(greedy_opt);
  sub->add_option("--greedy-batch", opt->greedy_batch,
                  "With --greedy: HF solves per step, at the largest estimates (run on --jobs threads, or over the "
                  "MPI ranks under mpirun); 1: the classic greedy")
      ->capture_default_str()
      ->needs(greedy_opt);
  sub->add_option("--greedy-saturation", opt->greedy_saturation,
                  "With --greedy: saturation constant of the lazy sweep (>= 1): a point whose last estimate times "
                  "this is below the largest fresh one is not solved again; inf: every point every step")
      ->capture_default_str()
      ->needs(greedy_opt);
  sub->add_flag("--greedy-rebuild", opt->greedy_rebuild,
                "With --greedy: rebuild each step's model by POD instead of extending the previous one (row cone)")
      ->needs(greedy_opt);
  sub->add_option("--greedy-preconditioner-points", opt->greedy_preconditioner_points,
                  "With --greedy and the row cone: points of the returned model's online start and preconditioner, "
                  "its snapshots then training points farthest first (the model file grows by N^2 doubles a point); "
                  "0: the snapshots only")
      ->capture_default_str()
      ->needs(greedy_opt);
  sub->add_option("--out", opt->out,
                  "Output model file (HDF5); offline.json (greedy.csv, greedy.json with --greedy) goes to the same "
                  "directory")
      ->required();
  return {sub, [opt] { return run_offline(*opt); }};
}

}  // namespace contactrb::app
