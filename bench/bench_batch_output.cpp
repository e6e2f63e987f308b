// Per-line cost of the `online --batch` output beyond the solve (docs/performance.md, "Batch and
// sampling"). One answered line of
// realistic sizes (N reduced DOFs, R multipliers) is written again and again to /dev/null:
//   BM_Json  the JSON line as cmd_online.cpp builds it (nlohmann::json object with u_hat,
//            lambda_hat and the estimate's parts, dumped, newline; no flush: the flush per line
//            of the JSON mode is a write(2) on top)
//   BM_Csv   io::CsvBatchWriter::write (--format csv)
//   BM_Npy   io::NpyBatchWriter::write (--format npy; the final write of the array is amortized
//            by the BM_NpyFinish figure per row)
// Arguments: N, R.  build/bench/bench_batch_output
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "contactrb/io/batch_table.hpp"

namespace {

using contactrb::io::BatchRow;

BatchRow sample_row(int k) {
  BatchRow r;
  r.line = k;
  r.answered = true;
  r.mu = Eigen::VectorXd::Constant(1, 0.3 + 1e-7 * k);
  r.status = 0;
  r.status_name = "converged";
  r.iterations = 9;
  r.energy = 0.12848609565024205 + 1e-9 * k;
  r.contact_force = 1.4726845965697068;
  r.has_estimate = true;
  r.estimate = 0.00222509391732218;
  return r;
}

nlohmann::json to_json(const Eigen::VectorXd& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v(i));
  return a;
}

void BM_Json(benchmark::State& state) {
  const auto N = state.range(0), R = state.range(1);
  const Eigen::VectorXd u = Eigen::VectorXd::Random(N), lambda = Eigen::VectorXd::Random(R);
  std::ofstream out("/dev/null");
  int k = 0;
  for (auto _ : state) {
    const BatchRow r = sample_row(++k);
    nlohmann::json j = {{"line", k}};
    j["mu"] = r.mu(0);
    j["converged"] = true;
    j["status"] = r.status_name;
    j["iterations"] = r.iterations;
    j["energy"] = r.energy;
    j["contact_force"] = r.contact_force;
    j["time_s"] = 1.5e-5;
    j["sizes"] = {{"N", N}, {"R", R}, {"Mk", 6}, {"Mg", 5}};
    j["estimate"] = {{"energy", r.estimate},  {"residual", 1e-3},     {"coercivity", 1.0}, {"violation", 1e-9},
                     {"complementarity", 1e-17}, {"multiplier_norm", 1.9}, {"eim_residual", 1e-17},
                     {"eim_slack", 1e-18}};
    j["u_hat"] = to_json(u);
    j["lambda_hat"] = to_json(lambda);
    out << j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_Csv(benchmark::State& state) {
  std::ofstream out("/dev/null");
  contactrb::io::CsvBatchWriter w(out, {"imposed displacement"});
  int k = 0;
  for (auto _ : state) w.write(sample_row(++k));
  state.SetItemsProcessed(state.iterations());
}

void BM_Npy(benchmark::State& state) {
  contactrb::io::NpyBatchWriter w(1);
  int k = 0;
  for (auto _ : state) w.write(sample_row(++k));
  state.SetItemsProcessed(state.iterations());
}

// finish() of 100000 rows, per row.
void BM_NpyFinish(benchmark::State& state) {
  contactrb::io::NpyBatchWriter w(1);
  constexpr int kRows = 100000;
  for (int k = 0; k < kRows; ++k) w.write(sample_row(k));
  std::ofstream out("/dev/null", std::ios::binary);
  for (auto _ : state) w.finish(out);
  state.SetItemsProcessed(state.iterations() * kRows);
}

}  // namespace

BENCHMARK(BM_Json)->Args({12, 10})->Args({40, 30});
BENCHMARK(BM_Csv);
BENCHMARK(BM_Npy);
BENCHMARK(BM_NpyFinish);
BENCHMARK_MAIN();
