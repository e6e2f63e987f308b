#include "contactrb/offline/offline_greedy.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <iomanip>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <utility>

#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/theta.hpp"
#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/offline/geometric_term.hpp"
#include "contactrb/offline/greedy_sweep.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::offline {

using model::ReducedModel;
using model::ReducedReconstruction;
using online::OnlineSettings;
using online::OnlineSolution;
using online::OnlineSolver;
using online::reconstruct_displacement;
using online::reconstruct_multipliers;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
inline std::size_t sz(int i) { return static_cast<std::size_t>(i); }
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string mu_text(const GreedyMu& mu) { return cases::mu_values_text(mu); }

// Progress: one line per step (ProgressMode conventions of snapshot_generation.hpp; a step is
// long, so the Terminal mode prints lines as well).
class GreedyProgress {
 public:
  GreedyProgress(ProgressMode mode, std::ostream* stream) : stream_(stream ? stream : &std::cerr), on_(mode != ProgressMode::None) {}
  void start(const GreedyMu& mu, int index, int count, const io::Snapshot& s) {
    if (!on_) return;
    *stream_ << "greedy: start at mu = " << cases::mu_short_text(mu) << " (training point " << index << " of " << count << "), HF "
             << (s.converged ? "converged in " + std::to_string(s.iterations) + " iterations" : "FAILED (" + s.status + ")")
             << ", " << std::fixed << std::setprecision(3) << s.time_s << " s" << std::defaultfloat
             << std::setprecision(6) << "\n"
             << std::flush;
  }
  void step(const GreedyStep& r, const char* stop_reason) {
    if (!on_) return;
    std::ostream& os = *stream_;
    os << "greedy step " << r.step << ": " << r.snapshots << " snapshots, N " << r.N << ", R " << r.R << ", Mk " << r.Mk
       << ", Mg " << r.Mg << ", max estimate " << std::setprecision(3) << r.max_estimate << " at mu = "
       << cases::mu_short_text(r.argmax_mu);
    if (r.online_failures > 0) os << " (" << r.online_failures << " online failures)";
    os << std::fixed << std::setprecision(3) << ", build " << r.build_s << " s, sweep " << r.sweep_s << " s ("
       << r.sweep_solves << " online solves)";
    if (r.chosen >= 0) {
      os << ", HF " << r.hf_s << " s" << std::defaultfloat << std::setprecision(3);
      if (r.hf_converged) {
        os << ", true error " << r.true_error << ", e_press " << r.true_e_press;
      } else {
        os << ", HF FAILED (" << r.hf_status << "): point excluded";
      }
      if (r.batch_points.size() > 1) {
        os << "; batch of " << r.batch_points.size() << " HF solves";
        if (r.batch_failures > 0) os << ", " << r.batch_failures << " FAILED (points excluded)";
      }
    }
    os << std::defaultfloat << std::setprecision(6);
    if (stop_reason != nullptr) os << "; stop: " << stop_reason;
    os << "\n" << std::flush;
  }
  // The model returned: the best step's, which is the last one unless a later model did worse.
  void model(const GreedyStep& best, int steps) {
    if (!on_ || best.step == steps) return;
    *stream_ << "greedy: returning the model of step " << best.step << " (" << best.snapshots
             << " snapshots, max estimate " << std::setprecision(3) << best.max_estimate << std::setprecision(6)
             << (best.online_failures > 0 ? ", " + std::to_string(best.online_failures) + " online failures" : "")
             << "): the later models did worse\n"
             << std::flush;
  }

 private:
  std::ostream* stream_;
  bool on_;
};

// The HF solves of one greedy run must live in one discretization (generate_snapshots checks it
// within one call; the greedy calls it once per point).
void check_same_layout(const io::SnapshotSet& a, const io::SnapshotSet& b, const GreedyMu& mu) {
  require(a.num_dofs == b.num_dofs && a.free_dofs == b.free_dofs && a.contact_dofs == b.contact_dofs &&
              a.slave == b.slave && a.master == b.master && a.constraint == b.constraint,
          "greedy: the HF discretization at mu = " + mu_text(mu) +
              " differs from the one of the first snapshot (DOF map, contact chains or constraint)");
}

}  // namespace

const char* to_string(GreedyOfflineStatus status) {
  switch (status) {
    case GreedyOfflineStatus::ToleranceReached: return "tolerance_reached";
    case GreedyOfflineStatus::Budget: return "budget";
    case GreedyOfflineStatus::Stagnated: return "stagnated";
  }
  return "unknown";
}

GreedyOfflineStatus greedy_offline_status_from_string(const std::string& name) {
  using enum GreedyOfflineStatus;
  return enum_from_string(name, "greedy status", std::array{ToleranceReached, Budget, Stagnated});
}

void check_settings(const GreedyOfflineSettings& s) {
  require(std::isfinite(s.tolerance) && s.tolerance > 0.0,
          "greedy: the tolerance must be finite and > 0, got " + number_text(s.tolerance));
  require(s.max_hf >= 1, "greedy: the HF budget must be >= 1, got " + std::to_string(s.max_hf));
  require(s.jobs >= 1, "greedy: the number of jobs must be >= 1, got " + std::to_string(s.jobs));
  require(s.batch >= 1, "greedy: the batch (HF solves per step) must be >= 1, got " + std::to_string(s.batch));
  require(s.saturation >= 1.0, "greedy: the saturation constant must be >= 1 (+inf: every point every step), got " +
                                   number_text(s.saturation));
  require(s.preconditioner_points >= 0, "greedy: the number of preconditioner points must be >= 0, got " +
                                          std::to_string(s.preconditioner_points));
  // Each model has its own sizes: the sweep sets every point's start itself.
  require(!s.online.start, "greedy: the online settings may not carry a start (OnlineSettings::start); the sweep "
                           "starts each point from its own last answer");
  check_settings(s.offline);
}

double reduced_energy_norm(const ReducedModel& model, const GreedyMu& mu, const Eigen::VectorXd& u_hat) {
  const Eigen::Index N = u_hat.size();
  require(N <= model.N_max, "reduced_energy_norm: u_hat has " + std::to_string(N) + " entries, the model N_max " +
                                std::to_string(model.N_max));
  const Eigen::VectorXd ta = cases::evaluate(model.thetas.a, mu);
  const Eigen::VectorXd tl = cases::evaluate(model.thetas.lift, mu);
  const int Ja = model.J_a(), JD = static_cast<int>(tl.size());
  // u = u_D + P Theta u_hat:  u'Au = u_hat' Theta'A_00 Theta u_hat + 2 u_hat' Theta'(A u_D)_0 + u_D'A u_D,
  // each term affine in theta^a (49) and, for the lift, bilinear in theta^lift.
  double q = 0.0;
  for (int j = 0; j < Ja; ++j) {
    q += ta(j) * u_hat.dot(model.A_hat[sz(j)].topLeftCorner(N, N) * u_hat);
    for (int k = 0; k < JD; ++k) {
      q += 2.0 * ta(j) * tl(k) * u_hat.dot(model.A_lift_hat[sz(j * JD + k)].head(N));
      for (int l = 0; l < JD; ++l) q += ta(j) * tl(k) * tl(l) * model.lift_AA[sz((j * JD + k) * JD + l)];
    }
  }
  return std::sqrt(std::max(0.0, q));  // rounding can make a tiny q negative
}

double relative_estimate(const ReducedModel& model, const GreedyMu& mu, const OnlineSolution& s) {
  if (!s.converged() || !s.estimate.available || !std::isfinite(s.estimate.energy)) return kInf;
  const double norm = reduced_energy_norm(model, mu, s.u_hat);
  if (norm > 0.0) return s.estimate.energy / norm;
  return s.estimate.energy > 0.0 ? kInf : 0.0;
}

int greedy_start_index(const std::vector<cases::ParameterSpec>& parameters, const std::vector<GreedyMu>& training) {
  require(!training.empty(), "greedy: the training set is empty");
  int best = 0;
  double best_d = kInf;
  for (std::size_t i = 0; i < training.size(); ++i) {
    require(training[i].size() == static_cast<Eigen::Index>(parameters.size()),
            "greedy: training point " + std::to_string(i) + " has " + std::to_string(training[i].size()) +
                " values for " + std::to_string(parameters.size()) + " parameters");
    double d = 0.0;
    for (std::size_t k = 0; k < parameters.size(); ++k) {
      const cases::ParameterSpec& q = parameters[k];
      const double width = q.max - q.min;
      const double x = training[i](static_cast<Eigen::Index>(k)) - 0.5 * (q.min + q.max);
      d += width > 0.0 ? (x / width) * (x / width) : x * x;
    }
    if (d < best_d) {  // strict: ties go to the smallest index
      best_d = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

namespace {

// What the greedy's steps share: the problem, the training set and which of its points are
// selected (HF snapshot taken) or excluded (HF solve failed), and the result being built.
struct Greedy {
  const cases::CaseSpec& spec;
  const SnapshotRequest& request;
  const GreedyOfflineSettings& settings;
  OfflineSettings offline;  // of every build (settings.offline, extended when incremental)
  const std::vector<GreedyMu>& training;
  // HF data of the true error at the chosen points (offline side: A(mu) = sum theta^a_j A_j).
  cases::AffineTerms terms;
  cases::AffineThetas thetas;
  OnlineSettings online;  // with the error estimate
  std::vector<char> selected, excluded;
  GreedyEstimates estimates;  // each training point's last estimate
  GreedyOfflineResult out;
  OfflineBuildCache cache;  // what the steps' builds share
  std::optional<OnlineSettings> fallback;  // of the sweep's points where `online` does not converge
};

// The run options of the greedy's HF solves.
SnapshotRunOptions hf_run_options(const GreedyOfflineSettings& settings) {
  SnapshotRunOptions run;
  run.jobs = settings.jobs;
  run.warm_start = SnapshotRunOptions::WarmStart::Off;
  return run;
}

// The HF solves at some training points: one snapshot set in the order of `indices`. Cold
// starts (no warm start between the points of a step), so that each snapshot depends on its
// point only, not on the threads or processes that share the step out.
io::SnapshotSet hf_solve(Greedy& g, const std::vector<int>& indices) {
  SnapshotRequest step = g.request;
  step.mu.clear();
  for (int i : indices) step.mu.push_back(g.training[sz(i)]);
  g.out.hf_solves += static_cast<int>(indices.size());
  const GreedyOfflineSettings& settings = g.settings;
  const GreedyDistribution& dist = settings.distribution;
  // Each new snapshot's eta_p from its own HF solver's factor of A_00(mu_p), by the point's
  // position in the step (-inf: none); distributed without `max`, left to the builds.
  const bool ratios = solved_on_exact_rows(settings.offline) && step.dimension == 2 && (!dist.share || dist.max);
  std::vector<double> eta(indices.size(), -kInf);
  std::mutex eta_mutex;  // a process's part writes the step's positions of its points
  const auto solve = [&](const SnapshotRequest& part) {
    SnapshotRunOptions run = hf_run_options(settings);
    if (ratios) {
      run.after_solve = [&](std::size_t k, const io::Snapshot& snapshot, const hf::HFSolver& solver) {
        double value = -kInf;
        try {
          value = geometric_ratio(solver, snapshot);
        } catch (const std::exception&) {  // left to the build, which reports it
        }
        const auto at = std::find(step.mu.begin(), step.mu.end(), part.mu[k]);
        const std::lock_guard<std::mutex> lock(eta_mutex);
        if (at != step.mu.end()) eta[static_cast<std::size_t>(at - step.mu.begin())] = value;
      };
    }
    return generate_snapshots(part, run);
  };
  // Distributed: each process solves its share, every process gets all (the same set everywhere).
  io::SnapshotSet set = dist.share ? dist.share(solve, step) : solve(step);
  if (!ratios) return set;
  if (dist.share) dist.max(eta);
  for (std::size_t k = 0; k < eta.size(); ++k) {
    if (eta[k] > -kInf && set.snapshots[k].converged) g.cache.add_geometric_ratio(set.snapshots[k].mu, eta[k]);
  }
  return set;
}

// Start: one HF solve at the training point nearest the domain centre.
void start(Greedy& g, GreedyProgress& progress) {
  g.out.start = greedy_start_index(g.spec.parameters, g.training);
  const auto t0 = Clock::now();
  g.out.snapshots = hf_solve(g, {g.out.start});
  g.out.start_hf_s = seconds_since(t0);
  const io::Snapshot& s = g.out.snapshots.snapshots.front();
  progress.start(g.training[sz(g.out.start)], g.out.start, static_cast<int>(g.training.size()), s);
  require(s.converged, "greedy: the HF solve at the start point mu = " + mu_text(s.mu) + " failed (" + s.status +
                           (s.message.empty() ? "" : ": " + s.message) + "); no model can be built");
  g.out.snapshots.set_name = "greedy";
  g.out.selected.push_back(g.out.start);
  g.selected[sz(g.out.start)] = 1;
}

// Extend's counterpart: the reduced model of the selected snapshots.
void build_model(Greedy& g, GreedyStep& row) {
  const auto t0 = Clock::now();
  OfflineResult next = build_reduced_model(g.out.snapshots, g.spec, g.offline, &g.cache);
  carry_starts(g.settings.sweep_warm_start ? coordinate_map(g.out.offline, next) : std::nullopt, g.estimates);
  g.out.offline = std::move(next);
  row.build_s = seconds_since(t0);
  const ReducedModel& model = g.out.offline.model;
  row.N = model.N_max;
  row.R = model.online_R_max();
  row.Mk = model.Mk_max;
  row.Mg = model.Mg_max;
}

// The step's figures from the fresh estimates: failures, the max over the points answered and
// its argmax (the first failing point when there is one).
void summarize_sweep(const Greedy& g, GreedyStep& row) {
  const GreedyEstimates& e = g.estimates;
  row.online_failures = 0;
  row.max_estimate = -kInf;
  int argmax_answered = -1;
  for (std::size_t i = 0; i < g.training.size(); ++i) {
    if (g.excluded[i] || !e.fresh[i]) continue;
    if (e.failed[i] || !std::isfinite(e.value[i])) {
      if (row.online_failures++ == 0) row.argmax = static_cast<int>(i);
    } else if (e.value[i] > row.max_estimate) {  // strict: ties to the smallest index
      row.max_estimate = e.value[i];
      argmax_answered = static_cast<int>(i);
    }
  }
  if (row.online_failures == 0) row.argmax = argmax_answered;
}

// Evaluate: the relative estimate at the points that may hold the largest ones (greedy_sweep.hpp;
// every point when GreedyOfflineSettings::saturation is +inf), and at every point before the
// greedy stops on the tolerance, so that the stop is checked on the whole training set. Online
// failures and points without a finite estimate are enriched first (+inf in the order below).
// Returns the points not selected yet, largest estimate first: the next HF solves.
std::vector<int> evaluate(Greedy& g, GreedyStep& row) {
  const auto t0 = Clock::now();
  const int P = static_cast<int>(g.training.size());
  std::vector<std::unique_ptr<OnlineSolver>> solvers;  // of this step's model, kept across its chunks
  const SweepContext context{g.out.offline.model, g.training, g.online, g.settings.jobs, g.settings.distribution,
                             g.excluded, &solvers, g.settings.sweep_warm_start, g.fallback ? &*g.fallback : nullptr};
  std::vector<char> eligible(sz(P), 0);
  std::vector<int> candidates;
  for (int i = 0; i < P; ++i) {
    eligible[sz(i)] = !g.excluded[sz(i)] && !g.selected[sz(i)];
    if (eligible[sz(i)]) candidates.push_back(i);
  }
  sweep_largest(context, eligible, sz(g.settings.batch), g.settings.saturation, g.estimates);
  row.sweep_solves = g.estimates.solves;
  row.sweep_iterations = g.estimates.iterations;
  summarize_sweep(g, row);
  const bool partial = std::any_of(candidates.begin(), candidates.end(), [&](int i) { return !g.estimates.fresh[sz(i)]; });
  if (partial && row.online_failures == 0 && row.max_estimate <= g.settings.tolerance) {
    sweep_stale(context, g.estimates);
    row.sweep_solves += g.estimates.solves;
    row.sweep_iterations += g.estimates.iterations;
    summarize_sweep(g, row);
  }
  row.sweep_s = seconds_since(t0);
  const std::vector<double>& value = g.estimates.value;
  std::stable_sort(candidates.begin(), candidates.end(),  // stable: ties to the smallest index
                   [&](int a, int b) { return value[sz(a)] > value[sz(b)]; });
  row.argmax_mu = g.training[sz(row.argmax)];
  return candidates;
}

// The stopping test, in this order: the tolerance, the HF budget, no point left. nullptr: go on.
const char* stop_reason(Greedy& g, const GreedyStep& row, const std::vector<int>& candidates) {
  if (row.online_failures == 0 && row.max_estimate <= g.settings.tolerance) {
    g.out.status = GreedyOfflineStatus::ToleranceReached;
    return "tolerance reached";
  }
  if (g.out.hf_solves >= g.settings.max_hf) {
    g.out.status = GreedyOfflineStatus::Budget;
    return "HF budget spent";
  }
  if (candidates.empty()) {
    g.out.status = GreedyOfflineStatus::Stagnated;
    return "every training point is selected (stagnated)";
  }
  return nullptr;
}

// The current model's true error at mu against the HF snapshot there: |u_rb - u_hf|_A(mu) /
// |u_hf|_A(mu) and e_press, the L2(Gamma^c) norm of the P0 pressures with the weights |I_r|(mu)
// of the HF quadrature.
void true_errors(const Greedy& g, const GreedyMu& mu, const OnlineSolution& rb, const io::Snapshot& snap,
                 GreedyStep& row) {
  const ReducedReconstruction& rec = g.out.offline.reconstruction;
  const fem::SparseMatrix A = cases::combine(g.terms.A, cases::evaluate(g.thetas.a, mu));
  const Eigen::VectorXd d = reconstruct_displacement(rec, mu, rb.u_hat) - snap.u;
  const double norm_hf = std::sqrt(std::max(0.0, snap.u.dot(A * snap.u)));
  const double norm_d = std::sqrt(std::max(0.0, d.dot(A * d)));
  row.true_error = norm_hf > 0.0 ? norm_d / norm_hf : norm_d;
  const Eigen::VectorXd dl = reconstruct_multipliers(rec, mu, rb.lambda_hat) - snap.lambda;
  const double lh = std::sqrt(snap.weight.dot(snap.lambda.cwiseAbs2()));
  const double ld = std::sqrt(snap.weight.dot(dl.cwiseAbs2()));
  row.true_e_press = lh > 0.0 ? ld / lh : ld;
}

// The current model's answer at training point `index`: the sweep's when it solved the point with
// this model (GreedyEstimates::start), else an online solve.
OnlineSolution current_answer(const Greedy& g, int index) {
  const ReducedModel& model = g.out.offline.model;
  const Eigen::VectorXd* x = g.estimates.start.empty() ? nullptr : &g.estimates.start[sz(index)];
  const int N = model.N_max, R = model.online_R_max();
  if (g.estimates.fresh[sz(index)] && x != nullptr && x->size() == N + R) {
    OnlineSolution answer;
    answer.status = solve::KacanovStatus::Converged;
    answer.u_hat = x->head(N);
    answer.lambda_hat = x->tail(R);
    return answer;
  }
  OnlineSolver solver(model);
  OnlineSettings online = g.online;
  std::optional<OnlineSettings> fallback = g.fallback;
  return solve_point(solver, g.training[sz(index)], online, fallback ? &*fallback : nullptr, nullptr);
}

// The step's converged snapshots join the set; a point whose HF solve failed leaves the
// training set (reported in the step).
void add_snapshots(Greedy& g, io::SnapshotSet& s, GreedyStep& row) {
  for (std::size_t k = 0; k < row.batch_points.size(); ++k) {
    const int index = row.batch_points[k];
    io::Snapshot& solved = s.snapshots[k];
    if (solved.converged) {
      g.out.snapshots.snapshots.push_back(std::move(solved));
      g.out.selected.push_back(index);
      g.selected[sz(index)] = 1;
    } else {
      ++row.batch_failures;
      g.out.excluded.push_back(index);
      g.excluded[sz(index)] = 1;
    }
  }
}

// Extend: the HF solves at the `batch` largest estimates among the points not selected yet
// (within the budget). Where the overall max is at a selected point, the estimate there is its
// floor (docs/offline-online.md, "Greedy sampling"): another solve there adds nothing, a new
// point still enriches the bases, the cone and the EIM. Then the current model's true error at
// the first of them.
void extend(Greedy& g, const std::vector<int>& candidates, GreedyStep& row) {
  const std::size_t count =
      std::min({candidates.size(), sz(g.settings.batch), sz(g.settings.max_hf - g.out.hf_solves)});
  row.batch_points.assign(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(count));
  row.chosen = candidates.front();
  const GreedyMu& mu = g.training[sz(row.chosen)];
  row.chosen_mu = mu;
  const OnlineSolution rb = current_answer(g, row.chosen);
  const auto t0 = Clock::now();
  io::SnapshotSet s = hf_solve(g, row.batch_points);
  row.hf_s = seconds_since(t0);
  require(s.snapshots.size() == count, "internal: the greedy's HF solves gave " + std::to_string(s.snapshots.size()) +
                                           " snapshots for " + std::to_string(count) + " points");
  const io::Snapshot& snap = s.snapshots.front();
  row.hf_converged = snap.converged;
  row.hf_status = snap.status;
  if (std::any_of(s.snapshots.begin(), s.snapshots.end(), [](const io::Snapshot& x) { return x.converged; })) {
    check_same_layout(g.out.snapshots, s, mu);
  }
  if (snap.converged && rb.converged()) true_errors(g, mu, rb, snap, row);
  add_snapshots(g, s, row);
}

// A model answering at more training points is better; among equals, the smaller maximum
// estimate (a later step wins ties: it holds more snapshots).
bool at_least_as_good(const GreedyStep& a, const GreedyStep& b) {
  if (a.online_failures != b.online_failures) return a.online_failures < b.online_failures;
  return a.max_estimate <= b.max_estimate;
}

}  // namespace

// The weak greedy as pyMOR's two-step protocol: each step builds the model of the selected
// snapshots, evaluates the estimate over the training set and extends by HF solves at its
// largest values, until the tolerance, the HF budget or the training set is spent.
GreedyOfflineResult run_offline_greedy(const cases::CaseSpec& spec, const SnapshotRequest& request,
                                       const GreedyOfflineSettings& settings) {
  const auto t_total = Clock::now();
  check_settings(settings);
  const std::vector<GreedyMu>& training = request.mu;
  require(!training.empty(), "greedy: the training set '" + request.set_name + "' is empty");
  require(request.dimension == 2, "greedy: the case is " + std::to_string(request.dimension) +
                                      "D: reduced models are built from 2D cases only in this build");
  require(static_cast<bool>(request.make_problem), "greedy: no problem factory given");
  const std::size_t P = training.size();
  Greedy g{spec, request, settings, settings.offline, training, cases::assemble_affine_terms(spec, cases::reference_mesh(spec, request.level)),
           cases::theta_functions(spec), settings.online, std::vector<char>(P, 0), std::vector<char>(P, 0), GreedyEstimates(P), {}, {}, {}};
  g.online.error_estimate = true;
  g.offline.extend_basis = settings.incremental && settings.offline.dual_method == DualConeMethod::Rows &&
                           settings.offline.compression;
  // Not for the steps' models, whose sweeps start from warm starts without the preconditioner:
  // the returned model only.
  g.offline.training_jacobians = false;
  if (settings.offline.dual_method == DualConeMethod::Rows && g.online.iteration == online::OnlineIteration::Automatic &&
      !g.online.kacanov) {
    // The row cone's estimate has no floor but the last step's lag: the sweep solves with the
    // accelerated iteration to kRowConeSweepAcceleratedTolerance and, where that does not converge,
    // with the reduced Newton to kRowConeSweepTolerance (docs/offline-online.md, "Greedy sampling").
    g.fallback = g.online;
    g.fallback->iteration = online::OnlineIteration::Newton;
    g.fallback->kacanov = solve::KacanovSettings{1.0, kRowConeSweepTolerance, kRowConeSweepIterations};
    g.online.iteration = online::OnlineIteration::Accelerated;
    g.online.kacanov =
        solve::KacanovSettings{1.0, kRowConeSweepAcceleratedTolerance, kRowConeSweepAcceleratedIterations};
  }
  GreedyProgress progress(settings.progress, settings.progress_stream);

  start(g, progress);
  std::optional<OfflineResult> best;  // the best model so far (at_least_as_good), returned
  for (int step = 1;; ++step) {
    const auto t_step = Clock::now();
    GreedyStep row;
    row.step = step;
    row.snapshots = static_cast<int>(g.out.selected.size());
    row.hf_solves = g.out.hf_solves;
    build_model(g, row);
    const std::vector<int> candidates = evaluate(g, row);
    if (!best || at_least_as_good(row, g.out.steps[sz(g.out.model_step - 1)])) {
      best = g.out.offline;
      g.out.model_step = step;
    }
    const char* stop = stop_reason(g, row, candidates);
    if (stop == nullptr) extend(g, candidates, row);
    row.step_s = seconds_since(t_step);
    progress.step(row, stop);
    g.out.steps.push_back(row);
    if (stop != nullptr) break;
  }
  g.out.offline = std::move(*best);
  if (settings.offline.training_jacobians) {
    add_preconditioner_points(g.out.offline.model, training, settings.preconditioner_points, settings.jobs);
    add_training_jacobians(g.out.offline.model, settings.jobs);
  }
  progress.model(g.out.steps[sz(g.out.model_step - 1)], static_cast<int>(g.out.steps.size()));
  g.out.total_s = seconds_since(t_total);
  return std::move(g.out);
}

void write_greedy_csv(const GreedyOfflineResult& result, const std::string& path) {
  const std::vector<io::SnapshotParameter>& params = result.snapshots.parameters;
  std::vector<std::string> columns{"step", "snapshots", "hf_solves", "N", "R", "Mk", "Mg", "max_estimate"};
  for (const io::SnapshotParameter& q : params) columns.push_back("argmax_" + q.name);
  columns.push_back("online_failures");
  for (const io::SnapshotParameter& q : params) columns.push_back("chosen_" + q.name);
  for (const char* c : {"hf_status", "true_error", "true_e_press", "build_s", "sweep_s", "hf_s", "step_s", "batch_solves",
                        "batch_failures", "sweep_solves", "sweep_iterations"}) {
    columns.push_back(c);
  }
  io::CsvWriter csv(columns);
  const auto value = [](const GreedyMu& mu, std::size_t k) {
    return static_cast<Eigen::Index>(k) < mu.size() ? mu(static_cast<Eigen::Index>(k)) : std::nan("");
  };
  for (const GreedyStep& r : result.steps) {
    std::vector<io::CsvCell> row{static_cast<long long>(r.step), static_cast<long long>(r.snapshots),
                                 static_cast<long long>(r.hf_solves), static_cast<long long>(r.N),
                                 static_cast<long long>(r.R), static_cast<long long>(r.Mk),
                                 static_cast<long long>(r.Mg), r.max_estimate};
    for (std::size_t k = 0; k < params.size(); ++k) row.emplace_back(value(r.argmax_mu, k));
    row.emplace_back(static_cast<long long>(r.online_failures));
    for (std::size_t k = 0; k < params.size(); ++k) row.emplace_back(value(r.chosen_mu, k));
    for (const io::CsvCell& c : std::vector<io::CsvCell>{r.hf_status, r.true_error, r.true_e_press, r.build_s, r.sweep_s,
                                                         r.hf_s, r.step_s, static_cast<long long>(r.batch_points.size()),
                                                         static_cast<long long>(r.batch_failures),
                                                         static_cast<long long>(r.sweep_solves), r.sweep_iterations}) {
      row.push_back(c);
    }
    csv.add_row(row);
  }
  csv.write(path);
}

}  // namespace contactrb::offline
