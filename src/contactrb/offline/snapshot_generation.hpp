#pragma once
// High-fidelity snapshots over a parameter set, in parallel (DESIGN.md data flow: "snapshot
// store over the training set (parallel over mu)").
//
// J worker threads take parameter indices from one shared atomic counter (per wave of the
// warm-start schedule, SnapshotRunOptions::warm_start); each builds its own problem and
// HFSolver, and writes its result to the slot of that index. The HF solver
// holds no shared mutable state, so the stored data do not depend on J (only the timings
// do). A failed solve (not converged, or an exception while building or solving) is
// recorded with its status and message, never dropped.
#include <functional>
#include <cstddef>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/level_sequence.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/hf/contact_problem.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/io/snapshot_file.hpp"

namespace contactrb::offline {

// Builds the HF problem at mu (Dim = 2 or 3). Called concurrently from the worker threads: it
// must not modify shared state (capture immutable data only).
template <int Dim>
using BasicProblemFactory = std::function<hf::BasicContactProblem<Dim>(const cases::Mu& mu)>;
using ProblemFactory = BasicProblemFactory<2>;
using ProblemFactory3 = BasicProblemFactory<3>;

// What to compute, and the metadata the snapshot file records about it.
struct SnapshotRequest {
  std::string case_name;
  std::string case_kind = "builtin";  // "builtin" | "toml"
  std::string case_spec;              // the case name (builtin) or the TOML text
  int level = 0;
  std::vector<io::SnapshotParameter> parameters;
  std::string set_name;
  std::vector<cases::Mu> mu;  // the parameter points, in the order of the output
  // The space dimension: 2 solves with make_problem on `reference`, 3 with make_problem3 on
  // `reference3` (one code path, BasicHFSolver<Dim>); recorded in the set.
  int dimension = 2;
  ProblemFactory make_problem;
  ProblemFactory3 make_problem3;
  // The HF method (settings.method: default_snapshot_method of the dimension and level, from
  // make_snapshot_request) and its settings; recorded in the set (SnapshotSet::solver).
  hf::HFSettings settings;
  // The reference mesh the factory maps, recorded in the set (SnapshotSet::mesh or mesh3, /mesh
  // of the file); null: not recorded.
  std::shared_ptr<const mesh::Mesh> reference;
  std::shared_ptr<const mesh::Mesh3> reference3;
  // The case and constraint the factory builds (make_snapshot_request), for the coarse problems
  // of the grid sequencing; null: no sequencing possible.
  std::shared_ptr<const cases::CaseSpec> spec;
  std::optional<contact::Discretization> constraint;
  // Grid sequencing of the cold solves (set_snapshot_sequence; docs/solvers.md, "Grid
  // sequencing"): the coarse meshes of the request's level; empty: none.
  std::shared_ptr<const cases::CoarseMeshes<2>> coarse;
  std::shared_ptr<const cases::CoarseMeshes<3>> coarse3;
};

// A request for a case specification (2D or 3D, cases::case_dimension) over one of its named
// sets (or over `values` when given, recorded as set "custom"). The reference mesh is generated once, here, and mapped
// per mu by the factory (Gmsh is serialized and slow; mapping is cheap).
// Throws contactrb::Error for an unknown set or a value outside the parameter domain.
SnapshotRequest make_snapshot_request(const cases::CaseSpec& spec, const std::string& set_name, int level = 0,
                                      std::optional<contact::Discretization> constraint = std::nullopt,
                                      const std::optional<std::vector<cases::Mu>>& values = std::nullopt);

// Grid sequencing of the request's cold solves: `count` coarse levels (cases::sequence_levels of
// request.level; -1: cases::default_sequence of the request's dimension, method and level), whose
// meshes are generated here, before any worker thread (cases::CoarseMeshes). A solve without a
// converged start (the first wave of a warm-started sweep, every solve of a cold one, a part)
// starts from the coarse chain's transferred solution; a warm-started solve starts from its
// neighbour (measured: docs/performance.md, "Warm starts and grid sequencing in snapshot
// sweeps"). Returns the count used. Throws contactrb::Error for count < -1 or a request without
// its case (spec).
int set_snapshot_sequence(SnapshotRequest& request, int count);

// The HF method of snapshot solves when none is asked for: hf::default_method (measured on the
// training sets, docs/solvers.md, "Which solver for snapshots").
hf::HFMethod default_snapshot_method(int dimension, int level);

// True when the request holds the problem factory of its dimension.
bool has_problem_factory(const SnapshotRequest& request);

// What a snapshot file records of the case's parameters.
std::vector<io::SnapshotParameter> snapshot_parameters(const cases::CaseSpec& spec);

enum class ProgressMode {
  Automatic,  // Terminal when the stream is stderr and stderr is a terminal, else Lines
  Terminal,   // one status line rewritten with '\r'
  Lines,      // one line per finished parameter value
  None,
};
const char* to_string(ProgressMode value);  // "automatic" | "terminal" | "lines" | "none"
ProgressMode progress_mode_from_string(const std::string& name);  // throws contactrb::Error

struct SnapshotRunOptions {
  int jobs = 1;  // worker threads (>= 1; more than the number of values is capped)
  // Warm start (docs/solvers.md, "Warm start"): each solve starts from the converged solution (u, lambda) of the
  // nearest point (scaled coordinates, cases::scaled_distance) among those solved before it in
  // a FIXED schedule, independent of `jobs`, so the stored data stay bitwise independent of the
  // thread count: the points are ordered farthest-first (start at the first point, then the
  // point farthest from those already ordered, ties to the smaller index) and solved in waves
  // of 1, 2, 4, ... points; the points of one wave run in parallel and start from the waves
  // before it (cold when none converged). The answers agree with cold starts to the solver
  // tolerance, not bitwise (tests/offline/test_snapshot_warm_start.cpp).
  // Automatic: on for the Newton method (tolerance 1e-10: start-dependence at 1e-9), off for
  // Kacanov (eps_KA = 1e-3: the snapshots move by up to 8e-4, enough to change the paper's
  // tables downstream, e.g. the hertz-b demo's N, R and the POD spectra; measured).
  enum class WarmStart { Automatic, On, Off };
  WarmStart warm_start = WarmStart::Automatic;
  ProgressMode progress = ProgressMode::None;
  std::ostream* progress_stream = nullptr;  // nullptr: std::cerr
  // Called after each converged 2D solve, on its worker thread (concurrently for different
  // indices), with the snapshot and its solver, which lives only for the call and then holds its
  // factor of A_00 (hf::BasicHFSolver::held_inverse_block; HFSetupOptions::keep_newton_factor):
  // what the caller computes from the solver's data at that mu (the greedy's geometric ratio).
  // Not in the snapshot's times. An exception from it fails the snapshot (status "exception").
  std::function<void(std::size_t index, const io::Snapshot& snapshot, const hf::HFSolver& solver)> after_solve;
};
const char* to_string(SnapshotRunOptions::WarmStart value);  // "auto" | "on" | "off"
SnapshotRunOptions::WarmStart warm_start_from_string(const std::string& name);  // throws contactrb::Error

// The BLAS threads of a snapshot run (solve/blas_threads.hpp), set for the whole run: the solves
// run in parallel over the values (threads, MPI ranks), and the Newton solver's BLAS-3 results
// depend on the BLAS's thread count in the last bits, so one count makes the data the same under
// any launcher (mpirun binds a rank to one core: OpenBLAS then runs one thread) and any
// OPENBLAS_NUM_THREADS.
inline constexpr int kSnapshotBlasThreads = 1;

// Runs the HF solves of `request` and returns the snapshot set (one Snapshot per value of
// request.mu, in order), with kSnapshotBlasThreads BLAS threads. Throws contactrb::Error for jobs < 1, an empty set, a missing
// factory, or solvers that disagree on the discretization (different DOF maps or contact
// chains at different mu: the snapshots would not live in one space).
io::SnapshotSet generate_snapshots(const SnapshotRequest& request, const SnapshotRunOptions& options = {});

// Summary figures of a snapshot set (for the command line and the bench). Iteration
// figures are over the converged solves (0 when none converged).
struct SnapshotSummary {
  int solves = 0;
  int failures = 0;
  int iterations_min = 0;
  double iterations_median = 0.0;
  int iterations_max = 0;
  double time_total_s = 0.0;      // sum of the per-solve wall times (problem, HF setup, solve)
  double cpu_time_total_s = 0.0;  // sum of the per-solve CPU times
};
SnapshotSummary summarize(const io::SnapshotSet& set);

// The pieces of generate_snapshots, for drivers that distribute the solves over processes
// (apps/contactrb/mpi_snapshots.cpp, snapshots --part): the same calls in the same schedule
// give the same bytes.

// The discretization a solver works in (what a snapshot file records once); must agree across mu.
struct SnapshotLayout {
  bool valid = false;  // false: no solver was built (an exception before it)
  int num_dofs = 0;
  std::vector<int> free_dofs;
  std::vector<int> contact_dofs;
  std::vector<int> slave;
  std::vector<int> master;
  std::string constraint;

  bool operator==(const SnapshotLayout& o) const {
    return num_dofs == o.num_dofs && free_dofs == o.free_dofs && contact_dofs == o.contact_dofs && slave == o.slave &&
           master == o.master && constraint == o.constraint;
  }
};

// The warm-start schedule of SnapshotRunOptions::warm_start: waves of indices, and the index
// each point starts from (nullopt: cold). One wave of all indices when warm starts are off.
struct SnapshotSchedule {
  std::vector<std::vector<std::size_t>> waves;
  std::vector<std::optional<std::size_t>> start;
};
SnapshotSchedule snapshot_schedule(const SnapshotRequest& request, const SnapshotRunOptions& options);

// One parameter value (request.mu[index]) built, solved and extracted into `out`, starting from
// `start` when it is a converged snapshot of the same sizes. Never throws: an exception becomes
// a failed snapshot. Returns the solver's layout (invalid when no solver was built).
SnapshotLayout solve_snapshot(const SnapshotRequest& request, std::size_t index, io::Snapshot& out,
                              const io::Snapshot* start);

// The set of `snapshots` (one per value of request.mu, in order) with the metadata of
// `request`. Throws contactrb::Error when two valid layouts differ.
io::SnapshotSet assemble_snapshot_set(const SnapshotRequest& request, std::vector<io::Snapshot> snapshots,
                                      const std::vector<SnapshotLayout>& layouts);

// Progress reports of finished solves (ProgressMode), safe to call from several threads.
class SnapshotProgress {
 public:
  SnapshotProgress(ProgressMode mode, std::ostream* stream, std::size_t total);
  ~SnapshotProgress();
  SnapshotProgress(const SnapshotProgress&) = delete;
  SnapshotProgress& operator=(const SnapshotProgress&) = delete;
  void finished(const io::Snapshot& s);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace contactrb::offline
