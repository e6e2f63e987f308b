#include "contactrb/study/evaluation.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/level_sequence.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/run_threads.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/offline/cone_projection.hpp"
#include "contactrb/online/model_check.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/online/registered_basis.hpp"

namespace contactrb::study {

using model::ReducedModel;
using model::ReducedReconstruction;
using offline::ProgressMode;
using offline::project_onto_cone;
using offline::weighted_norm;
using online::OnlineSolution;
using online::OnlineSolver;
using online::check_model;
using online::check_reconstruction;
using online::reconstruct_displacement;
using online::reconstruct_multipliers;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size();
  return m % 2 == 1 ? v[m / 2] : 0.5 * (v[m / 2 - 1] + v[m / 2]);
}

// Whether `mu` is one of the requested multiplier values (they come from text: compare with a
// relative tolerance, not bitwise).
bool same_value(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max({1.0, std::abs(a), std::abs(b)}); }
bool same_value(const cases::Mu& a, const cases::Mu& b) {
  if (a.size() != b.size()) return false;
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (!same_value(a(k), b(k))) return false;
  }
  return true;
}

struct OnlineRun {
  OnlineSolution solution;
  double time_s = 0.0;
};

// Progress of the HF part (the slow one), serialized by a mutex as in snapshot_generation.
class Progress {
 public:
  Progress(ProgressMode mode, std::ostream* stream, std::size_t total)
      : stream_(stream ? stream : &std::cerr), total_(total) {
    if (mode == ProgressMode::Automatic) {
      mode = (stream_ == &std::cerr && ::isatty(STDERR_FILENO) == 1) ? ProgressMode::Terminal : ProgressMode::Lines;
    }
    mode_ = mode;
  }
  void finished(const EvaluationRow& row) {
    if (mode_ == ProgressMode::None) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    std::ostream& os = *stream_;
    if (mode_ == ProgressMode::Terminal) {
      os << "\revaluate: " << done_ << "/" << total_ << " HF solves done, " << std::fixed << std::setprecision(1)
         << seconds_since(start_) << " s" << std::defaultfloat << std::setprecision(6) << (done_ == total_ ? "\n" : "")
         << std::flush;
    } else {
      os << "evaluate " << done_ << "/" << total_ << ": mu = " << cases::mu_short_text(row.mu) << " HF "
         << (row.hf_converged ? "converged in " + std::to_string(row.hf_iterations) + " iterations" : "FAILED (" + row.hf_status + ")")
         << ", " << std::fixed << std::setprecision(3) << row.hf_time_s << " s" << std::defaultfloat
         << std::setprecision(6) << ", e_displ " << row.e_displ << "\n"
         << std::flush;
    }
  }

 private:
  std::ostream* stream_;
  ProgressMode mode_ = ProgressMode::None;
  std::size_t total_;
  std::size_t done_ = 0;
  Clock::time_point start_ = Clock::now();
  std::mutex mutex_;
};

// The HF solve at row.mu and the three errors of the reconstructed online solution.
// `coarse`: the grid sequencing's meshes (EvaluationOptions::sequence), whose stages are timed with the solve.
void evaluate_one(hf::HFMethod method, const ReducedModel& model, const ReducedReconstruction& rec, const cases::CaseSpec& spec,
                  const mesh::Mesh& reference, const cases::CoarseMeshes<2>& coarse, const OnlineRun& online,
                  const std::vector<cases::Mu>& multiplier_mus, EvaluationRow& row) {
  hf::HFSettings settings;
  settings.kacanov = solve::KacanovSettings{model.kacanov_alpha, model.kacanov_tolerance, model.kacanov_max_iterations};
  settings.method = method;
  // HF time: the problem at mu (mapped mesh, data), assembly, factorization, condensation and
  // the HF solve; the reference mesh (generated once) is excluded.
  const auto t0 = Clock::now();
  const hf::HFSolver solver(cases::make_problem(spec, reference, row.mu, model.surface.discretization),
                            hf::setup_options_for(settings));
  const cases::SequenceStart start =
      cases::sequence_start(spec, row.mu, coarse, model.surface.discretization, settings, solver);
  const hf::HFSolution hf_solution = solver.solve(settings, start.guess);
  row.hf_time_s = seconds_since(t0);
  row.hf_converged = hf_solution.converged;
  row.hf_status = solve::to_string(hf_solution.status);
  row.hf_iterations = hf_solution.iterations;

  const mesh::Mesh& m = solver.problem().mesh;
  const std::string at = "evaluation at mu = " + cases::mu_values_text(row.mu) + ": ";
  require(m.num_dofs() == rec.num_dofs && solver.dofs().free_dofs() == rec.free_dofs,
          at + "the HF discretization of the case (" + std::to_string(m.num_dofs()) + " DOFs, " +
              std::to_string(solver.dofs().num_free()) + " free) does not match the model's reconstruction data (" +
              std::to_string(rec.num_dofs) + " DOFs, " + std::to_string(rec.free_dofs.size()) + " free)");
  require(solver.quadrature().weight.size() == rec.num_constraints,
          at + "the HF solver has " + std::to_string(solver.quadrature().weight.size()) +
              " constraint rows, the model " + std::to_string(rec.num_constraints));

  const OnlineSolution& s = online.solution;
  const Eigen::VectorXd u = reconstruct_displacement(rec, row.mu, s.u_hat);
  const Eigen::VectorXd& uh = hf_solution.u;
  const Eigen::SparseMatrix<double>& A = solver.stiffness();
  const Eigen::VectorXd& f = solver.load();
  const double a_rb = u.dot(A * u), f_rb = f.dot(u);
  const double a_hf = uh.dot(A * uh), f_hf = f.dot(uh);
  row.energy_rb = 0.5 * a_rb - f_rb;
  row.energy_hf = 0.5 * a_hf - f_hf;
  row.e_ener = 0.5 * std::abs(a_rb - f_rb - a_hf + f_hf);  // (64)

  const fem::SparseMatrix H1 = fem::h1_product(m);  // on Omega(mu)
  const Eigen::VectorXd d = u - uh;
  const double norm_hf = std::sqrt(std::max(0.0, uh.dot(H1 * uh)));
  const double norm_d = std::sqrt(std::max(0.0, d.dot(H1 * d)));
  row.e_displ = norm_hf > 0.0 ? norm_d / norm_hf : norm_d;  // (65)
  // The energy-norm error the a posteriori estimate bounds (error_estimate.hpp).
  row.e_energy_norm = std::sqrt(std::max(0.0, d.dot(A * d)));
  if (s.estimate.available) {
    row.estimate = s.estimate.energy;
    if (row.e_energy_norm > 0.0) row.effectivity = row.estimate / row.e_energy_norm;
  }

  // (66): the pointwise gap g(u) - k(u; u) of the slave nodes, geometry re-evaluated at u (as
  // HFSolution::gap_violation); its negative parts are the interpenetration.
  try {
    const contact::PointwiseContact pw = contact::project_slave_nodes(m, solver.pair(), u);
    const Eigen::VectorXd penetration = (pw.K * u - pw.g).cwiseMax(0.0);
    row.e_inter = penetration.norm();
  } catch (const Error&) {  // a reconstructed master so distorted that a segment vanishes
    row.e_inter = std::numeric_limits<double>::infinity();
  }

  // Contact pressure: the L2(Gamma^c) norm of the P0 multipliers is sum_r |I_r| lambda_r^2.
  const Eigen::VectorXd lambda = reconstruct_multipliers(rec, row.mu, s.lambda_hat);
  const contact::ContactQuadrature& q = solver.quadrature();
  {
    const Eigen::VectorXd& lh = hf_solution.lambda;
    const Eigen::VectorXd& w = q.weight;
    require(lh.size() == lambda.size() && w.size() == lambda.size(),
            at + "the HF multipliers (" + std::to_string(lh.size()) + ") and the reconstructed ones (" +
                std::to_string(lambda.size()) + ") differ in size");
    const double norm_hf = std::sqrt(w.dot(lh.cwiseAbs2()));
    const double norm_d = std::sqrt(w.dot((lambda - lh).cwiseAbs2()));
    row.e_press = norm_hf > 0.0 ? norm_d / norm_hf : norm_d;
    row.force_hf = w.dot(lh);
    row.force_rb = w.dot(lambda);
    row.e_force = row.force_hf != 0.0 ? std::abs(row.force_rb - row.force_hf) / std::abs(row.force_hf)
                                      : std::abs(row.force_rb);
    row.peak_hf = lh.size() > 0 ? lh.maxCoeff() : 0.0;
    row.peak_rb = lambda.size() > 0 ? lambda.maxCoeff() : 0.0;
    row.e_peak = row.peak_hf > 0.0 ? std::abs(row.peak_rb - row.peak_hf) / row.peak_hf : std::abs(row.peak_rb);
    // Best approximation in the cone of the R generators used online.
    const Eigen::Index R = s.lambda_hat.size();
    Eigen::VectorXd lk(static_cast<Eigen::Index>(rec.kept_rows.size())), wk(lk.size());
    double dropped = 0.0;
    Eigen::VectorXd on_kept = Eigen::VectorXd::Zero(lh.size());
    for (std::size_t i = 0; i < rec.kept_rows.size(); ++i) {
      lk(static_cast<Eigen::Index>(i)) = lh(rec.kept_rows[i]);
      wk(static_cast<Eigen::Index>(i)) = w(rec.kept_rows[i]);
      on_kept(rec.kept_rows[i]) = 1.0;
    }
    for (Eigen::Index r = 0; r < lh.size(); ++r) dropped += (1.0 - on_kept(r)) * w(r) * lh(r) * lh(r);
    const double cone_err =
        R > 0 ? project_onto_cone(online::dual_basis(rec, row.mu, static_cast<int>(R)), lk, wk).error : weighted_norm(lk, wk);
    const double best = std::sqrt(cone_err * cone_err + dropped);
    row.e_press_cone = norm_hf > 0.0 ? best / norm_hf : best;
  }

  for (const cases::Mu& mu : multiplier_mus) {
    if (!same_value(mu, row.mu)) continue;
    MultiplierProfile& p = row.multipliers;
    for (Eigen::Index r = 0; r < lambda.size(); ++r) {
      p.abscissa.push_back(reference.nodes[static_cast<std::size_t>(q.center_node[static_cast<std::size_t>(r)])].x());
      p.lambda_hf.push_back(r < hf_solution.lambda.size() ? hf_solution.lambda(r) : 0.0);
      p.lambda_rb.push_back(lambda(r));
    }
    break;
  }
}

EvaluationSummary summarize(const std::vector<EvaluationRow>& rows) {
  EvaluationSummary s;
  s.count = static_cast<int>(rows.size());
  std::vector<double> hf_times, online_times, speedups;
  int both = 0;
  for (const EvaluationRow& r : rows) {
    s.hf_failures += r.hf_converged ? 0 : 1;
    s.rb_failures += r.rb_converged ? 0 : 1;
    if (!r.hf_converged || !r.rb_converged) continue;
    ++both;
    const auto add = [](double& max, double& sum, double value) {
      max = std::max(max, value);
      sum += value;
    };
    add(s.max_e_ener, s.mean_e_ener, r.e_ener);
    add(s.max_e_displ, s.mean_e_displ, r.e_displ);
    add(s.max_e_inter, s.mean_e_inter, r.e_inter);
    add(s.max_e_press, s.mean_e_press, r.e_press);
    add(s.max_e_force, s.mean_e_force, r.e_force);
    add(s.max_e_peak, s.mean_e_peak, r.e_peak);
    s.max_e_press_cone = std::max(s.max_e_press_cone, r.e_press_cone);
    hf_times.push_back(r.hf_time_s);
    online_times.push_back(r.online_time_s);
    speedups.push_back(r.speedup);
  }
  if (both > 0) {
    for (double* mean : {&s.mean_e_ener, &s.mean_e_displ, &s.mean_e_inter, &s.mean_e_press, &s.mean_e_force,
                         &s.mean_e_peak}) {
      *mean /= both;
    }
  }
  s.median_hf_time_s = median(hf_times);
  s.median_online_time_s = median(online_times);
  s.median_speedup = median(speedups);
  std::vector<double> eff;
  for (const EvaluationRow& r : rows) {
    if (r.hf_converged && r.rb_converged && std::isfinite(r.effectivity)) eff.push_back(r.effectivity);
  }
  s.effectivity_count = static_cast<int>(eff.size());
  if (!eff.empty()) {
    s.min_effectivity = *std::min_element(eff.begin(), eff.end());
    s.max_effectivity = *std::max_element(eff.begin(), eff.end());
    s.median_effectivity = median(eff);
  }
  return s;
}

}  // namespace

Evaluation evaluate_model(const ReducedModel& model, const ReducedReconstruction& reconstruction,
                          const cases::CaseSpec& spec, const std::vector<cases::Mu>& mus,
                          const EvaluationOptions& options) {
  require(!mus.empty(), "evaluation: no parameter value");
  require(options.online_repeats >= 1,
          "evaluation: online_repeats must be >= 1 (got " + std::to_string(options.online_repeats) + ")");
  require(options.jobs >= 1, "evaluation: jobs must be >= 1 (got " + std::to_string(options.jobs) + ")");
  for (const cases::Mu& mu : mus) cases::check_mu(spec.parameters, mu, "evaluation of " + spec.context());
  for (const cases::Mu& mu : options.multiplier_mus) {
    const bool found = std::any_of(mus.begin(), mus.end(), [&mu](const cases::Mu& v) { return same_value(mu, v); });
    std::ostringstream os;
    os << "evaluation: the multipliers were requested at mu = " << cases::mu_values_text(mu)
       << ", which is not an evaluated value";
    require(found, os.str());
  }
  check_model(model);
  check_reconstruction(model, reconstruction);

  Evaluation out;
  for (const cases::ParameterSpec& p : model.parameters) out.parameter_names.push_back(p.name);
  OnlineSolver online_solver(model, options.sizes);
  out.N = online_solver.N();
  out.R = online_solver.R();
  out.Mk = online_solver.Mk();
  out.Mg = online_solver.Mg();

  // Online solves first, serially (nothing else running: clean timings).
  const std::size_t n = mus.size();
  std::vector<OnlineRun> online(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<double> times;
    for (int k = 0; k < options.online_repeats; ++k) {
      const auto t0 = Clock::now();
      online[i].solution = online_solver.solve(mus[i], options.online);
      times.push_back(seconds_since(t0));
    }
    online[i].time_s = median(times);
  }

  // HF solves and errors, in parallel over mu.
  // The mesh stored with the reconstruction (no .msh file needed), else the case's.
  const mesh::Mesh reference =
      reconstruction.mesh.nodes.empty() ? cases::reference_mesh(spec, model.level) : reconstruction.mesh;
  require(reference.num_dofs() == reconstruction.num_dofs,
          "evaluation: the mesh of case '" + spec.name + "' at level " + std::to_string(model.level) + " has " +
              std::to_string(reference.num_dofs()) + " DOFs, the model's reconstruction data " +
              std::to_string(reconstruction.num_dofs));
  // The coarse meshes before the worker threads (cases::CoarseMeshes); none on a mesh read from a file.
  const int sequence = cases::resolve_sequence(options.sequence, 2, options.hf_method, model.level,
                                               "evaluation: the grid sequencing");
  const cases::CoarseMeshes<2> coarse = cases::coarse_meshes<2>(
      spec, spec.mesh.msh_file.empty() ? cases::sequence_levels(model.level, sequence) : std::vector<int>{});
  out.hf_solver = hf::to_string(options.hf_method);
  out.hf_sequence = coarse.levels;
  out.rows.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    EvaluationRow& row = out.rows[i];
    row.mu = mus[i];
    const OnlineSolution& s = online[i].solution;
    row.rb_converged = s.converged();
    row.rb_status = solve::to_string(s.status);
    row.rb_iterations = s.iterations;
    row.online_time_s = online[i].time_s;
  }
  Progress progress(options.progress, options.progress_stream, n);
  std::vector<std::exception_ptr> errors(n);
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i = next.fetch_add(1); i < n; i = next.fetch_add(1)) {
      try {
        evaluate_one(options.hf_method, model, reconstruction, spec, reference, coarse, online[i], options.multiplier_mus,
                     out.rows[i]);
        out.rows[i].speedup = out.rows[i].online_time_s > 0.0 ? out.rows[i].hf_time_s / out.rows[i].online_time_s : 0.0;
      } catch (...) {  // nothing may escape a worker thread
        errors[i] = std::current_exception();
      }
      progress.finished(out.rows[i]);
    }
  };
  run_threads(std::min(n, static_cast<std::size_t>(options.jobs)), [&](std::size_t) { work(); });
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  out.summary = summarize(out.rows);
  return out;
}

void write_evaluation_csv(const Evaluation& evaluation, const std::string& path) {
  std::vector<std::string> columns = evaluation.parameter_names.size() > 1 ? evaluation.parameter_names
                                                                          : std::vector<std::string>{"mu"};
  const std::size_t p = columns.size();
  const std::vector<std::string> rest{"hf_solver", "hf_converged", "hf_iterations", "hf_time_s", "rb_converged", "rb_status", "rb_iterations",
                     "online_time_s", "speedup", "e_ener", "e_displ", "e_inter", "e_press", "e_force", "e_peak",
                     "e_press_cone", "force_hf", "force_rb", "peak_hf", "peak_rb", "energy_hf", "energy_rb",
                     "e_energy_norm", "estimate", "effectivity"};
  columns.insert(columns.end(), rest.begin(), rest.end());
  io::CsvWriter csv(columns);
  for (const EvaluationRow& r : evaluation.rows) {
    require(static_cast<std::size_t>(r.mu.size()) == p, "write_evaluation_csv: a row's mu has " +
                                                            std::to_string(r.mu.size()) + " values for " +
                                                            std::to_string(p) + " parameter columns");
    std::vector<io::CsvCell> cells;
    for (Eigen::Index k = 0; k < r.mu.size(); ++k) cells.emplace_back(r.mu(k));
    const std::vector<io::CsvCell> values{evaluation.hf_solver, static_cast<long long>(r.hf_converged), static_cast<long long>(r.hf_iterations), r.hf_time_s,
                 static_cast<long long>(r.rb_converged), r.rb_status, static_cast<long long>(r.rb_iterations),
                 r.online_time_s, r.speedup, r.e_ener, r.e_displ, r.e_inter, r.e_press, r.e_force, r.e_peak,
                 r.e_press_cone, r.force_hf, r.force_rb, r.peak_hf, r.peak_rb, r.energy_hf, r.energy_rb,
                 r.e_energy_norm, r.estimate, r.effectivity};
    cells.insert(cells.end(), values.begin(), values.end());
    csv.add_row(std::move(cells));
  }
  csv.write(path);
}

void write_multiplier_csv(const MultiplierProfile& profile, const std::string& path) {
  require(profile.abscissa.size() == profile.lambda_hf.size() && profile.abscissa.size() == profile.lambda_rb.size(),
          "write_multiplier_csv: the profile's columns differ in length");
  io::CsvWriter csv({"abscissa", "lambda_hf", "lambda_rb"});
  for (std::size_t i = 0; i < profile.abscissa.size(); ++i) {
    csv.add_row({profile.abscissa[i], profile.lambda_hf[i], profile.lambda_rb[i]});
  }
  csv.write(path);
}

}  // namespace contactrb::study
