// High-fidelity contact solver figures (Kacanov on the paper's Hertz meshes; docs/validation.md, "Hertz"):
//  - BM_HertzB: wall time and Kacanov iterations of hertz-b at the paper's Table 1-2
//    parameter values, for mesh levels 1 (about 1604 DOFs) and 2 (about 3364), both
//    constraint discretizations, alpha = 0.3 (paper) and alpha = 1.
//  - BM_HertzASize: wall time per solve against mesh size (levels 0..5), paper settings.
// Iterations are reported as counters; run with --benchmark_counters_tabular=true.
#include <benchmark/benchmark.h>

#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/hf/hf_solver.hpp"

using namespace contactrb;

namespace {
void BM_HertzB(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  const double mu = static_cast<double>(state.range(1)) / 100.0;
  const auto d = state.range(2) == 0 ? contact::Discretization::Collocation : contact::Discretization::LAC;
  hf::HFSettings s;
  s.kacanov.alpha = static_cast<double>(state.range(3)) / 10.0;
  const hf::ContactProblem problem = cases::make_problem("hertz-b", mu, level, d);
  hf::HFSolution sol;
  for (auto _ : state) {
    sol = hf::HFSolver(problem).solve(s);
    benchmark::DoNotOptimize(sol.energy);
  }
  state.counters["dofs"] = problem.mesh.num_dofs();
  state.counters["iterations"] = sol.iterations;
  state.counters["converged"] = sol.converged ? 1 : 0;
  state.SetLabel(std::string(contact::to_string(d)));
}

void BM_HertzASize(benchmark::State& state) {
  const hf::ContactProblem problem = cases::make_problem("hertz-a", 0.3, static_cast<int>(state.range(0)));
  hf::HFSolution sol;
  double setup = 0.0;
  for (auto _ : state) {
    const hf::HFSolver solver(problem);
    sol = solver.solve();
    setup = solver.setup_time_s();
    benchmark::DoNotOptimize(sol.energy);
  }
  state.counters["dofs"] = problem.mesh.num_dofs();
  state.counters["iterations"] = sol.iterations;
  state.counters["setup_ms"] = setup * 1e3;
}
}  // namespace

BENCHMARK(BM_HertzB)
    ->ArgsProduct({{1, 2}, {90, 95, 105, 112}, {0, 1}, {3, 10}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK(BM_HertzASize)->DenseRange(0, 5)->Unit(benchmark::kMillisecond)->Iterations(3);

BENCHMARK_MAIN();
