#include "contactrb/offline/snapshot_generation.hpp"

#include <unistd.h>

#include <ctime>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <memory>
#include <mutex>
#include <sstream>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/cases/catalog.hpp"
#include "contactrb/cases/parameter_sets.hpp"
#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/run_threads.hpp"
#include "contactrb/solve/blas_threads.hpp"

namespace contactrb::offline {

namespace {

// CaseSpec::origin of the built-in cases (cases::builtin_case_spec).
constexpr const char* kBuiltinOrigin = "built-in";

bool is_unmodified_builtin(const cases::CaseSpec& spec) {
  if (spec.origin != kBuiltinOrigin) return false;
  for (const cases::CaseInfo& c : cases::builtin_cases()) {
    if (c.name == spec.name) return cases::same_case(spec, cases::builtin_case_spec(spec.name));
  }
  return false;
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// CPU time of the calling thread (what a solve costs, whatever the machine's load).
double thread_cpu_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

using Layout = SnapshotLayout;

template <int Dim>
Layout layout_of(const hf::BasicHFSolver<Dim>& solver) {
  Layout l;
  l.valid = true;
  l.num_dofs = solver.problem().mesh.num_dofs();
  l.free_dofs = solver.dofs().free_dofs();
  l.slave = solver.pair().slave;
  l.master = solver.pair().master;
  l.constraint = contact::to_string(solver.problem().discretization);
  std::vector<int> nodes = l.slave;
  nodes.insert(nodes.end(), l.master.begin(), l.master.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  for (int node : nodes) {
    for (int c = 0; c < Dim; ++c) l.contact_dofs.push_back(Dim * node + c);
  }
  return l;
}

// The factory of the request's dimension.
template <int Dim>
const BasicProblemFactory<Dim>& factory_of(const SnapshotRequest& request) {
  if constexpr (Dim == 2) {
    return request.make_problem;
  } else {
    return request.make_problem3;
  }
}

// K (R x num_dofs) on the contact DOF columns (R x n_c).
io::SnapshotRows contact_columns(const Eigen::SparseMatrix<double, Eigen::RowMajor>& K, const Layout& layout) {
  std::vector<int> column(static_cast<std::size_t>(layout.num_dofs), -1);
  for (std::size_t c = 0; c < layout.contact_dofs.size(); ++c) {
    column[static_cast<std::size_t>(layout.contact_dofs[c])] = static_cast<int>(c);
  }
  // contact_dofs ascend, so the columns of a row stay ascending; stored zeros are dropped.
  io::SnapshotRows D(K.rows(), static_cast<Eigen::Index>(layout.contact_dofs.size()));
  D.reserve(K.nonZeros());
  for (Eigen::Index r = 0; r < K.outerSize(); ++r) {
    D.startVec(r);
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(K, r); it; ++it) {
      const int c = column[static_cast<std::size_t>(it.col())];
      if (c < 0) {
        throw Error("internal: constraint row " + std::to_string(r) + " touches DOF " + std::to_string(it.col()) +
                    ", which is not on a contact boundary");
      }
      if (it.value() != 0.0) D.insertBack(r, c) = it.value();
    }
  }
  D.finalize();
  return D;
}

// The coarse meshes of the request's dimension (null: no sequencing).
template <int Dim>
const cases::CoarseMeshes<Dim>* coarse_of(const SnapshotRequest& request) {
  if constexpr (Dim == 2) {
    return request.coarse.get();
  } else {
    return request.coarse3.get();
  }
}

// Where the solve at `mu` starts: `start` when it is a converged snapshot of the solver's sizes,
// else the grid sequencing's guess (SnapshotRequest::coarse), else cold.
template <int Dim>
hf::HFInitialGuess initial_guess(const SnapshotRequest& request, const cases::Mu& mu,
                                 const hf::BasicHFSolver<Dim>& solver, const io::Snapshot* start) {
  hf::HFInitialGuess guess;
  if (start != nullptr && start->converged && start->u.size() == solver.problem().mesh.num_dofs() &&
      start->lambda.size() == solver.quadrature().weight.size()) {
    guess.u = start->u;
    guess.lambda = start->lambda;
    return guess;
  }
  const cases::CoarseMeshes<Dim>* coarse = coarse_of<Dim>(request);
  if (coarse == nullptr || coarse->levels.empty() || !request.spec) return guess;
  return cases::sequence_start(*request.spec, mu, *coarse, request.constraint, request.settings, solver).guess;
}

// One parameter value: build, solve, extract. Exceptions become a failed snapshot.
using AfterSolve = std::function<void(std::size_t, const io::Snapshot&, const hf::HFSolver&)>;

// SnapshotRunOptions::after_solve on a converged 2D snapshot; its exception fails the snapshot.
template <int Dim>
void call_after_solve(const AfterSolve* after, std::size_t index, io::Snapshot& out,
                      const std::optional<hf::BasicHFSolver<Dim>>& solver) {
  if constexpr (Dim == 2) {
    if (after == nullptr || !*after || !out.converged || !solver) return;
    try {
      (*after)(index, out, *solver);
    } catch (const std::exception& e) {
      out.converged = false;
      out.status = "exception";
      out.message = e.what();
    } catch (...) {  // nothing may escape a worker thread
      out.converged = false;
      out.status = "exception";
      out.message = "unknown exception after the solve";
    }
  }
}

template <int Dim>
void solve_one(const SnapshotRequest& request, std::size_t index, io::Snapshot& out, Layout& layout,
               const io::Snapshot* start, const AfterSolve* after) {
  const auto t0 = Clock::now();
  const double cpu0 = thread_cpu_seconds();
  out.mu = request.mu[index];
  std::optional<hf::BasicHFSolver<Dim>> held;  // kept for after_solve
  try {
    hf::HFSetupOptions setup;  // after_solve may read the Newton solve's factor of A_00
    setup.keep_newton_factor = after != nullptr && static_cast<bool>(*after);
    const hf::BasicHFSolver<Dim>& solver = held.emplace(factory_of<Dim>(request)(out.mu), setup);
    layout = layout_of(solver);
    const hf::HFInitialGuess guess = initial_guess(request, out.mu, solver, start);
    hf::BasicHFSolution<Dim> s = solver.solve(request.settings, guess);
    out.converged = s.converged;
    out.status = solve::to_string(s.status);
    out.message = s.message;
    out.iterations = s.iterations;
    out.u0 = std::move(s.u0);
    out.u = std::move(s.u);
    out.lambda = std::move(s.lambda);
    if (s.rows.K.rows() == out.lambda.size() && s.rows.K.cols() == layout.num_dofs) {
      out.K = contact_columns(s.rows.K, layout);
      out.g = std::move(s.rows.g);
    }
    // A step that failed before any QP solution leaves lambda empty: then no row data.
    if (solver.quadrature().weight.size() == out.lambda.size()) out.weight = solver.quadrature().weight;
    out.gap_pointwise = std::move(s.pointwise.g);
    if (out.converged && (out.u0.size() == 0 || out.K.rows() != out.lambda.size())) {
      out.converged = false;
      out.status = "step_failed";
      out.message = "the solver reported convergence without a complete solution";
    }
  } catch (const std::exception& e) {
    out = io::Snapshot{};
    out.mu = request.mu[index];
    out.status = "exception";
    out.message = e.what();
  } catch (...) {  // nothing may escape a worker thread (std::terminate)
    out = io::Snapshot{};
    out.mu = request.mu[index];
    out.status = "exception";
    out.message = "unknown exception";
  }
  out.time_s = seconds_since(t0);
  out.cpu_time_s = thread_cpu_seconds() - cpu0;
  call_after_solve(after, index, out, held);
}

void solve_one(const SnapshotRequest& request, std::size_t index, io::Snapshot& out, Layout& layout,
               const io::Snapshot* start, const AfterSolve* after = nullptr) {
  if (request.dimension == 3) {
    solve_one<3>(request, index, out, layout, start, after);
  } else {
    solve_one<2>(request, index, out, layout, start, after);
  }
}

// Progress reports, serialized by a mutex (workers finish concurrently).
class Progress {
 public:
  Progress(ProgressMode mode, std::ostream* stream, std::size_t total) : stream_(stream ? stream : &std::cerr), total_(total) {
    if (mode == ProgressMode::Automatic) {
      mode = (stream_ == &std::cerr && ::isatty(STDERR_FILENO) == 1) ? ProgressMode::Terminal : ProgressMode::Lines;
    }
    mode_ = mode;
  }
  void finished(const io::Snapshot& s) {
    if (mode_ == ProgressMode::None) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    failed_ += s.converged ? 0 : 1;
    std::ostream& os = *stream_;
    if (mode_ == ProgressMode::Terminal) {
      os << "\rsnapshots: " << done_ << "/" << total_ << " done, " << failed_ << " failed, "
         << std::fixed << std::setprecision(1) << seconds_since(start_) << " s" << std::defaultfloat
         << std::setprecision(6) << (done_ == total_ ? "\n" : "") << std::flush;
    } else {
      os << "snapshot " << done_ << "/" << total_ << ": mu = " << cases::mu_short_text(s.mu) << " ";
      if (s.converged) {
        os << "converged in " << s.iterations << " iterations";
      } else {
        os << "FAILED (" << s.status << ")";
      }
      os << ", " << std::fixed << std::setprecision(3) << s.time_s << " s" << std::defaultfloat << std::setprecision(6)
         << "\n"
         << std::flush;
    }
  }

 private:
  std::ostream* stream_;
  ProgressMode mode_ = ProgressMode::None;
  std::size_t total_;
  std::size_t done_ = 0;
  std::size_t failed_ = 0;
  Clock::time_point start_ = Clock::now();
  std::mutex mutex_;
};

}  // namespace

SnapshotRequest make_snapshot_request(const cases::CaseSpec& spec, const std::string& set_name, int level,
                                      std::optional<contact::Discretization> constraint,
                                      const std::optional<std::vector<cases::Mu>>& values) {
  cases::check_case_spec(spec);
  SnapshotRequest r;
  r.case_name = spec.name;
  // A built-in case is named; any other case is stored as its TOML text (self-contained:
  // a .msh path is resolved), which cases::case_from_toml_string reads back.
  if (is_unmodified_builtin(spec)) {
    r.case_kind = "builtin";
    r.case_spec = spec.name;
  } else {
    r.case_kind = "toml";
    r.case_spec = cases::to_toml(spec);
  }
  r.level = level;
  r.parameters = snapshot_parameters(spec);
  r.dimension = cases::case_dimension(spec);
  r.spec = std::make_shared<const cases::CaseSpec>(spec);
  r.constraint = constraint;
  r.settings.method = default_snapshot_method(r.dimension, level);
  r.set_name = values ? "custom" : set_name;
  r.mu = values ? *values : spec.set(set_name);
  for (const cases::Mu& mu : r.mu) spec.check_mu(mu);
  if (values) cases::check_points(spec.parameters, *values, "the explicit parameter values");
  // One reference mesh, shared read-only by every worker.
  if (r.dimension == 3) {
    auto reference = std::make_shared<const mesh::Mesh3>(cases::reference_mesh3(spec, level));
    r.make_problem3 = [spec, reference, constraint](const cases::Mu& mu) {
      return cases::make_problem(spec, *reference, mu, constraint);
    };
    r.reference3 = reference;
  } else {
    auto reference = std::make_shared<const mesh::Mesh>(cases::reference_mesh(spec, level));
    r.make_problem = [spec, reference, constraint](const cases::Mu& mu) {
      return cases::make_problem(spec, *reference, mu, constraint);
    };
    r.reference = reference;
  }
  return r;
}

int set_snapshot_sequence(SnapshotRequest& request, int count) {
  count = cases::resolve_sequence(count, request.dimension, request.settings.method, request.level);
  request.coarse.reset();
  request.coarse3.reset();
  const std::vector<int> levels = cases::sequence_levels(request.level, count);
  if (levels.empty()) return count;
  require(request.spec != nullptr, "grid sequencing of snapshots: the request has no case specification");
  if (request.dimension == 3) {
    request.coarse3 = std::make_shared<const cases::CoarseMeshes<3>>(cases::coarse_meshes<3>(*request.spec, levels));
  } else {
    request.coarse = std::make_shared<const cases::CoarseMeshes<2>>(cases::coarse_meshes<2>(*request.spec, levels));
  }
  return count;
}

hf::HFMethod default_snapshot_method(int dimension, int level) {
  return hf::default_method(dimension, level);
}

bool has_problem_factory(const SnapshotRequest& request) {
  return request.dimension == 3 ? static_cast<bool>(request.make_problem3) : static_cast<bool>(request.make_problem);
}

SnapshotSchedule snapshot_schedule(const SnapshotRequest& request, const SnapshotRunOptions& options) {
  require(!request.mu.empty(), "the parameter set '" + request.set_name + "' is empty");
  const std::size_t n = request.mu.size();
  SnapshotSchedule schedule;
  // The schedule: waves of indices; start[i] is the index i warm-starts from (or none).
  std::vector<std::vector<std::size_t>>& waves = schedule.waves;
  std::vector<std::optional<std::size_t>>& start = schedule.start;
  start.resize(n);
  const bool warm = options.warm_start == SnapshotRunOptions::WarmStart::On ||
                    (options.warm_start == SnapshotRunOptions::WarmStart::Automatic &&
                     request.settings.method == hf::HFMethod::Newton);
  if (!warm) {
    waves.emplace_back(n);
    for (std::size_t i = 0; i < n; ++i) waves[0][i] = i;
  } else {
    cases::ParameterBox box;
    for (const io::SnapshotParameter& p : request.parameters) {
      box.names.push_back(p.name);
    }
    const Eigen::Index p = request.mu.front().size();
    box.min.resize(p);
    box.max.resize(p);
    if (static_cast<Eigen::Index>(request.parameters.size()) == p) {
      for (Eigen::Index k = 0; k < p; ++k) {
        box.min(k) = request.parameters[static_cast<std::size_t>(k)].min;
        box.max(k) = request.parameters[static_cast<std::size_t>(k)].max;
      }
    } else {  // no recorded domain: the bounding box of the points
      box.names.assign(static_cast<std::size_t>(p), "");
      box.min = request.mu.front();
      box.max = request.mu.front();
      for (const cases::Mu& mu : request.mu) {
        box.min = box.min.cwiseMin(mu);
        box.max = box.max.cwiseMax(mu);
      }
    }
    // Farthest-first order; distance[i]: from point i to the points ordered so far.
    std::vector<std::size_t> order{0};
    std::vector<double> distance(n, std::numeric_limits<double>::infinity());
    std::vector<char> taken(n, 0);
    taken[0] = 1;
    for (std::size_t w = 0, begin = 0; begin < n; ++w) {
      const std::size_t end = std::min(n, begin + (std::size_t{1} << w));
      waves.emplace_back();
      for (std::size_t k = begin; k < end; ++k) {
        if (k >= order.size()) {  // the next farthest point (ties: smallest index)
          std::size_t best = n;
          for (std::size_t i = 0; i < n; ++i) {
            if (!taken[i] && (best == n || distance[i] > distance[best])) best = i;
          }
          order.push_back(best);
          taken[best] = 1;
        }
        const std::size_t i = order[k];
        waves.back().push_back(i);
        for (std::size_t j = 0; j < n; ++j) {
          if (taken[j]) continue;
          const double d = cases::scaled_distance(request.mu[j], request.mu[i], box);
          distance[j] = std::min(distance[j], d);
        }
      }
      // Points ordered in this wave start from the nearest of the EARLIER waves only.
      for (std::size_t k = begin; k < end; ++k) {
        const std::size_t i = order[k];
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t kk = 0; kk < begin; ++kk) {  // ties: the earlier-ordered point
          const double d = cases::scaled_distance(request.mu[i], request.mu[order[kk]], box);
          if (d < best) {
            best = d;
            start[i] = order[kk];
          }
        }
      }
      begin = end;
    }
  }
  return schedule;
}

io::SnapshotSet generate_snapshots(const SnapshotRequest& request, const SnapshotRunOptions& options) {
  require(options.jobs >= 1, "the number of jobs must be >= 1 (got " + std::to_string(options.jobs) + ")");
  require(!request.mu.empty(), "the parameter set '" + request.set_name + "' is empty");
  require(has_problem_factory(request), "no problem factory given");

  const solve::ScopedBlasThreads blas(kSnapshotBlasThreads);
  const std::size_t n = request.mu.size();
  std::vector<io::Snapshot> snapshots(n);
  std::vector<Layout> layouts(n);
  Progress progress(options.progress, options.progress_stream, n);
  const SnapshotSchedule schedule = snapshot_schedule(request, options);
  const std::vector<std::optional<std::size_t>>& start = schedule.start;
  for (const std::vector<std::size_t>& wave : schedule.waves) {
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      for (std::size_t k = next.fetch_add(1); k < wave.size(); k = next.fetch_add(1)) {
        const std::size_t i = wave[k];
        solve_one(request, i, snapshots[i], layouts[i], start[i] ? &snapshots[*start[i]] : nullptr,
                  &options.after_solve);
        progress.finished(snapshots[i]);
      }
    };
    run_threads(std::min(wave.size(), static_cast<std::size_t>(options.jobs)), [&](std::size_t) { work(); });
  }

  return assemble_snapshot_set(request, std::move(snapshots), layouts);
}

io::SnapshotSet assemble_snapshot_set(const SnapshotRequest& request, std::vector<io::Snapshot> snapshots,
                                      const std::vector<SnapshotLayout>& layouts) {
  const std::size_t n = request.mu.size();
  require(snapshots.size() == n && layouts.size() == n, "internal: one snapshot and one layout per parameter value");
  io::SnapshotSet set;
  set.case_name = request.case_name;
  set.case_kind = request.case_kind;
  set.case_spec = request.case_spec;
  set.level = request.level;
  set.parameters = request.parameters;
  set.set_name = request.set_name;
  set.solver = hf::to_string(request.settings.method);
  set.kacanov_alpha = request.settings.kacanov.alpha;
  set.kacanov_tolerance = request.settings.kacanov.tolerance;
  set.kacanov_max_iterations = request.settings.kacanov.max_iterations;
  set.dimension = request.dimension;
  // The discretization of the first value whose solver was built; all others must agree.
  const Layout* first = nullptr;
  for (std::size_t i = 0; i < n; ++i) {
    if (!layouts[i].valid) continue;
    if (first == nullptr) {
      first = &layouts[i];
    } else if (!(layouts[i] == *first)) {
      std::ostringstream os;
      os << "the HF discretization at mu = " << cases::mu_values_text(request.mu[i]) << " differs from the one at mu = "
         << cases::mu_values_text(request.mu[static_cast<std::size_t>(first - layouts.data())])
         << " (DOF map, contact chains or constraint): the snapshots would not live in one space";
      throw Error(os.str());
    }
  }
  if (first != nullptr) {
    set.num_dofs = first->num_dofs;
    set.free_dofs = first->free_dofs;
    set.contact_dofs = first->contact_dofs;
    set.slave = first->slave;
    set.master = first->master;
    set.constraint = first->constraint;
    if (set.dimension == 2 && request.reference && request.reference->num_dofs() == set.num_dofs) {
      set.mesh = *request.reference;
    }
    if (set.dimension == 3 && request.reference3 && request.reference3->num_dofs() == set.num_dofs) {
      set.mesh3 = *request.reference3;
    }
  }
  set.snapshots = std::move(snapshots);
  return set;
}

SnapshotLayout solve_snapshot(const SnapshotRequest& request, std::size_t index, io::Snapshot& out,
                              const io::Snapshot* start) {
  Layout layout;
  solve_one(request, index, out, layout, start);
  return layout;
}

struct SnapshotProgress::State {
  Progress progress;
};
SnapshotProgress::SnapshotProgress(ProgressMode mode, std::ostream* stream, std::size_t total)
    : state_(new State{Progress(mode, stream, total)}) {}
SnapshotProgress::~SnapshotProgress() = default;
void SnapshotProgress::finished(const io::Snapshot& s) { state_->progress.finished(s); }

SnapshotSummary summarize(const io::SnapshotSet& set) {
  SnapshotSummary s;
  s.solves = static_cast<int>(set.snapshots.size());
  std::vector<int> iterations;
  for (const io::Snapshot& snap : set.snapshots) {
    s.failures += snap.converged ? 0 : 1;
    s.time_total_s += snap.time_s;
    s.cpu_time_total_s += snap.cpu_time_s;
    if (snap.converged) iterations.push_back(snap.iterations);
  }
  if (!iterations.empty()) {
    std::sort(iterations.begin(), iterations.end());
    const std::size_t m = iterations.size();
    s.iterations_min = iterations.front();
    s.iterations_max = iterations.back();
    s.iterations_median = m % 2 == 1 ? iterations[m / 2] : 0.5 * (iterations[m / 2 - 1] + iterations[m / 2]);
  }
  return s;
}

std::vector<io::SnapshotParameter> snapshot_parameters(const cases::CaseSpec& spec) {
  std::vector<io::SnapshotParameter> out;
  for (const cases::ParameterSpec& p : spec.parameters) out.push_back({p.name, cases::to_string(p.kind), p.units, p.min, p.max});
  return out;
}

const char* to_string(ProgressMode value) {
  switch (value) {
    case ProgressMode::Automatic: return "automatic";
    case ProgressMode::Terminal: return "terminal";
    case ProgressMode::Lines: return "lines";
    case ProgressMode::None: return "none";
  }
  return "unknown";
}

ProgressMode progress_mode_from_string(const std::string& name) {
  using enum ProgressMode;
  return enum_from_string(name, "progress mode", std::array{Automatic, Terminal, Lines, None});
}

const char* to_string(SnapshotRunOptions::WarmStart value) {
  switch (value) {
    case SnapshotRunOptions::WarmStart::Automatic: return "auto";
    case SnapshotRunOptions::WarmStart::On: return "on";
    case SnapshotRunOptions::WarmStart::Off: return "off";
  }
  return "unknown";
}

SnapshotRunOptions::WarmStart warm_start_from_string(const std::string& name) {
  using enum SnapshotRunOptions::WarmStart;
  return enum_from_string(name, "warm start", std::array{Automatic, On, Off});
}

}  // namespace contactrb::offline
