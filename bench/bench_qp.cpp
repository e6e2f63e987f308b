// Timings of the non-negative QP (solve/nonnegative_qp.hpp) on random positive definite
// problems with about one third of the variables active at the solution (x* > 0 on two
// thirds, c = Q x* - r with r > 0 on the rest).
// Run: build/bench/bench_qp [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "contactrb/solve/nonnegative_qp.hpp"

namespace {

using contactrb::solve::NonnegativeQPSolver;
using contactrb::solve::QPResult;
using contactrb::solve::QPStatus;

struct Problem {
  Eigen::MatrixXd Q;
  Eigen::VectorXd c;
  std::vector<int> passive;  // the optimal passive set
};

Problem make_problem(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.5, 1.5);
  Eigen::MatrixXd B(n + 5, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n + 5; ++i) B(i, j) = N(rng);
  Problem p;
  p.Q = B.transpose() * B;
  p.Q = 0.5 * (p.Q + p.Q.transpose()).eval();
  Eigen::VectorXd xs = Eigen::VectorXd::Zero(n), r = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    if (i % 3 == 2) {
      r[i] = U(rng);
    } else {
      xs[i] = U(rng);
      p.passive.push_back(i);
    }
  }
  p.c = p.Q * xs - r;
  return p;
}

void BM_ColdStart(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Problem p = make_problem(n, 42);
  NonnegativeQPSolver solver;
  int iterations = 0;
  for (auto _ : state) {
    const QPResult& r = solver.solve(p.Q, p.c);
    if (r.status != QPStatus::Solved) state.SkipWithError("not solved");
    iterations = r.iterations;
    benchmark::DoNotOptimize(r.x.data());
  }
  state.counters["iterations"] = iterations;
}

void BM_WarmStartOptimalSet(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Problem p = make_problem(n, 42);
  NonnegativeQPSolver solver;
  int iterations = 0;
  for (auto _ : state) {
    const QPResult& r = solver.solve(p.Q, p.c, p.passive);
    if (r.status != QPStatus::Solved) state.SkipWithError("not solved");
    iterations = r.iterations;
    benchmark::DoNotOptimize(r.x.data());
  }
  state.counters["iterations"] = iterations;
}

// The free function (allocates its workspace and result on every call).
void BM_ColdStartFreeFunction(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Problem p = make_problem(n, 42);
  for (auto _ : state) {
    const QPResult r = contactrb::solve::solve_nonnegative_qp(p.Q, p.c);
    benchmark::DoNotOptimize(r.x.data());
  }
}

}  // namespace

BENCHMARK(BM_ColdStart)->Arg(10)->Arg(25)->Arg(50)->Arg(100)->Arg(250)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WarmStartOptimalSet)
    ->Arg(10)
    ->Arg(25)
    ->Arg(50)
    ->Arg(100)
    ->Arg(250)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ColdStartFreeFunction)->Arg(10)->Arg(25)->Arg(250)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
