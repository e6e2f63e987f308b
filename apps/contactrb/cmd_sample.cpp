// `contactrb sample`: uncertainty quantification with a reduced model (docs/parallel.md,
// "Sampling"). Draws --n parameter points from --dist (online/sampling.hpp: point i depends on
// --seed and i only), answers them with online solves on --jobs threads (online/online_many.hpp)
// and, under mpirun, over the ranks (equal blocks, gathered on rank 0), then writes the
// statistics of the outputs (--out, CSV), their histograms (<stem>_histograms.csv) and a
// figure of them (<stem>.png, scripts/plot_sample.py). A query that does not converge is left
// out of the statistics and counted; the command then exits 3 unless --allow-failures.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <future>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/online/online_many.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/online/sampling.hpp"
#include "mpi_gather.hpp"
#include "mpi_world.hpp"
#include "plot_script.hpp"

namespace contactrb::app {

namespace {

// The figure's title: the distribution of each parameter, as sampled (sampling.hpp), and n.
std::string input_description(const std::vector<cases::ParameterSpec>& parameters,
                              const online::SampleDistribution& dist, std::size_t n, std::uint64_t seed) {
  std::ostringstream os;
  os << std::setprecision(6) << n << " points (seed " << seed << "): ";
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const cases::ParameterSpec& p = parameters[k];
    os << (k == 0 ? "" : ", ") << p.name;
    if (dist.kind == online::SampleDistribution::Kind::Uniform) {
      os << " uniform on [" << p.min << ", " << p.max << "]";
    } else {
      os << " normal (mean " << dist.mean[k] << ", sd " << dist.sd[k] << ") truncated to [" << p.min << ", " << p.max
         << "]";
    }
  }
  return os.str();
}

constexpr int kExitNotConverged = 3;  // as `contactrb online`

struct SampleOptions {
  std::string model;
  long long n = 0;
  std::string dist = "uniform";
  std::uint64_t seed = 1;
  int jobs = 0;  // 0: every hardware thread
  int bins = 50;
  bool no_plot = false;
  bool gaps = false;  // --gaps: max_gap and min_gap
  bool allow_failures = false;
  std::string points;  // --points FILE: every point and its outputs
  std::string out;
};

// The outputs, in the order of the files. peak_pressure needs the model's reconstruction data.
// max_gap, min_gap (--gaps): of the deformed normal gap over the slave nodes
// (OnlineSolver::surface_gap).
struct Outputs {
  std::vector<double> contact_force, peak_pressure, max_gap, min_gap, energy, estimate, iterations;
  std::vector<std::pair<std::string, std::vector<double>*>> named(bool with_peak, bool with_gaps) {
    std::vector<std::pair<std::string, std::vector<double>*>> v{{"contact_force", &contact_force}};
    if (with_peak) v.emplace_back("peak_pressure", &peak_pressure);
    if (with_gaps) {
      v.emplace_back("max_gap", &max_gap);
      v.emplace_back("min_gap", &min_gap);
    }
    v.emplace_back("energy", &energy);
    v.emplace_back("estimate", &estimate);
    v.emplace_back("iterations", &iterations);
    return v;
  }
};

std::string stem_of(const std::string& out) {
  const std::filesystem::path p(out);
  return (p.parent_path() / p.stem()).string();
}

// --points: one line per point, "index,<parameter names>,converged,<outputs>", numbers
// round-trip exact (%.17g); an output without a value (not converged) is empty.
void write_points(const std::string& path, const contactrb::model::ReducedModel& model,
                  const online::SampleDistribution& dist, std::uint64_t seed, Outputs& out, bool with_peak,
                  bool with_gaps) {
  const auto columns = out.named(with_peak, with_gaps);
  write_file_atomically(path, [&](std::ostream& os) {
    os << "index";
    for (const cases::ParameterSpec& q : model.parameters) os << ',' << q.name;
    os << ",converged";
    for (const auto& [name, column] : columns) os << ',' << name;
    os << '\n';
    char buffer[32];
    const auto number = [&](double x) {
      if (std::isfinite(x)) {
        std::snprintf(buffer, sizeof buffer, "%.17g", x);
        os << buffer;
      }
    };
    for (std::size_t i = 0; i < out.contact_force.size(); ++i) {
      os << i;
      const cases::Mu mu = online::sample_point(dist, model.parameters, seed, i);
      for (Eigen::Index k = 0; k < mu.size(); ++k) {
        os << ',';
        number(mu(k));
      }
      os << ',' << (std::isnan(out.contact_force[i]) ? 0 : 1);
      for (const auto& [name, column] : columns) {
        os << ',';
        number((*column)[i]);
      }
      os << '\n';
    }
  });
}

int run_sample(const SampleOptions& opt) {
  const std::unique_ptr<MpiWorld> world = MpiWorld::start_if_launched();
  const int rank = world ? world->rank() : 0, ranks = world ? world->size() : 1;
  require(opt.n >= 1, "--n must be >= 1 (got " + std::to_string(opt.n) + ")");
  // The outputs are held in memory for the quantiles: 40 bytes per point (4 GB at the limit).
  require(opt.n <= 100000000, "--n must be at most 100000000 (got " + std::to_string(opt.n) + ")");
  require(opt.jobs >= 0, "--jobs must be >= 0 (0: every hardware thread; got " + std::to_string(opt.jobs) + ")");
  require(opt.bins >= 1 && opt.bins <= 100000, "--bins must be in [1, 100000] (got " + std::to_string(opt.bins) + ")");
  const int jobs = opt.jobs == 0 ? online::hardware_jobs() : opt.jobs;
  const std::string hist_path = stem_of(opt.out) + "_histograms.csv";
  const std::string png_path = stem_of(opt.out) + ".png";
  check_output_file(opt.out);
  require(std::filesystem::path(opt.out).extension() == ".csv", "--out '" + opt.out + "': expected a .csv file name "
                                                                "(the histograms and the figure are written next to it)");
  std::vector<FileRole> outputs{{"--out", opt.out}, {"the histograms next to --out", hist_path}};
  if (!opt.no_plot) outputs.push_back({"the figure next to --out", png_path});
  if (!opt.points.empty()) {
    check_output_file(opt.points);
    outputs.push_back({"--points", opt.points});
  }
  check_file_roles({{"--model", opt.model}}, outputs);
  const contactrb::model::ReducedModel model = io::read_reduced_model_file(opt.model);
  const online::SampleDistribution dist = online::parse_distribution(opt.dist, model.parameters);
  const std::string script = opt.no_plot || rank != 0 ? std::string() : find_script("plot_sample.py", "use --no-plot");
  // The peak pressure max_r (Xi lambda_hat)_r on the HF rows: from the reconstruction data.
  const bool with_peak = io::has_reconstruction(opt.model);
  contactrb::model::ReducedReconstruction rec;
  if (with_peak) {
    rec = io::read_reconstruction(opt.model);
    online::check_reconstruction(model, rec);
  }
  if (world && !world->agree(true)) {
    if (rank == 0) throw Error("an MPI rank could not start the run (its error is above)");
    return 1;
  }

  const auto n = static_cast<std::size_t>(opt.n);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Outputs out;
  for (auto& [name, column] : out.named(true, true)) column->assign(n, nan);
  const auto [begin, end] = rank_block(n, rank, ranks);
  const auto t0 = std::chrono::steady_clock::now();
  std::string error;
  try {
    online::OnlineSettings settings;
    online::for_each_query(model, {}, end - begin, jobs, [&](online::OnlineSolver& solver, std::size_t j) {
      const std::size_t i = begin + j;
      const cases::Mu mu = online::sample_point(dist, model.parameters, opt.seed, i);
      const online::OnlineSolution s = solver.solve(mu, settings);
      out.iterations[i] = s.iterations;
      if (!s.converged()) return;  // NaN: left out of the statistics, counted
      out.contact_force[i] = s.contact_force;
      out.energy[i] = s.energy;
      if (s.estimate.available) out.estimate[i] = s.estimate.energy;
      if (with_peak) out.peak_pressure[i] = online::reconstruct_multipliers(rec, mu, s.lambda_hat).maxCoeff();
      if (opt.gaps) {
        const online::OnlineSolver::SurfaceGap gap = solver.surface_gap(mu, s);
        out.max_gap[i] = gap.max;
        out.min_gap[i] = gap.min;
      }
    }, 256);
  } catch (const Error& e) {
    error = e.what();
  }
  if (world) {
    const bool ok = world->agree(error.empty());
    require(error.empty(), error);
    if (!ok) {
      if (rank == 0) throw Error("another MPI rank failed (its error is above)");
      return 1;
    }
    std::vector<std::vector<double>*> columns;
    for (auto& [name, column] : out.named(true, true)) columns.push_back(column);
    gather_blocks(*world, columns);
    if (rank != 0) return 0;
  }
  require(error.empty(), error);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::size_t failures = 0;
  for (double c : out.contact_force) failures += std::isnan(c) ? 1 : 0;
  io::CsvWriter stats({"output", "count", "mean", "sd", "min", "max", "q05", "q50", "q95"});
  io::CsvWriter hist({"output", "bin", "lo", "hi", "count"});
  std::ostringstream table;
  table << std::setprecision(6);
  // The statistics of each output (a sort of its n values each, ~10 ms per 10^5): independent,
  // so on the --jobs threads, one output at a time (the same results as one after the other).
  const auto named = out.named(with_peak, opt.gaps);
  std::vector<online::OutputStats> all(named.size());
  {
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      for (std::size_t k = next++; k < named.size(); k = next++)
        all[k] = online::output_stats(named[k].first, *named[k].second, opt.bins);
    };
    std::vector<std::future<void>> helpers;
    for (int t = 1; t < jobs && static_cast<std::size_t>(t) < named.size(); ++t) helpers.push_back(std::async(std::launch::async, work));
    work();
    for (std::future<void>& h : helpers) h.get();
  }
  for (std::size_t k = 0; k < named.size(); ++k) {
    const std::string& name = named[k].first;
    const online::OutputStats& s = all[k];
    stats.add_row({name, static_cast<long long>(s.count), s.mean, s.sd, s.min, s.max, s.q05, s.q50, s.q95});
    const double width = s.histogram.size() > 1 ? (s.max - s.min) / static_cast<double>(s.histogram.size()) : 0.0;
    for (std::size_t b = 0; b < s.histogram.size(); ++b) {
      const double lo = s.min + width * static_cast<double>(b);
      const double hi = b + 1 == s.histogram.size() ? s.max : s.min + width * static_cast<double>(b + 1);
      hist.add_row({name, static_cast<long long>(b), lo, hi, static_cast<long long>(s.histogram[b])});
    }
    table << "  " << std::left << std::setw(14) << name << std::right << " mean " << s.mean << ", sd " << s.sd << ", min "
          << s.min << ", q05 " << s.q05 << ", median " << s.q50 << ", q95 " << s.q95 << ", max " << s.max << " (" << s.count
          << " values)\n";
  }
  {
    // The statistics, histograms, points and figure appear together or not at all (OutputSet):
    // the script reads the staged tables and draws into a temporary of the figure.
    const OutputLock lock(std::filesystem::path(opt.out).parent_path());
    OutputSet outputs;
    stats.write(opt.out);
    hist.write(hist_path);
    if (!opt.points.empty()) write_points(opt.points, model, dist, opt.seed, out, with_peak, opt.gaps);
    if (!script.empty()) {
      remove_stale_temporaries(png_path);
      const std::filesystem::path png_tmp = temporary_path(png_path);
      outputs.add(png_tmp, png_path);
      run_python_script(script,
                        {outputs.staged(opt.out).string(), outputs.staged(hist_path).string(), png_tmp.string(),
                         input_description(model.parameters, dist, n, opt.seed)},
                        "no file was written (--no-plot writes the statistics without the figure)");
    }
    outputs.commit();
  }
  std::cout << "sample: " << n << " points, " << opt.dist << ", seed " << opt.seed << ", " << jobs
            << (jobs == 1 ? " thread" : " threads") << (world ? " per rank, " + std::to_string(ranks) + " MPI ranks" : "")
            << "\n"
            << "failures: " << failures << " (not converged: left out of the statistics)\n"
            << std::fixed << std::setprecision(3) << "time: " << seconds << " s (" << std::setprecision(0)
            << static_cast<double>(n) / seconds << " queries/s)\n"
            << std::defaultfloat << table.str() << "wrote " << opt.out << ", " << hist_path
            << (script.empty() ? "" : ", " + png_path) << "\n";
  if (failures > 0) {
    std::cerr << "contactrb: " << (opt.allow_failures ? "warning: " : "error: ") << failures << " of " << n
              << " online solves did not converge (left out of the statistics)\n";
    return opt.allow_failures ? 0 : kExitNotConverged;
  }
  return 0;
}

}  // namespace

Command add_sample_command(CLI::App& app) {
  auto opt = std::make_shared<SampleOptions>();
  CLI::App* sub =
      app.add_subcommand("sample", "Uncertainty quantification: statistics of online answers at random parameter points");
  sub->add_option("--model", opt->model, "Reduced model file written by `contactrb offline`")->required();
  sub->add_option("--n", opt->n, "Number of points")->required();
  sub->add_option("--dist", opt->dist,
                  "uniform | normal (mean: the middle, sd: a sixth of the interval) | normal:MEAN:SD[,MEAN:SD...] "
                  "(one pair per parameter); normals truncated to the domain")
      ->capture_default_str();
  sub->add_option("--seed", opt->seed, "Seed: point i depends on the seed and i only")->capture_default_str();
  sub->add_option("--jobs,-j", opt->jobs, "Threads (per MPI rank; 0: every hardware thread)")->capture_default_str();
  sub->add_option("--bins", opt->bins, "Histogram bins")->capture_default_str();
  sub->add_flag("--no-plot", opt->no_plot, "No PNG figure (no Python needed)");
  sub->add_flag("--gaps", opt->gaps,
                "Also max_gap and min_gap: the deformed normal gap over every slave node (one more projection of "
                "the contact surface per query: about as long as the solve)");
  sub->add_flag("--allow-failures", opt->allow_failures, "Exit 0 even when some queries did not converge");
  sub->add_option("--points", opt->points, "Also a CSV of every point: index, mu, converged and the outputs");
  sub->add_option("--out", opt->out,
                  "Statistics CSV (output,count,mean,sd,min,max,q05,q50,q95); <stem>_histograms.csv and <stem>.png "
                  "next to it")
      ->required();
  return {sub, [opt] { return run_sample(*opt); }};
}

}  // namespace contactrb::app
