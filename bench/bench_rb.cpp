// Timings of the dual-cone builders (rb/): CPG (Algorithm 2) against the angle-greedy and the
// NMF (Appendix A) on synthetic "Hertz-like" multiplier snapshots
//     lambda(mu)(x) = (1 + mu) sqrt(max(0, a(mu)^2 - x^2)),  a(mu) = 0.2 + 1.5 mu,
// 51 collocation points on [-1, 1] (Lambda-norm weights |I_r|), 31 parameters mu = 0.15 + 0.01 i,
// plus the POD and EIM greedies at the same sizes. The paper (Section 5) reports CPG about ten
// times the angle-greedy time; BM_CPGOverAngle reports that ratio as the counter cpg_over_angle.
// Run: build/bench/bench_rb [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "contactrb/offline/angle_greedy.hpp"
#include "contactrb/offline/cpg.hpp"
#include "contactrb/offline/eim.hpp"
#include "contactrb/offline/nmf.hpp"
#include "contactrb/offline/pod.hpp"

namespace {

using namespace contactrb::offline;

constexpr int kPoints = 51;
constexpr int kParameters = 31;

Eigen::MatrixXd hertz_like() {
  Eigen::MatrixXd S(kPoints, kParameters);
  for (int p = 0; p < kParameters; ++p) {
    const double mu = 0.15 + 0.01 * p;
    const double a = 0.2 + 1.5 * mu;
    for (int i = 0; i < kPoints; ++i) {
      const double x = -1.0 + 2.0 * i / (kPoints - 1);
      S(i, p) = (1.0 + mu) * std::sqrt(std::max(0.0, a * a - x * x));
    }
  }
  return S;
}

Eigen::VectorXd weights() {
  const double h = 2.0 / (kPoints - 1);
  Eigen::VectorXd w = Eigen::VectorXd::Constant(kPoints, h);
  w(0) = w(kPoints - 1) = 0.5 * h;
  return w;
}

// Both greedies run to the same size R (no tolerance), so they select the same number of vectors.
DualConeSettings settings_for(int R) {
  DualConeSettings s;
  s.weights = weights();
  s.greedy.max_size = R;
  s.cone_history = false;  // angle-greedy: time the algorithm only
  return s;
}

void BM_CPG(benchmark::State& state) {
  const Eigen::MatrixXd S = hertz_like();
  const DualConeSettings s = settings_for(static_cast<int>(state.range(0)));
  double last = 0.0;
  for (auto _ : state) {
    const DualConeResult r = build_cpg(S, s);
    last = r.errors.back();
    benchmark::DoNotOptimize(r.generators.data());
  }
  state.counters["final_error"] = last;
}
BENCHMARK(BM_CPG)->Arg(5)->Arg(10)->Arg(20)->Arg(31)->Unit(benchmark::kMicrosecond);

void BM_AngleGreedy(benchmark::State& state) {
  const Eigen::MatrixXd S = hertz_like();
  const DualConeSettings s = settings_for(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const DualConeResult r = build_angle_greedy(S, s);
    benchmark::DoNotOptimize(r.generators.data());
  }
}
BENCHMARK(BM_AngleGreedy)->Arg(5)->Arg(10)->Arg(20)->Arg(31)->Unit(benchmark::kMicrosecond);

// One NMF of rank R ("truncated NMF"), 500 multiplicative updates at most.
void BM_NMF(benchmark::State& state) {
  const Eigen::MatrixXd S = hertz_like();
  NMFSettings ns;
  ns.max_iterations = 500;
  for (auto _ : state) {
    const NMFResult r = nmf(S, static_cast<int>(state.range(0)), ns);
    benchmark::DoNotOptimize(r.W.data());
  }
}
BENCHMARK(BM_NMF)->Arg(5)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

// The NMF dual cone with its history: one NMF per R = 1..R (what a tolerance-driven NMF costs).
void BM_NMFCone(benchmark::State& state) {
  const Eigen::MatrixXd S = hertz_like();
  DualConeSettings s = settings_for(static_cast<int>(state.range(0)));
  NMFSettings ns;
  ns.max_iterations = 500;
  double last = 0.0;
  for (auto _ : state) {
    const DualConeResult r = build_nmf_cone(S, s, ns);
    last = r.errors.back();
    benchmark::DoNotOptimize(r.generators.data());
  }
  state.counters["final_error"] = last;
}
BENCHMARK(BM_NMFCone)->Arg(10)->Unit(benchmark::kMillisecond);

// CPG time / angle-greedy time at the same R, measured side by side.
void BM_CPGOverAngle(benchmark::State& state) {
  const Eigen::MatrixXd S = hertz_like();
  const DualConeSettings s = settings_for(static_cast<int>(state.range(0)));
  double cpg = 0.0, angle = 0.0;
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(build_cpg(S, s).generators.data());
    auto t1 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(build_angle_greedy(S, s).generators.data());
    auto t2 = std::chrono::steady_clock::now();
    cpg += std::chrono::duration<double>(t1 - t0).count();
    angle += std::chrono::duration<double>(t2 - t1).count();
  }
  state.counters["cpg_over_angle"] = angle > 0.0 ? cpg / angle : 0.0;
}
BENCHMARK(BM_CPGOverAngle)->Arg(10)->Arg(31)->Unit(benchmark::kMicrosecond);

void BM_POD(benchmark::State& state) {
  const Eigen::MatrixXd S = hertz_like();
  PODSettings s;
  s.tolerance = 1e-6;
  for (auto _ : state) benchmark::DoNotOptimize(pod(S, s).basis.data());
}
BENCHMARK(BM_POD)->Unit(benchmark::kMicrosecond);

void BM_EIM(benchmark::State& state) {
  const Eigen::MatrixXd S = hertz_like();
  EIMSettings s;
  s.tolerance = 1e-8;
  for (auto _ : state) benchmark::DoNotOptimize(eim(S, s).Q.data());
}
BENCHMARK(BM_EIM)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
