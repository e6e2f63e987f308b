// One OnlineSolver on a model file, timed per query at the midpoints of n equispaced values of
// the (first) parameter's domain, with and without the error estimate: the split of a query
// between the reduced solve and its estimate (docs/performance.md, "Moving contact zone").
//   OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 build/bench/bench_registered_query MODEL.h5 [n] [repeats]
// Defaults: n = 30 points (hertz-a's verification set), 7 repeats per point. Prints, per setting,
// the median and maximum over the points of each point's median wall time, the median number of
// steps and the median estimate of |u_hf - u_rb|_A; the first query (the solver's first use) is
// reported apart.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/online/online_solver.hpp"

namespace {

using namespace contactrb;
using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

void run(const model::ReducedModel& model, const std::vector<cases::Mu>& points, int repeats, bool estimate) {
  online::OnlineSolver solver(model);
  online::OnlineSettings settings;
  settings.error_estimate = estimate;
  const auto t0 = Clock::now();
  (void)solver.solve(points.front(), settings);
  const double first = std::chrono::duration<double>(Clock::now() - t0).count();
  std::vector<double> per_point, steps, estimates;
  int failed = 0;
  for (const cases::Mu& mu : points) {
    std::vector<double> times;
    online::OnlineSolution s;
    for (int k = 0; k < repeats; ++k) {
      const auto t = Clock::now();
      s = solver.solve(mu, settings);
      times.push_back(std::chrono::duration<double>(Clock::now() - t).count());
    }
    failed += s.converged() ? 0 : 1;
    per_point.push_back(median(times));
    steps.push_back(s.iterations);
    if (s.estimate.available) estimates.push_back(s.estimate.energy);
  }
  std::printf("estimate %-3s  median %8.1f us  max %8.1f us  first query %8.1f us  steps (median) %4.1f  "
              "estimate (median) %.3e  failed %d\n",
              estimate ? "on" : "off", 1e6 * median(per_point), 1e6 * *std::max_element(per_point.begin(), per_point.end()),
              1e6 * first, median(steps), median(estimates), failed);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MODEL.h5 [points] [repeats]\n", argv[0]);
    return 2;
  }
  const int n = argc > 2 ? std::atoi(argv[2]) : 30;
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 7;
  if (n < 1 || repeats < 1) {
    std::fprintf(stderr, "points and repeats must be positive\n");
    return 2;
  }
  try {
    const model::ReducedModel model = io::read_reduced_model_file(argv[1]);
    const cases::ParameterSpec& p = model.parameters.front();
    std::vector<cases::Mu> points;
    for (int i = 0; i < n; ++i) {
      cases::Mu mu = cases::reference_mu(model.parameters);
      mu(0) = p.min + (p.max - p.min) * (i + 0.5) / n;
      points.push_back(mu);
    }
    run(model, points, repeats, false);
    run(model, points, repeats, true);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_registered_query: %s\n", e.what());
    return 1;
  }
  return 0;
}
