// HF solver scaling (docs/performance.md, "HF solve by level"): one configuration per
// run, one CSV line on stdout (run bench/hf_scaling.sh for the sweep). A plain program,
// not Google Benchmark: the peak memory of a configuration is the peak RSS of its own process.
//
//   bench_hf_scaling --case hertz-a --level 4 --mu 0.3 --solver newton [--constraint lac]
//                    [--repeat 3] [--alpha 0.3] [--tolerance 1e-3] [--linear schur|lu] [--passes frozen|consistent] [--lu umfpack|eigen]
//                    [--linearization analytic|fd] [--branch-passes N] [--krylov 100 (0: dense LU)] [--verbose] [--header]
//                    [--threads N (Newton: OpenBLAS threads of the factorization and the selected-inverse
//                     block from 200 000 free DOFs, one elsewhere; default: the hardware threads;
//                     0: OPENBLAS_NUM_THREADS everywhere)]
//                    [--ordering auto|cholmod|node-metis] [--keep-freed 1 (0: glibc's default malloc thresholds)]
//                    [--sequence K [--sequence-step 2]] (grid sequencing: K coarse solves on levels
//                     L - K*step, ..., L - step, each from the previous one, the fine one from the last;
//                     cases/level_sequence.hpp)
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
// or solve_s).
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <string>
#include <thread>
#include <vector>

#include "contactrb/common/keep_freed_memory.hpp"
#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/cases/level_sequence.hpp"
#include "contactrb/hf/hf_solver.hpp"

using namespace contactrb;

int main(int argc, char** argv) {
  std::string case_name = "hertz-a", solver = "newton", constraint, lu = "umfpack", linear = "schur", passes = "frozen";
  int level = 0, repeat = 1, inner = -1, free_steps = -1, branch_passes = -1, krylov = -1;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string ordering = "auto";
  std::string linearization = "analytic";
  bool verbose = false;
  bool keep_freed = true;
  bool ahead = true;
  double mu = 0.3, alpha = 0.3, tolerance = 1e-3, branch_below = -1.0, safeguard = -1.0;
  int newton_passes = -1, switch_passes = -1, chord = -1;
  int sequence = 0, sequence_step = 2;
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
                  "force,energy,kkt,active,peak_rss_mb,cpu_s,mesh_cpu_s,sequence,coarse_s\n");
      return 0;
    }
    if (a == "--case") case_name = next();
    else if (a == "--level") level = std::stoi(next());
    else if (a == "--mu") mu = std::stod(next());
    else if (a == "--solver") solver = next();
    else if (a == "--constraint") constraint = next();
    else if (a == "--verbose") verbose = true;
    else if (a == "--lu") lu = next();
    else if (a == "--linear") linear = next();
    else if (a == "--inner") inner = std::stoi(next());
    else if (a == "--passes") passes = next();
    else if (a == "--free-steps") free_steps = std::stoi(next());
    else if (a == "--branch-passes") branch_passes = std::stoi(next());
    else if (a == "--branch-below") branch_below = std::stod(next());
    else if (a == "--safeguard") safeguard = std::stod(next());
    else if (a == "--newton-passes") newton_passes = std::stoi(next());
    else if (a == "--switch-passes") switch_passes = std::stoi(next());
    else if (a == "--chord") chord = std::stoi(next());
    else if (a == "--linearization") linearization = next();
    else if (a == "--krylov") krylov = std::stoi(next());
    else if (a == "--threads") threads = std::stoi(next());
    else if (a == "--keep-freed") keep_freed = std::stoi(next()) != 0;
    else if (a == "--ahead") ahead = std::stoi(next()) != 0;
    else if (a == "--ordering") ordering = next();
    else if (a == "--sequence") sequence = std::stoi(next());
    else if (a == "--sequence-step") sequence_step = std::stoi(next());
    else if (a == "--repeat") repeat = std::stoi(next());
    else if (a == "--alpha") alpha = std::stod(next());
    else if (a == "--tolerance") tolerance = std::stod(next());
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (keep_freed) contactrb::keep_freed_memory();  // docs/performance.md, "Kept freed memory"
  try {
    std::optional<contact::Discretization> d;
    if (!constraint.empty()) d = contact::discretization_from_string(constraint);
    rusage before{};
    getrusage(RUSAGE_SELF, &before);
    const hf::ContactProblem problem = cases::make_problem(case_name, mu, level, d);
    rusage after_mesh{};
    getrusage(RUSAGE_SELF, &after_mesh);
    auto cpu = [](const rusage& r) {
      return static_cast<double>(r.ru_utime.tv_sec + r.ru_stime.tv_sec) +
             1e-6 * static_cast<double>(r.ru_utime.tv_usec + r.ru_stime.tv_usec);
    };
    const double mesh_cpu_s = cpu(after_mesh) - cpu(before);
    hf::HFSettings settings;
    settings.method = hf::hf_method_from_string(solver);
    settings.newton.lu = solve::sparse_lu_backend_from_string(lu);
    settings.newton.linear_solver = hf::newton_linear_solver_from_string(linear);
    if (inner > 0) settings.newton.tuning.max_inner_iterations = inner;
    settings.newton.tuning.inner_passes = hf::newton_inner_passes_from_string(passes);
    if (free_steps >= 0) settings.newton.tuning.max_free_steps = free_steps;
    if (branch_passes >= 0) settings.newton.tuning.max_branch_passes = branch_passes;
    if (branch_below >= 0.0) settings.newton.tuning.branch_passes_below = branch_below;
    if (safeguard >= 0.0) settings.newton.tuning.kacanov_safeguard = safeguard;
    if (newton_passes > 0) settings.newton.tuning.max_newton_passes = newton_passes;
    if (switch_passes > 0) settings.newton.tuning.switch_passes = switch_passes;
    if (chord >= 0) settings.newton.tuning.chord_steps = chord;
    if (linearization == "fd") {
      settings.newton.linearization.method = contact::LinearizationMethod::FiniteDifference;
    } else if (linearization != "analytic") {
      std::fprintf(stderr, "unknown --linearization %s (analytic or fd)\n", linearization.c_str());
      return 2;
    }
    if (krylov >= 0) settings.newton.tuning.krylov_max_iterations = krylov;
    settings.newton.tuning.blas_threads = threads;
    if (ordering == "cholmod") settings.newton.ordering = solve::FactorOrdering::Cholmod;
    else if (ordering == "node-metis") settings.newton.ordering = solve::FactorOrdering::NodeMetis;
    else if (ordering != "auto") {
      std::fprintf(stderr, "unknown --ordering %s (auto, cholmod or node-metis)\n", ordering.c_str());
      return 2;
    }
    settings.kacanov.alpha = alpha;
    settings.kacanov.tolerance = tolerance;
    const std::vector<int> coarse_levels = cases::sequence_levels(level, sequence, sequence_step);
    std::vector<double> setup, solve, total, coarse;
    hf::HFSolution sol;
    cases::SequenceStart start;
    for (int r = 0; r < std::max(1, repeat); ++r) {
      hf::HFSetupOptions prepare = hf::setup_options_for(settings);
      prepare.newton_analysis = prepare.newton_analysis && ahead;
      const hf::HFSolver s(problem, prepare);
      start = cases::sequence_start(cases::builtin_case_spec(case_name), cases::Mu::Constant(1, mu), coarse_levels, d,
                                    settings, s);
      sol = s.solve(settings, start.guess);
      setup.push_back(s.setup_time_s());
      total.push_back(sol.time_s + start.time_s);
      solve.push_back(sol.time_s - s.setup_time_s());
      coarse.push_back(start.time_s);
    }
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
    if (stages.empty()) stages = "-";
    auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    if (verbose) {
      const hf::NewtonTimings& tm = sol.newton_timings;
      std::fprintf(stderr, "  A_00: analysis %.4f s%s numeric factorization %.4f s (nnz(L) %ld, %d BLAS threads) z %.4f s; initial evaluation %.4f s\n",
                   tm.analyze_s, tm.analysis_ahead ? (" (beside the assembly; waited " + std::to_string(tm.analysis_wait_s) + " s)").c_str() : "",
                   tm.numeric_s, tm.factor_nonzeros, tm.blas_threads, tm.rhs_s, tm.initial_s);
      for (const auto& it : sol.newton_history) {
        std::fprintf(stderr, "  kkt %.3e merit %.3e active %d changed %d systems %d |E| %d step %g colours %d branch passes %d kacanov step %d chord %d lin %.4f s linear algebra %.4f s (G block %.4f s) krylov %d line search %.4f s\n",
                     it.residual, it.merit, it.active, it.changed, it.factorizations, it.reduced_size, it.step, it.colours, it.branch_passes, it.kacanov_step ? 1 : 0, it.chord_steps,
                     it.linearize_s, it.factorize_s, it.block_s, it.krylov, it.search_s);
      }
      if (!sol.message.empty()) std::fprintf(stderr, "  %s\n", sol.message.c_str());
    }
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const double cpu_s = (cpu(usage) - cpu(after_mesh)) / std::max(1, repeat);
    std::printf("%s,%d,%d,%zu,%s,%s,%g,%.4f,%.4f,%.4f,%d,%s,%.9g,%.9g,%.2e,%d,%.1f,%.4f,%.2f,%s,%.4f\n", case_name.c_str(), level,
                problem.mesh.num_dofs(), problem.mesh.boundaries.at(mesh::kSlaveBoundary).size() + 1, solver.c_str(),
                contact::to_string(problem.discretization), mu, median(setup), median(solve), median(total),
                sol.iterations, solve::to_string(sol.status), sol.contact_force, sol.energy, sol.kkt.max(),
                sol.active_constraints, static_cast<double>(usage.ru_maxrss) / 1024.0, cpu_s, mesh_cpu_s,
                stages.c_str(), median(coarse));
    return sol.converged ? 0 : 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_hf_scaling: %s\n", e.what());
    return 1;
  }
}
