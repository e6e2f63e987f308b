// Online query time (docs/performance.md, "Online query").
// Per case (hertz-a, hertz-b, ring-block): HF snapshots on the training and verification sets
// (HF settings: the paper's alpha = 0.3, eps_KA = 1e-3), a reduced model at the paper's
// tolerances (eps_POD 1e-5, eps_DU 1e-4, eps_EIM^k 1e-2, eps_EIM^g 1e-3, CPG; "/paper") and
// one with the paper's cone at the former default tolerances ("/cpg": CPG, eps_POD 3e-5 relative; the
// row cone, the default, is timed by bench_moving_zone), then online queries over the verification set. Reported counters:
//   median_us      median over the verification set of the per-mu median CPU time of one
//                  query (CLOCK_THREAD_CPUTIME_ID: the machine is shared; repeated queries)
//   kacanov_it     median reduced Kacanov iterations per query
//   err_u          max over the verification set of |u_RB - u_HF| / |u_HF| (Euclidean, all DOFs)
//   e_press        max over the verification set of the relative L2(Gamma^c) pressure error
//                  |lambda_RB - lambda_HF|_Lambda / |lambda_HF|_Lambda (weights |I_r| of the snapshot)
//   e_force        max relative error of the total contact force sum_r |I_r| lambda_r
//   dev_u          max over the verification set of |u_hat - u_hat*| / |u_hat*|, u_hat* the
//                  reduced fixed point (relaxed iteration to eps_KA = 1e-10): the Kacanov error
//   N, R, Mk, Mg   the model's sizes
//   median_us_noest  the same queries without the a posteriori estimate
//                  (OnlineSettings::error_estimate = false), interleaved with the timed ones so
//                  that both see the same machine load; est_cost = median_us / median_us_noest - 1
//   eff_min, eff_med, eff_max  effectivity of the estimate, Delta_u / |u_RB - u_HF|_A(mu), over the
//                  verification set
// Variants: reference:0 the default OnlineSettings (accelerated iteration), reference:1 the
// relaxed iteration at the HF snapshots' alpha (OnlineIteration::Relaxed, the paper's (12));
// "/nosup": the model without supremizers (OfflineSettings::supremizers = false, the POD basis only).
// Snapshots take about a minute per case on 2 cores; set CONTACTRB_BENCH_CACHE=<dir> to keep
// them as snapshot files between runs.
//   build/bench/bench_online [--benchmark_filter=hertz-b]
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/theta.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

namespace {

using namespace contactrb;

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

io::SnapshotSet snapshots(const std::string& name, const std::string& set_name) {
  const char* cache = std::getenv("CONTACTRB_BENCH_CACHE");
  std::string path;
  if (cache != nullptr && *cache != '\0') {
    path = std::string(cache) + "/" + name + "-" + set_name + ".h5";
    if (std::filesystem::exists(path)) return io::read_snapshot_file(path);
  }
  contactrb::offline::SnapshotRunOptions options;
  options.jobs = 2;
  io::SnapshotSet set = contactrb::offline::generate_snapshots(
      contactrb::offline::make_snapshot_request(cases::builtin_case_spec(name), set_name), options);
  if (!path.empty()) {
    std::filesystem::create_directories(cache);
    io::write_snapshot_file(set, path);
  }
  return set;
}

struct CaseData {
  io::SnapshotSet verification;
  contactrb::offline::OfflineResult offline;
  cases::AffineTerms terms;  // for |u_RB - u_HF|_A(mu), the error the estimate bounds
};

// paper: the paper's tolerances; otherwise CPG at the default tolerances but eps_POD 3e-5.
const CaseData& case_data(const std::string& name, bool paper, bool supremizers) {
  static std::map<std::string, std::unique_ptr<CaseData>> cache;
  static std::map<std::string, io::SnapshotSet> training;
  auto& slot = cache[name + (paper ? "/paper" : "/cpg") + (supremizers ? "" : "/nosup")];
  if (!slot) {
    slot = std::make_unique<CaseData>();
    if (training.count(name) == 0) training[name] = snapshots(name, "training");
    slot->verification = snapshots(name, "verification");
    contactrb::offline::OfflineSettings s;
    s.supremizers = supremizers;
    s.dual_method = contactrb::offline::DualConeMethod::CPG;
    s.eps_pod = 3e-5;
    if (paper) {
      s.set_absolute();  // the paper's tolerances, read as absolute
      s.eps_pod = 1e-5;
      s.eps_du = 1e-4;
      s.eps_eim_k = 1e-2;
      s.eps_eim_g = 1e-3;
    }
    slot->offline = contactrb::offline::build_reduced_model(training[name], cases::builtin_case_spec(name), s);
    const cases::CaseSpec spec = cases::builtin_case_spec(name);
    slot->terms = cases::assemble_affine_terms(spec, cases::reference_mesh(spec, training[name].level));
  }
  return *slot;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void BM_OnlineQuery(benchmark::State& state, const std::string& name, bool paper, bool supremizers) {
  const CaseData& d = case_data(name, paper, supremizers);
  const model::ReducedModel& m = d.offline.model;
  online::OnlineSolver solver(m);
  online::OnlineSettings settings;
  if (state.range(0) == 1) {
    settings.kacanov = solve::KacanovSettings{m.kacanov_alpha, m.kacanov_tolerance, m.kacanov_max_iterations};
    settings.iteration = online::OnlineIteration::Relaxed;
  }
  const auto& snaps = d.verification.snapshots;
  const std::size_t P = snaps.size();
  std::vector<std::vector<double>> times(P);
  std::vector<double> iterations(P, 0.0);
  double err_u = 0.0, e_press = 0.0, e_force = 0.0, dev_u = 0.0;
  std::vector<double> effectivity;
  int failures = 0;
  // The fixed point itself: the relaxed iteration at the HF alpha to eps_KA = 1e-10.
  online::OnlineSettings tight;
  tight.kacanov = solve::KacanovSettings{m.kacanov_alpha, 1e-10, 10000};
  tight.iteration = online::OnlineIteration::Relaxed;
  // Accuracy against HF, once per mu (outside the timed loop).
  for (std::size_t p = 0; p < P; ++p) {
    const online::OnlineSolution sol = solver.solve(snaps[p].mu, settings);
    if (!sol.converged()) ++failures;
    iterations[p] = sol.iterations;
    const online::OnlineSolution fixed_point = solver.solve(snaps[p].mu, tight);
    dev_u = std::max(dev_u, (sol.u_hat - fixed_point.u_hat).norm() / fixed_point.u_hat.norm());
    const Eigen::VectorXd u = online::reconstruct_displacement(d.offline.reconstruction, snaps[p].mu, sol.u_hat);
    const Eigen::VectorXd l = online::reconstruct_multipliers(d.offline.reconstruction, snaps[p].mu, sol.lambda_hat);
    err_u = std::max(err_u, (u - snaps[p].u).norm() / snaps[p].u.norm());
    const Eigen::VectorXd& lh = snaps[p].lambda;
    const Eigen::VectorXd& w = snaps[p].weight;
    e_press = std::max(e_press, std::sqrt(w.dot((l - lh).cwiseAbs2()) / w.dot(lh.cwiseAbs2())));
    e_force = std::max(e_force, std::abs(w.dot(l) - w.dot(lh)) / std::abs(w.dot(lh)));
    if (sol.converged() && sol.estimate.available) {
      const auto A = cases::combine(d.terms.A, cases::evaluate(m.thetas.a, snaps[p].mu));
      const Eigen::VectorXd e = u - snaps[p].u;
      const double err_A = std::sqrt(std::max(0.0, e.dot(A * e)));
      if (err_A > 0.0) effectivity.push_back(sol.estimate.energy / err_A);
    }
  }
  online::OnlineSettings no_estimate = settings;
  no_estimate.error_estimate = false;
  std::vector<std::vector<double>> times_noest(P);
  std::size_t q = 0;
  for (auto _ : state) {
    const std::size_t p = q++ % P;
    const double t0 = thread_cpu_seconds();
    const online::OnlineSolution sol = solver.solve(snaps[p].mu, settings);
    const double t1 = thread_cpu_seconds();
    benchmark::DoNotOptimize(sol.u_hat.data());
    times[p].push_back(t1 - t0);
    const double t2 = thread_cpu_seconds();
    const online::OnlineSolution bare = solver.solve(snaps[p].mu, no_estimate);
    const double t3 = thread_cpu_seconds();
    benchmark::DoNotOptimize(bare.u_hat.data());
    times_noest[p].push_back(t3 - t2);
  }
  std::vector<double> per_mu;
  for (const auto& t : times) {
    if (!t.empty()) per_mu.push_back(median(t));
  }
  std::vector<double> per_mu_noest;
  for (const auto& t : times_noest) {
    if (!t.empty()) per_mu_noest.push_back(median(t));
  }
  state.counters["median_us"] = 1e6 * median(per_mu);
  state.counters["median_us_noest"] = 1e6 * median(per_mu_noest);
  state.counters["est_cost"] = median(per_mu) / median(per_mu_noest) - 1.0;
  std::sort(effectivity.begin(), effectivity.end());
  state.counters["eff_min"] = effectivity.empty() ? 0.0 : effectivity.front();
  state.counters["eff_med"] = median(effectivity);
  state.counters["eff_max"] = effectivity.empty() ? 0.0 : effectivity.back();
  state.counters["kacanov_it"] = median(iterations);
  state.counters["err_u"] = err_u;
  state.counters["e_press"] = e_press;
  state.counters["e_force"] = e_force;
  state.counters["dev_u"] = dev_u;
  state.counters["failures"] = failures;
  state.counters["N"] = solver.N();
  state.counters["R"] = solver.R();
  state.counters["Mk"] = solver.Mk();
  state.counters["Mg"] = solver.Mg();
}

void register_all() {
  for (const char* name : {"hertz-a", "hertz-b", "ring-block"}) {
    for (const bool paper : {true, false}) {
      for (const bool sup : {true, false}) {
        const std::string label =
            std::string("BM_OnlineQuery/") + name + (paper ? "/paper" : "/cpg") + (sup ? "" : "/nosup");
        benchmark::RegisterBenchmark(label.c_str(),
                                     [name, paper, sup](benchmark::State& s) { BM_OnlineQuery(s, name, paper, sup); })
            ->ArgName("reference")
            ->Arg(0)
            ->Arg(1)
            ->MeasureProcessCPUTime()
            ->Unit(benchmark::kMicrosecond)
            ->MinTime(1.0);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
