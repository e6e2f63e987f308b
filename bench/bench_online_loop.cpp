// The C++ loop the Python module's Model.solve_many runs (python/src/bind_online.cpp), timed on
// its own: one OnlineSolver on a model file, queries at n equispaced points of the (first)
// parameter's domain, in order. Compare its per-query time with bench/python_online.py's
// solve_many figure on the same model (docs/python.md, "Performance").
//   CONTACTRB_BENCH_MODEL=model.h5 build/bench/bench_online_loop
// Counter per_query_us: wall time of the loop / n.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/online/online_solver.hpp"

namespace {

using namespace contactrb;

void BM_OnlineLoop(benchmark::State& state) {
  const char* path = std::getenv("CONTACTRB_BENCH_MODEL");
  if (path == nullptr) {
    state.SkipWithError("set CONTACTRB_BENCH_MODEL to a model file (contactrb offline --out ...)");
    return;
  }
  const contactrb::model::ReducedModel model = io::read_reduced_model_file(path);
  online::OnlineSolver solver(model);
  const int n = static_cast<int>(state.range(0));
  std::vector<cases::Mu> points;
  for (int i = 0; i < n; ++i) {
    cases::Mu mu = cases::reference_mu(model.parameters);
    const cases::ParameterSpec& p = model.parameters.front();
    mu(0) = p.min + (p.max - p.min) * i / (n - 1);
    points.push_back(mu);
  }
  double energy = 0.0, seconds = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    for (const cases::Mu& mu : points) energy += solver.solve(mu).energy;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  benchmark::DoNotOptimize(energy);
  state.counters["per_query_us"] = 1e6 * seconds / (static_cast<double>(n) * static_cast<double>(state.iterations()));
}
BENCHMARK(BM_OnlineLoop)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
