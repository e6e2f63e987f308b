// HF solver scaling (docs/performance.md, "HF solve by level" and "HF scaling in 3D"): one
// configuration per run, one CSV line on stdout (run bench/hf_scaling.sh for the 2D sweep,
// bench/hf_scaling_3d.sh for the 3D one). A plain program, not Google Benchmark: the peak memory
// of a configuration is the peak RSS of its own process. The case's dimension (2D or 3D) is read
// from the case; both go through the same code (hf::BasicHFSolver<Dim>).
//
//   bench_hf_scaling --case hertz-a --level 4 --mu 0.3 --solver newton [--constraint lac]
//                    (--mu: default the case's reference value; hertz-3d: --case hertz-3d --mu 0.02)
//                    [--repeat 3] [--alpha 0.3] [--tolerance 1e-3] [--linear schur|lu|amg|auto]
//                    [--linear-solver direct|amg|auto (direct: schur)] [--amg-from DOFS] [--krylov-tol 1e-9]
//                    [--krylov-max 400] [--krylov-restart 80] [--amg-threshold 0.25] [--amg-aggressive 1] [--amg-smoother forward-backward|symmetric] [--forcing-max 3e-2 (equal to --krylov-tol: a constant forcing term)] [--passes frozen|consistent] [--lu umfpack|eigen]
//                    [--linearization analytic|fd] [--branch-passes N] [--krylov 100 (0: dense LU)]
//                    [--frozen-rows-from-dimension 3 (4: never)] [--verbose] [--header]
//                    [--threads N (Newton: OpenBLAS threads of the factorization and the selected-inverse
//                     block from 200 000 free DOFs, one elsewhere; default: the hardware threads;
//                     0: OPENBLAS_NUM_THREADS everywhere)]
//                    [--ordering auto|cholmod|node-metis] [--keep-freed 1 (0: glibc's default malloc thresholds)]
//                    [--sequence K [--sequence-step 2]] (grid sequencing: K coarse solves on levels
//                     L - K*step, ..., L - step, each from the previous one, the fine one from the last;
//                     cases/level_sequence.hpp; -1: contactrb solve's default, cases::default_sequence)
//                    [--fine-size H (hertz-3d: the mesh generated with contact-zone size H,
//                     mesh::Hertz3dGeometry::fine_size, instead of the level's 0.04 / 2^level, for a
//                     point between two levels; --level then names only the coarse levels of --sequence)]
//                    [--ahead 1 (Newton: A_00's ordering and symbolic analysis beside the assembly,
//                     hf::HFSetupOptions; 0: in the solve, after it)]
//
// Columns: case, level, DOFs, slave nodes, solver, constraint, mu, setup_s (assembly, lifting;
// Kacanov: plus the factorization and the condensed block S), solve_s (iterations), total_s
// (median over --repeat runs of setup + solve), iterations, status, contact force, energy,
// KKT residual, active rows, peak RSS (MB), CPU time per repeat of setup + solve (user + system
// of the process, s; on a loaded machine the wall times above are not the cost), CPU time of the
// mesh generation (not in the other columns); with --sequence: the coarse stages as
// level:iterations joined by '+' (a '!' after a stage that did not converge; '-' without), and
// their wall time per repeat (coarse meshes, setups, solves, transfers; in total_s, not in setup_s
// or solve_s); the wall time of the mesh generation and the peak RSS right after it (MB); the
// Newton linear solver taken (schur, lu or amg; '-' for Kacanov) and the GMRES products of all
// its systems.
// Grid sequencing (cases/level_sequence.hpp) in 2D and 3D alike.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/level_sequence.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/keep_freed_memory.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "contactrb/mesh/mesh.hpp"

using namespace contactrb;

namespace {

struct BenchOptions {
  std::string case_name = "hertz-a", solver = "newton", constraint, lu = "umfpack", linear = "schur", passes = "frozen";
  int level = 0, repeat = 1, inner = -1, free_steps = -1, branch_passes = -1, krylov = -1, frozen_rows_from_dimension = -1;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string ordering = "auto";
  std::string linearization = "analytic";
  bool verbose = false;
  bool keep_freed = true;
  bool ahead = true;
  std::optional<double> mu;  // default: the case's reference value
  double alpha = 0.3, tolerance = 1e-3, branch_below = -1.0, safeguard = -1.0;
  int newton_passes = -1, switch_passes = -1, chord = -1;
  int sequence = 0, sequence_step = 2;
  double fine_size = 0.0;  // > 0: hertz-3d at this contact-zone size instead of the level's
  int amg_from = -1, krylov_max = -1, krylov_restart = -1, amg_aggressive = -1;
  double krylov_tolerance = -1.0, amg_threshold = -1.0, forcing_max = -1.0;
  std::string amg_smoother;
};

// Parses argv into `o`; returns false after --header (the header printed) and exits with code 2
// on a bad option.
bool parse_options(int argc, char** argv, BenchOptions& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "missing value after %s\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--header") {
      std::printf("case,level,dofs,slave_nodes,solver,constraint,mu,setup_s,solve_s,total_s,iterations,status,"
                  "force,energy,kkt,active,peak_rss_mb,cpu_s,mesh_cpu_s,sequence,coarse_s,mesh_s,mesh_rss_mb,linear,krylov\n");
      return false;
    }
    if (a == "--case") o.case_name = next();
    else if (a == "--level") o.level = std::stoi(next());
    else if (a == "--fine-size") o.fine_size = std::stod(next());
    else if (a == "--mu") o.mu = std::stod(next());
    else if (a == "--solver") o.solver = next();
    else if (a == "--constraint") o.constraint = next();
    else if (a == "--verbose") o.verbose = true;
    else if (a == "--lu") o.lu = next();
    else if (a == "--linear") o.linear = next();
    else if (a == "--linear-solver") o.linear = next() == std::string("direct") ? "schur" : argv[i];
    else if (a == "--amg-from") o.amg_from = std::stoi(next());
    else if (a == "--krylov-tol") o.krylov_tolerance = std::stod(next());
    else if (a == "--krylov-max") o.krylov_max = std::stoi(next());
    else if (a == "--krylov-restart") o.krylov_restart = std::stoi(next());
    else if (a == "--amg-threshold") o.amg_threshold = std::stod(next());
    else if (a == "--amg-aggressive") o.amg_aggressive = std::stoi(next());
    else if (a == "--amg-smoother") o.amg_smoother = next();
    else if (a == "--forcing-max") o.forcing_max = std::stod(next());
    else if (a == "--inner") o.inner = std::stoi(next());
    else if (a == "--passes") o.passes = next();
    else if (a == "--free-steps") o.free_steps = std::stoi(next());
    else if (a == "--branch-passes") o.branch_passes = std::stoi(next());
    else if (a == "--branch-below") o.branch_below = std::stod(next());
    else if (a == "--safeguard") o.safeguard = std::stod(next());
    else if (a == "--newton-passes") o.newton_passes = std::stoi(next());
    else if (a == "--switch-passes") o.switch_passes = std::stoi(next());
    else if (a == "--chord") o.chord = std::stoi(next());
    else if (a == "--linearization") o.linearization = next();
    else if (a == "--krylov") o.krylov = std::stoi(next());
    else if (a == "--frozen-rows-from-dimension") o.frozen_rows_from_dimension = std::stoi(next());
    else if (a == "--threads") o.threads = std::stoi(next());
    else if (a == "--keep-freed") o.keep_freed = std::stoi(next()) != 0;
    else if (a == "--ahead") o.ahead = std::stoi(next()) != 0;
    else if (a == "--ordering") o.ordering = next();
    else if (a == "--sequence") o.sequence = std::stoi(next());
    else if (a == "--sequence-step") o.sequence_step = std::stoi(next());
    else if (a == "--repeat") o.repeat = std::stoi(next());
    else if (a == "--alpha") o.alpha = std::stod(next());
    else if (a == "--tolerance") o.tolerance = std::stod(next());
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      std::exit(2);
    }
  }
  return true;
}

// The HF settings of the options; throws contactrb::Error on an unknown name.
hf::HFSettings settings_from(const BenchOptions& o) {
  hf::HFSettings settings;
  settings.method = hf::hf_method_from_string(o.solver);
  settings.newton.lu = solve::sparse_lu_backend_from_string(o.lu);
  settings.newton.linear_solver = hf::newton_linear_solver_from_string(o.linear);
  if (o.amg_from >= 0) settings.newton.amg_from_free_dofs = o.amg_from;
  if (o.krylov_tolerance > 0.0) settings.newton.krylov.tolerance = o.krylov_tolerance;
  if (o.krylov_max > 0) settings.newton.krylov.max_iterations = o.krylov_max;
  if (o.krylov_restart > 0) settings.newton.krylov.restart = o.krylov_restart;
  if (o.amg_threshold > 0.0) settings.newton.amg.strong_threshold = o.amg_threshold;
  if (o.amg_aggressive >= 0) settings.newton.amg.aggressive_levels = o.amg_aggressive;
  if (!o.amg_smoother.empty()) settings.newton.amg.smoother = solve::amg_smoother_from_string(o.amg_smoother);
  if (o.forcing_max > 0.0) settings.newton.krylov_forcing.max = o.forcing_max;
  hf::NewtonTuning& t = settings.newton.tuning;
  if (o.inner > 0) t.max_inner_iterations = o.inner;
  t.inner_passes = hf::newton_inner_passes_from_string(o.passes);
  if (o.free_steps >= 0) t.max_free_steps = o.free_steps;
  if (o.branch_passes >= 0) t.max_branch_passes = o.branch_passes;
  if (o.branch_below >= 0.0) t.branch_passes_below = o.branch_below;
  if (o.safeguard >= 0.0) t.kacanov_safeguard = o.safeguard;
  if (o.newton_passes > 0) t.max_newton_passes = o.newton_passes;
  if (o.switch_passes > 0) t.switch_passes = o.switch_passes;
  if (o.chord >= 0) t.chord_steps = o.chord;
  if (o.krylov >= 0) t.krylov_max_iterations = o.krylov;
  if (o.frozen_rows_from_dimension >= 0) t.frozen_rows_from_dimension = o.frozen_rows_from_dimension;
  t.blas_threads = o.threads;
  if (o.linearization == "fd") {
    settings.newton.linearization.method = contact::LinearizationMethod::FiniteDifference;
  } else if (o.linearization != "analytic") {
    throw Error("unknown --linearization " + o.linearization + " (analytic or fd)");
  }
  if (o.ordering == "cholmod") settings.newton.ordering = solve::FactorOrdering::Cholmod;
  else if (o.ordering == "node-metis") settings.newton.ordering = solve::FactorOrdering::NodeMetis;
  else if (o.ordering != "auto") throw Error("unknown --ordering " + o.ordering + " (auto, cholmod or node-metis)");
  settings.kacanov.alpha = o.alpha;
  settings.kacanov.tolerance = o.tolerance;
  return settings;
}

double cpu_seconds(const rusage& r) {
  return static_cast<double>(r.ru_utime.tv_sec + r.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(r.ru_utime.tv_usec + r.ru_stime.tv_usec);
}

rusage usage_now() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return r;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

mesh::Mesh reference_of(const BenchOptions& o, const cases::CaseSpec& spec, std::integral_constant<int, 2>) {
  require(o.fine_size <= 0.0, "--fine-size applies to the hertz-3d mesh only");
  return cases::reference_mesh(spec, o.level);
}
mesh::Mesh3 reference_of(const BenchOptions& o, const cases::CaseSpec& spec, std::integral_constant<int, 3>) {
  if (o.fine_size <= 0.0) return cases::reference_mesh3(spec, o.level);
  require(spec.mesh.generator == "hertz-3d", "--fine-size applies to the hertz-3d mesh only");
  mesh::Hertz3dGeometry geometry;
  geometry.fine_size = o.fine_size;
  return mesh::generate_hertz_3d(geometry);
}

// The coarse stages of the grid sequencing (level_sequence.hpp).
template <int Dim>
cases::SequenceStart coarse_start(const cases::CaseSpec& spec, const cases::Mu& mu, const std::vector<int>& levels,
                                  std::optional<contact::Discretization> d, const hf::HFSettings& settings,
                                  const hf::BasicHFSolver<Dim>& fine) {
  return cases::sequence_start(spec, mu, levels, d, settings, fine);
}

// The coarse stages as level:iterations joined by '+' ('!' after one that did not converge).
std::string stages_text(const cases::SequenceStart& start, bool verbose) {
  std::string stages;
  for (const cases::SequenceStage& st : start.stages) {
    // Appended piece by piece: GCC 12's -Wrestrict misfires on `const char* + std::string&&` here.
    if (!stages.empty()) stages += '+';
    stages += std::to_string(st.level);
    stages += ':';
    stages += std::to_string(st.iterations);
    if (!st.converged) stages += '!';
    if (verbose) {
      std::fprintf(stderr, "  coarse level %d: %d DOFs, %d iterations%s, mesh %.4f s, setup + solve %.4f s, transfer %.4f s\n",
                   st.level, st.dofs, st.iterations, st.converged ? "" : " (not converged)", st.mesh_s, st.solve_s, st.transfer_s);
    }
  }
  return stages.empty() ? "-" : stages;
}

template <int Dim>
void print_history(const hf::BasicHFSolution<Dim>& sol) {
  const hf::NewtonTimings& tm = sol.newton_timings;
  if (tm.linear_solver == hf::NewtonLinearSolver::Amg) std::fprintf(stderr, "  AMG: %d levels\n", tm.amg_levels);
  std::fprintf(stderr, "  A_00: analysis %.4f s%s numeric factorization %.4f s (nnz(L) %ld, %d BLAS threads) z %.4f s; initial evaluation %.4f s\n",
               tm.analyze_s, tm.analysis_ahead ? (" (beside the assembly; waited " + std::to_string(tm.analysis_wait_s) + " s)").c_str() : "",
               tm.numeric_s, tm.factor_nonzeros, tm.blas_threads, tm.rhs_s, tm.initial_s);
  for (const auto& it : sol.newton_history) {
    std::fprintf(stderr, "  kkt %.3e merit %.3e active %d changed %d systems %d |E| %d step %g colours %d branch passes %d kacanov step %d chord %d lin %.4f s linear algebra %.4f s (G block %.4f s) krylov %d (tolerance %.1e) line search %.4f s\n",
                 it.residual, it.merit, it.active, it.changed, it.factorizations, it.reduced_size, it.step, it.colours, it.branch_passes, it.kacanov_step ? 1 : 0, it.chord_steps,
                 it.linearize_s, it.factorize_s, it.block_s, it.krylov, it.forcing, it.search_s);
  }
  if (!sol.message.empty()) std::fprintf(stderr, "  %s\n", sol.message.c_str());
}

// One configuration in the case's dimension: mesh, then --repeat times setup + (coarse stages) +
// solve; prints the CSV line; returns the exit code (0 converged, 3 not).
template <int Dim>
int run(const BenchOptions& o, const cases::CaseSpec& spec, const cases::Mu& mu, const hf::HFSettings& settings) {
  std::optional<contact::Discretization> d;
  if (!o.constraint.empty()) d = contact::discretization_from_string(o.constraint);
  const rusage before = usage_now();
  const auto mesh_start = std::chrono::steady_clock::now();
  const auto reference = reference_of(o, spec, std::integral_constant<int, Dim>{});
  const hf::BasicContactProblem<Dim> problem = cases::make_problem(spec, reference, mu, d);
  const double mesh_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - mesh_start).count();
  const rusage after_mesh = usage_now();
  const double mesh_cpu_s = cpu_seconds(after_mesh) - cpu_seconds(before);
  const int sequence = cases::resolve_sequence(o.sequence, Dim, settings.method, o.level, "--sequence");
  const std::vector<int> coarse_levels = cases::sequence_levels(o.level, sequence, o.sequence_step);
  std::vector<double> setup, solve, total, coarse;
  hf::BasicHFSolution<Dim> sol;
  cases::SequenceStart start;
  for (int r = 0; r < std::max(1, o.repeat); ++r) {
    hf::HFSetupOptions prepare = hf::setup_options_for(settings);
    prepare.newton_analysis = prepare.newton_analysis && o.ahead;
    const hf::BasicHFSolver<Dim> s(problem, prepare);
    start = coarse_start(spec, mu, coarse_levels, d, settings, s);
    sol = s.solve(settings, start.guess);
    setup.push_back(s.setup_time_s());
    total.push_back(sol.time_s + start.time_s);
    solve.push_back(sol.time_s - s.setup_time_s());
    coarse.push_back(start.time_s);
  }
  const std::string stages = stages_text(start, o.verbose);
  if (o.verbose) print_history(sol);
  const rusage usage = usage_now();
  const double cpu_s = (cpu_seconds(usage) - cpu_seconds(after_mesh)) / std::max(1, o.repeat);
  int krylov = 0;
  for (const auto& it : sol.newton_history) krylov += it.krylov;
  const char* linear = sol.method == hf::HFMethod::Newton ? hf::to_string(sol.newton_timings.linear_solver) : "-";
  std::printf("%s,%d,%d,%zu,%s,%s,%g,%.4f,%.4f,%.4f,%d,%s,%.9g,%.9g,%.2e,%d,%.1f,%.4f,%.2f,%s,%.4f,%.2f,%.1f,%s,%d\n",
              o.case_name.c_str(), o.level, problem.mesh.num_dofs(),
              mesh::boundary_nodes(problem.mesh, mesh::kSlaveBoundary).size(), o.solver.c_str(),
              contact::to_string(problem.discretization), mu(0), median(setup), median(solve), median(total),
              sol.iterations, solve::to_string(sol.status), sol.contact_force, sol.energy, sol.kkt.max(),
              sol.active_constraints, static_cast<double>(usage.ru_maxrss) / 1024.0, cpu_s, mesh_cpu_s, stages.c_str(),
              median(coarse), mesh_s, static_cast<double>(after_mesh.ru_maxrss) / 1024.0, linear, krylov);
  return sol.converged ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  BenchOptions o;
  if (!parse_options(argc, argv, o)) return 0;
  if (o.keep_freed) contactrb::keep_freed_memory();  // docs/performance.md, "Kept freed memory"
  try {
    const cases::CaseSpec spec = cases::builtin_case_spec(o.case_name);
    const cases::Mu mu = cases::Mu::Constant(1, o.mu.value_or(spec.parameters.at(0).reference));
    const hf::HFSettings settings = settings_from(o);
    const int dimension = cases::case_dimension(spec);
    return dimension == 3 ? run<3>(o, spec, mu, settings) : run<2>(o, spec, mu, settings);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_hf_scaling: %s\n", e.what());
    return 1;
  }
}
