#pragma once
// Weak greedy sampling of a training set on the a posteriori error estimate (docs/theory.md,
// "Error estimate"; docs/offline-online.md, "Greedy sampling"). pyMOR's weak_greedy protocol (STYLE.md): each
// step *evaluates* the estimate of the current reduced model over the whole training set
// (online solves only) and *extends* the snapshot set by one HF solve where the relative
// estimate is largest. The reduced model of a step is offline::build_reduced_model on the snapshots
// selected so far: with the row cone, the previous step's basis and estimate data extended by the
// new snapshots (GreedyOfflineSettings::incremental); otherwise POD with the usual tolerance, the
// cone on the selected multipliers and supremizers, rebuilt. EIM trained on the selected snapshots.
//
// Offline only (it holds the HF reference mesh and the affine terms for the true error).
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

namespace contactrb::offline {

// The parameter point as the greedy sees it (p values; the code reaches it only through this
// alias and SnapshotRequest::mu).
using GreedyMu = cases::Mu;

enum class GreedyOfflineStatus {
  ToleranceReached,  // no online failure and max relative estimate over the (usable) training set <= tolerance
  Budget,            // max_hf HF solves spent, tolerance not reached
  Stagnated,         // every usable training point is selected: nothing left to add
};
const char* to_string(GreedyOfflineStatus status);  // "tolerance_reached" | "budget" | "stagnated"
GreedyOfflineStatus greedy_offline_status_from_string(const std::string& name);  // throws contactrb::Error


// The greedy over several processes (`mpirun -np K contactrb offline --greedy`,
// apps/contactrb/mpi_greedy.cpp; src/ holds no MPI). Every process calls run_offline_greedy with
// the same arguments and builds the same model at each step; each sweeps the estimate over its
// `block` of the training set and `gather` gives every process all the blocks, so that every
// process picks the same points as the serial run; the HF solves of a step are shared out by
// `share` (point k of the step on process k mod K: with GreedyOfflineSettings::batch = 1 process 0
// alone solves) and every process gets all the snapshots. Empty functions: one process.
struct GreedyDistribution {
  // [begin, end) of this process's points among n.
  std::function<std::pair<std::size_t, std::size_t>(std::size_t n)> block;
  // `values` has n * width entries on every process (width consecutive ones per point), this one
  // having filled its block of points (ok false: its sweep threw). Afterwards every process holds
  // every entry. Returns false when some process was not ok.
  std::function<bool(std::vector<double>& values, std::size_t width, bool ok)> gather;
  // The HF solves of the points of `step`: each process calls solve(part) on its part of them
  // (a request with a subset of step.mu, possibly none: then it does not call solve; solve may
  // throw) and every process returns the set of all of step.mu's snapshots, in step.mu's order,
  // as solve(step) would (an exception on any process is thrown on every process).
  using SolveFn = std::function<io::SnapshotSet(const SnapshotRequest& part)>;
  std::function<io::SnapshotSet(const SolveFn& solve, const SnapshotRequest& step)> share;
  // Elementwise max of `values` (the same size on every process) over the processes: each
  // process's geometric ratios of the step's snapshots it solved (-inf for the others) become
  // every process's, so that the builds take each ratio from its HF solve's factor as one process
  // does. Empty: the builds compute the ratios themselves on every process.
  std::function<void(std::vector<double>& values)> max;
  bool active() const { return static_cast<bool>(gather); }
};

// The sweep of a row-cone greedy (OfflineSettings::dual_method Rows) with the default online
// settings: the accelerated iteration (OnlineIteration::Accelerated) to this relative fixed-point
// residual, at most this many steps; where it does not converge, the reduced Newton to this
// relative increment, at most this many steps. An accelerated step has no contact linearization
// and no (N+R) LU (hertz-3p, N 48, R 15: about 6.5 us against about 90 us a Newton step); the
// greedy's hertz-3p sweeps need at most 16 of them a solve at level 0, 17 at level 3, and their
// estimates are the Newton's to 1e-6 relative (docs/offline-online.md, "Greedy sampling").
inline constexpr double kRowConeSweepAcceleratedTolerance = 1e-10;
inline constexpr int kRowConeSweepAcceleratedIterations = 40;
inline constexpr double kRowConeSweepTolerance = 1e-10;
inline constexpr int kRowConeSweepIterations = 30;

struct GreedyOfflineSettings {
  // Stop when max_mu Delta_u(mu) / |u_rb(mu)|_A(mu) <= tolerance (unit-free; relative_estimate()).
  // 1e-3: with the row cone (the default) the estimate has no floor and overestimates the
  // relative energy-norm error 1.5-4.5 times; hertz-3p reaches it in 33 HF solves with max
  // e_displ 1.8e-4 on its verification set, where 1e-2 stopped at 1.6e-3 (docs/offline-online.md,
  // "Greedy sampling"). The paper's cones stop near 1e-2 (the EIM estimate's square-root floor)
  // and spend the budget.
  double tolerance = 1e-3;
  // Budget of HF solves, the start point's included (>= 1). A failed HF solve counts.
  int max_hf = 50;
  // Threads of the estimate sweep (one OnlineSolver each) and of a step's HF solves; the result
  // does not depend on it.
  int jobs = 1;
  // HF solves per step (>= 1): the `batch` largest estimates among the usable points not selected
  // yet (a batched weak greedy: its solves run in parallel on `jobs` threads, or over the MPI
  // processes). 1: the classic weak greedy, one solve per model build. Larger batches spend fewer
  // builds and sweeps per HF solve, and may select points a one-at-a-time greedy would not.
  int batch = 1;
  // The saturation constant tau of the lazy sweep (greedy_sweep.hpp): a point whose last estimate
  // times tau is below the batch-th largest fresh estimate is not solved again this step. 1
  // assumes the estimate of a point never grows as the model is enriched; +inf solves every point
  // every step. Before the greedy stops on the tolerance every point is solved, whatever tau.
  double saturation = 1.0;
  // Of every build_reduced_model call: the defaults of `contactrb offline`, compression (Remark 7)
  // included. Measured both ways (docs/offline-online.md, "Greedy sampling"): with few snapshots
  // the kept rows can miss a row the reduced solution then penetrates (hertz-a, 61 points, eps_KA
  // 1e-6: verification e_displ 0.1, 1.7e-4 without compression); without it the EIM runs over
  // every row and the models missed their own snapshots on hertz-3p (e_displ 0.17 at a selected
  // point, 5e-4 with compression) and were 100 times less accurate on ring-block.
  OfflineSettings offline;
  // Extend the model at each step instead of rebuilding it (OfflineSettings::extend_basis: the
  // primal basis, the supremizers of the row cone and the estimate's Riesz data grow with the
  // snapshots; docs/offline-online.md, "Greedy sampling"). Applies to the row cone with the
  // constraint compression (the defaults); other cones rebuild by POD at every step.
  bool incremental = true;
  // Of the sweep (error_estimate is forced on; a row-cone greedy with the default iteration and
  // no Kacanov settings sweeps with the accelerated iteration and the reduced Newton where that
  // does not converge, kRowConeSweepAcceleratedTolerance and kRowConeSweepTolerance). Explicit
  // settings are used as given, with no fallback.
  contactrb::online::OnlineSettings online;
  // Start each sweep solve from the point's last reduced answer, carried into the new model's
  // coordinates, when the model extends the last one (greedy_sweep.hpp, "Warm starts"; a POD
  // rebuild starts as any online solve). The same answers to the sweep's tolerance in fewer
  // steps; a point whose solve from the model's own guess fails may converge from its warm start
  // and is then answered, not enriched first (docs/offline-online.md, "Greedy sampling").
  bool sweep_warm_start = true;
  // The returned row-cone model's online start and preconditioner points (add_preconditioner_points):
  // its snapshot points, then training points farthest first up to this many in all. 256: on
  // hertz-3p the median query takes 6 preconditioned steps instead of 7, for 4.7 MB of Jacobians
  // in the model file (docs/offline-online.md, "Online: the preconditioned iteration").
  // 0: the snapshot points only.
  int preconditioner_points = 256;
  ProgressMode progress = ProgressMode::None;  // one line per step (Terminal prints lines too)
  std::ostream* progress_stream = nullptr;     // nullptr: std::cerr
  GreedyDistribution distribution;             // empty: one process
};
// Throws contactrb::Error naming the first invalid setting (tolerance <= 0 or not finite,
// max_hf < 1, jobs < 1, batch < 1, saturation < 1 or NaN, invalid offline settings).
void check_settings(const GreedyOfflineSettings& settings);

// One step: the reduced model built from the `snapshots` selected so far, its estimate sweep,
// and (unless the greedy stops here) the HF solve at the argmax.
struct GreedyStep {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  int step = 0;       // 1, 2, ...
  int snapshots = 0;  // snapshots of this step's model
  int hf_solves = 0;  // HF solves spent before this step's own one (failed ones included)
  int N = 0, R = 0, Mk = 0, Mg = 0;
  // Max of relative_estimate over the usable training points the sweep solved (every point when the
  // greedy stops on the tolerance; under the saturation assumption, the max over every point) where
  // the online solve converged with a finite estimate (-inf when there is none); the others are
  // counted in online_failures and are the first points the step enriches.
  double max_estimate = 0.0;
  int argmax = -1;            // training index of the max, or of the first online failure when there is one
  GreedyMu argmax_mu;
  int online_failures = 0;    // usable training points without a converged online answer and finite estimate
  // The HF solve of this step at the largest estimate (-1 / NaN when the greedy stopped at this
  // step); with batch > 1 the step's other solves are in `batch_points`.
  int chosen = -1;
  GreedyMu chosen_mu;  // empty when the greedy stopped at this step
  bool hf_converged = false;
  std::string hf_status;
  // The error of this step's model at the chosen point, against the new HF solution (NaN when
  // either solve failed): |u_rb - u_hf|_A(mu) / |u_hf|_A(mu) (the quantity the relative
  // estimate estimates) and the contact-pressure error e_press (docs/offline-online.md).
  double true_error = kNaN;
  double true_e_press = kNaN;
  // Every HF solve of this step (training indices in decreasing estimate, `chosen` first; empty
  // when the greedy stopped here) and how many of them failed (those points are excluded).
  std::vector<int> batch_points;
  int batch_failures = 0;
  int sweep_solves = 0;  // online solves of the sweep (the training points solved)
  long long sweep_iterations = 0;  // their reduced iterations, summed
  // Wall times (s): build_reduced_model, the sweep, the step's HF solves, the whole step.
  double build_s = 0.0, sweep_s = 0.0, hf_s = 0.0, step_s = 0.0;
};

struct GreedyOfflineResult {
  GreedyOfflineStatus status = GreedyOfflineStatus::Budget;
  std::vector<int> selected;  // training indices of the snapshots, in selection order
  std::vector<int> excluded;  // training indices whose HF solve failed (skipped afterwards)
  int start = -1;             // the start index (selected[0])
  int hf_solves = 0;
  io::SnapshotSet snapshots;  // the selected HF snapshots, in selection order, set name "greedy"
  // The best step's model: fewest online failures, then the smallest max_estimate (a later step
  // wins ties), so a greedy never returns a model worse on its training set than one it built.
  // It holds the first steps[model_step - 1].snapshots snapshots of `snapshots`.
  OfflineResult offline;
  int model_step = 0;  // 1-based step whose model is `offline`
  std::vector<GreedyStep> steps;
  double start_hf_s = 0.0;
  double total_s = 0.0;
};

// |u_rb|_A(mu) = sqrt(u' A(mu) u), u = u_D(mu) + Theta u_hat the total displacement, from the
// model's reduced arrays only ((49) and the lift terms lift_AA, A_lift_hat); u_hat of size N <= N_max.
double reduced_energy_norm(const contactrb::model::ReducedModel& model, const GreedyMu& mu,
                           const Eigen::VectorXd& u_hat);

// The greedy's criterion: Delta_u(mu) / |u_rb(mu)|_A(mu), +inf when the online solve did not
// converge or carries no estimate (so that such a point is picked first); 0 / 0 = 0.
double relative_estimate(const contactrb::model::ReducedModel& model, const GreedyMu& mu,
                         const contactrb::online::OnlineSolution& solution);

// The start point: the training point nearest the centre of the parameter box (Euclidean distance
// in coordinates scaled to [0, 1] per parameter; ties to the smallest index).
int greedy_start_index(const std::vector<cases::ParameterSpec>& parameters, const std::vector<GreedyMu>& training);

// Runs the greedy over the training points request.mu (the request also gives the level, the
// constraint discretization and the HF settings; make_snapshot_request). Throws contactrb::Error
// for invalid settings, an empty training set, a failed HF solve at the start point, or an
// error of build_reduced_model. Non-convergence elsewhere is reported in the steps.
GreedyOfflineResult run_offline_greedy(const cases::CaseSpec& spec, const SnapshotRequest& request,
                                       const GreedyOfflineSettings& settings = {});

// The per-step table as CSV (one line per step: step,snapshots,hf_solves,N,R,Mk,Mg,max_estimate,
// argmax_<name>...,online_failures,chosen_<name>...,hf_status,true_error,true_e_press,build_s,sweep_s,
// hf_s,step_s,batch_solves,batch_failures,sweep_solves,sweep_iterations; one argmax_ and one chosen_
// column per parameter, chosen_ empty (NaN) when the greedy stopped at that step), written atomically.
void write_greedy_csv(const GreedyOfflineResult& result, const std::string& path);

}  // namespace contactrb::offline
