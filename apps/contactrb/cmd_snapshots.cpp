// `contactrb snapshots`: high-fidelity solves of a case (2D or 3D) over a parameter set, in
// parallel, stored in one HDF5 file (docs/cli.md, "`contactrb snapshots`"). Failed solves are recorded in
// the file; the command then exits with code 3 unless --allow-failures.
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <future>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "commands.hpp"
#include "hf_solver_option.hpp"
#include "mpi_snapshots.hpp"
#include "mpi_world.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "contactrb/offline/snapshot_parts.hpp"
#include "contactrb/solve/blas_threads.hpp"

namespace contactrb::app {

namespace {

// Exit code when some solve failed (same as `contactrb solve` for a non-converged solve).
constexpr int kExitSolveFailed = 3;

struct SnapshotsOptions {
  std::string case_name;
  std::string case_file;
  std::string set_name = "training";
  std::vector<std::string> values;  // overrides the set when given (parse_values_option)
  int jobs = 1;
  int level = 0;
  std::string constraint;  // empty: the case's default
  double alpha = solve::KacanovSettings{}.alpha;
  double tolerance = solve::KacanovSettings{}.tolerance;
  int max_iterations = solve::KacanovSettings{}.max_iterations;
  std::optional<std::string> solver;  // --solver (nullopt: offline::default_snapshot_method)
  bool allow_failures = false;
  bool quiet = false;
  std::string part;  // "k/K": part k of K of the values (offline/snapshot_parts.hpp)
  std::string warm_start = "auto";  // --warm-start (SnapshotRunOptions::warm_start)
  int sequence = -1;                // --sequence (offline::set_snapshot_sequence; -1: automatic)
  std::string out;
};

using Clock = std::chrono::steady_clock;

// What the solves need (the setup of one process or MPI rank).
struct Setup {
  offline::SnapshotRequest request;
  offline::SnapshotRunOptions run;
  Clock::time_point start, solves_start;  // the setup's start (after the cheap checks), its end
};

// The options checked, the case and its reference mesh built.
Setup make_setup(const SnapshotsOptions& opt, bool mpi) {
  require(!mpi || opt.jobs == 1, "--jobs " + std::to_string(opt.jobs) +
                                     ": under mpirun each rank solves one value at a time (start more ranks)");
  // Cheap checks first.
  const cases::CaseSpec spec =
      read_case(opt.case_name, opt.case_file);
  require(opt.jobs >= 1, "--jobs must be >= 1 (got " + std::to_string(opt.jobs) + ")");
  require(opt.level >= 0, "--level must be >= 0 (got " + std::to_string(opt.level) + ")");
  std::optional<contact::Discretization> constraint;
  if (!opt.constraint.empty()) constraint = contact::discretization_from_string(opt.constraint);
  hf::HFSettings settings;
  settings.kacanov.alpha = opt.alpha;
  settings.kacanov.tolerance = opt.tolerance;
  settings.kacanov.max_iterations = opt.max_iterations;
  solve::check_settings(settings.kacanov);
  const std::optional<hf::HFMethod> method = snapshot_solver_option(opt.solver);
  check_sequence_option(opt.sequence);
  check_output_file(opt.out);
  check_file_roles({{"--case-file", opt.case_file}, {"the case's mesh file", spec.mesh.msh_file}}, {{"--out", opt.out}});
  const std::optional<std::vector<cases::Mu>> values = parse_values_points(opt.values, "--values", spec.parameters);
  std::optional<offline::SnapshotPart> part;
  if (!opt.part.empty()) part = offline::parse_snapshot_part(opt.part);

  Setup p;
  p.start = Clock::now();
  p.request = offline::make_snapshot_request(spec, opt.set_name, opt.level, constraint, values);
  settings.method = method.value_or(p.request.settings.method);
  p.request.settings = settings;
  offline::set_snapshot_sequence(p.request, opt.sequence);
  if (part) offline::restrict_to_part(p.request, *part);
  offline::SnapshotRunOptions& run = p.run;
  run.jobs = opt.jobs;
  run.progress = opt.quiet ? offline::ProgressMode::None : offline::ProgressMode::Automatic;
  run.warm_start = option_enum("--warm-start", opt.warm_start, offline::warm_start_from_string);
  if (run.warm_start == offline::SnapshotRunOptions::WarmStart::On) {
    // A warm start would need other parts' values.
    require(!part, "--warm-start on: a part (--part) is solved cold, it has not the other parts' values");
  } else if (part) {
    run.warm_start = offline::SnapshotRunOptions::WarmStart::Off;
  }
  p.solves_start = Clock::now();
  return p;
}

// Under mpirun, MPI_Init mostly waits (0.2-0.3 s of little CPU with OpenMPI's default
// transports: the other processes, the network probes), so a thread does the setup meanwhile
// (`setup`) and then solves this rank's first task (`early`; mpi_snapshots.hpp, first_task;
// `rank`: the launcher's rank, -1 when unknown: no early solve).
struct EarlyStart {
  std::future<std::shared_ptr<const Setup>> setup;
  std::future<std::optional<EarlySolve>> early;
};
EarlyStart start_early(const SnapshotsOptions& opt, int rank) {
  auto setup = std::make_shared<std::promise<std::shared_ptr<const Setup>>>();
  EarlyStart e;
  e.setup = setup->get_future();
  e.early = std::async(std::launch::async, [&opt, rank, setup]() -> std::optional<EarlySolve> {
    std::shared_ptr<const Setup> s;
    try {
      s = std::make_shared<const Setup>(make_setup(opt, true));
    } catch (...) {
      setup->set_exception(std::current_exception());
      return std::nullopt;
    }
    setup->set_value(s);
    const std::optional<std::size_t> i =
        rank >= 0 ? first_task(offline::snapshot_schedule(s->request, s->run), rank) : std::nullopt;
    if (!i) return std::nullopt;
    EarlySolve solved;
    solved.index = *i;
    solved.layout = offline::solve_snapshot(s->request, *i, solved.snapshot, nullptr);  // `s` keeps the request alive
    return solved;
  });
  return e;
}

// CONTACTRB_MPI_INIT_OVERLAP=0: no work during MPI_Init nor MPI_Finalize (docs/parallel.md: MPI
// libraries whose MPI_Init installs memory hooks, e.g. UCX's, race with a thread that allocates
// meanwhile).
bool overlap_mpi_init() {
  const char* v = std::getenv("CONTACTRB_MPI_INIT_OVERLAP");
  return v == nullptr || std::string_view(v) != "0";
}

int run_snapshots(const SnapshotsOptions& opt) {
  // Under mpirun: every rank does the setup, rank 0 the rest (mpi_snapshots.hpp).
  const bool mpi = built_with_mpi() && mpirun_processes() > 1;
  // Before any thread: the MPI path (its early solve included) solves as generate_snapshots does.
  const solve::ScopedBlasThreads blas(offline::kSnapshotBlasThreads);
  const bool overlap = mpi && overlap_mpi_init();
  EarlyStart early;
  if (overlap) early = start_early(opt, mpirun_rank());
  // (A throw here or below waits for the thread of `early`: std::async's future.)
  std::unique_ptr<MpiWorld> world = MpiWorld::start_if_launched();
  const std::shared_ptr<const Setup> setup =
      overlap ? early.setup.get() : std::make_shared<const Setup>(make_setup(opt, world != nullptr));
  const offline::SnapshotRequest& request = setup->request;

  const auto seconds = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
  const auto t0 = setup->start;
  const auto t1 = setup->solves_start;
  std::optional<io::SnapshotSet> gathered = world ? mpi_generate_snapshots(*world, request, setup->run, std::move(early.early))
                                                  : offline::generate_snapshots(request, setup->run);
  if (!gathered) return 0;  // an MPI rank other than 0: its results are in rank 0's file
  const io::SnapshotSet set = std::move(*gathered);
  const auto t2 = Clock::now();
  const auto write = [&] {
    const OutputLock lock(std::filesystem::path(opt.out).parent_path());  // as every output set
    io::write_snapshot_file(set, opt.out);
  };
  const int ranks = world ? world->size() : 0;
  if (world && overlap) {
    // MPI is done with: the file is written on a thread while the main thread (the only one
    // that calls MPI) finalizes, so MPI_Finalize's handshake with the other ranks, which wait
    // in it from the end of their work, is off the critical path (docs/parallel.md).
    std::future<void> written = std::async(std::launch::async, write);
    world.reset();
    written.get();
  } else {
    write();
  }
  const auto t3 = Clock::now();
  const double solves_wall = seconds(t1, t2);

  const offline::SnapshotSummary s = offline::summarize(set);
  const std::size_t rows = set.snapshots.empty() ? 0 : static_cast<std::size_t>(set.snapshots.front().lambda.size());
  std::cout << "case " << set.case_name << (set.dimension == 3 ? " (3D)" : "") << ", set " << set.set_name << " (" << set.snapshots.size() << " values of "
            << set.parameters.front().name << (set.parameters.size() > 1 ? " and others" : "") << "), " << set.constraint << ", " << set.num_dofs << " DOFs, " << rows
            << " constraints, "
            << (ranks > 0 ? std::to_string(ranks) + " MPI ranks\n" : std::to_string(opt.jobs) + (opt.jobs == 1 ? " job\n" : " jobs\n"));
  std::cout << "solver: " << set.solver << "\n";
  if (request.coarse || request.coarse3) {
    const std::vector<int>& levels = request.coarse ? request.coarse->levels : request.coarse3->levels;
    std::cout << "grid sequencing: levels";
    for (std::size_t k = 0; k < levels.size(); ++k) std::cout << (k == 0 ? " " : ", ") << levels[k];
    std::cout << " (the solves without a warm start)\n";
  }
  std::cout << "solves: " << s.solves << "\n"
            << "failures: " << s.failures << "\n";
  if (s.failures < s.solves) {
    std::cout << "iterations: min " << s.iterations_min << ", median " << s.iterations_median << ", max "
              << s.iterations_max << " (converged solves)\n";
  } else {
    std::cout << "iterations: none converged\n";
  }
  std::cout << std::fixed << std::setprecision(3) << "total time: " << seconds(t0, t3) << " s (wall clock: reference mesh "
            << seconds(t0, t1) << " s, solves " << solves_wall << " s, file " << seconds(t2, t3) << " s)\n"
            << "time per solve: " << s.time_total_s / s.solves << " s wall, " << s.cpu_time_total_s / s.solves
            << " s CPU (means over the solves); throughput " << solves_wall / s.solves
            << " s per value (solves wall clock / solves)\n"
            << std::defaultfloat << std::setprecision(6) << "wrote " << opt.out << "\n";
  if (s.failures > 0) {
    std::ostringstream os;
    os << s.failures << " of " << s.solves << " solves failed (recorded in " << opt.out << "):";
    for (const io::Snapshot& snap : set.snapshots) {
      if (!snap.converged) os << "\n  mu = " << cases::mu_values_text(snap.mu) << ": " << snap.status << ": " << snap.message;
    }
    if (opt.allow_failures) {
      std::cerr << "contactrb: warning: " << os.str() << "\n";
      return 0;
    }
    std::cerr << "contactrb: error: " << os.str() << "\n";
    return kExitSolveFailed;
  }
  return 0;
}

}  // namespace

Command add_snapshots_command(CLI::App& app) {
  auto opt = std::make_shared<SnapshotsOptions>();
  CLI::App* sub = app.add_subcommand("snapshots", "High-fidelity snapshots of a case over a parameter set, in HDF5");
  // Exactly one case source (a usage error otherwise).
  CLI::Option_group* input = sub->add_option_group("case", "Case (exactly one)");
  input->add_option("--case", opt->case_name, "Built-in case (see `contactrb cases`)");
  input->add_option("--case-file", opt->case_file, "TOML case file (docs/cases.md)");
  input->require_option(1);
  sub->add_option("--set", opt->set_name, "Parameter set: training | verification")->capture_default_str();
  sub->add_option("--values", opt->values, "Explicit parameter values instead of a set (comma-separated)")
      ->delimiter(',');
  sub->add_option("--jobs,-j", opt->jobs, "Worker threads")->capture_default_str();
  sub->add_option("--level", opt->level, "Mesh refinement level of a generated mesh (0: the paper's mesh)")
      ->capture_default_str();
  sub->add_option("--constraint", opt->constraint, "collocation | lac | lac-simpson (default: the case's)");
  sub->add_option("--alpha", opt->alpha, "Kacanov relaxation in (0, 1]")->capture_default_str();
  sub->add_option("--tol", opt->tolerance, "Kacanov stopping tolerance eps_KA of (63), > 0")->capture_default_str();
  sub->add_option("--max-iterations", opt->max_iterations, "Kacanov iteration limit")->capture_default_str();
  add_snapshot_solver_option(sub, opt->solver);
  add_sequence_option(sub, opt->sequence, "", " of the solves without a warm start");
  sub->add_flag("--allow-failures", opt->allow_failures, "Exit 0 even when some solves failed (they are recorded)");
  sub->add_flag("--quiet,-q", opt->quiet, "No progress report on stderr");
  sub->add_option("--warm-start", opt->warm_start,
                  "auto (on for the Newton method, off for Kacanov) | on: each value starts from the solution of the "
                  "nearest value solved before it, in a fixed schedule (the same for any --jobs or MPI ranks) | off")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  sub->add_option("--part", opt->part, "k/K: only part k of K of the values (array jobs; join with `contactrb merge`)");
  sub->add_option("--out", opt->out, "Output HDF5 file (written atomically)")->required();
  return {sub, [opt] { return run_snapshots(*opt); }};
}

}  // namespace contactrb::app
