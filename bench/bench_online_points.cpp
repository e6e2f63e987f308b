// Online query time on a model file over a case's parameter set, without HF solves: the online
// column of bench_moving_zone (per point the median wall time of --repeats solves, default
// OnlineSettings, the estimate included; then the median and the worst over the points), with
// the reduced steps per query and the time to construct the OnlineSolver. --dump writes per point the steps, the time, the estimate and
// u_hat, lambda_hat to 17 digits (two builds or settings compared line by line).
//   build/bench/bench_online_points --model m.h5 --case hertz-3p [--set verification]
//                                   [--repeats 5] [--dump FILE] [--depth D] [--guess zero]
//                                   [--iteration accelerated|relaxed|newton] [--tolerance T]
//                                   [--max-steps K] [--estimate off] [--preconditioned off]
// --tolerance and --max-steps set the reduced iteration's stopping test (undamped steps);
// with --tolerance below reach and --max-steps K, --dump gives the iterate after K steps.
// docs/performance.md, "Moving contact zone".
#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/online/online_solver.hpp"

using namespace contactrb;

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string model, case_name, set = "verification", dump;
  int repeats = 5;
  online::OnlineSettings settings;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--model") {
      o.model = v;
    } else if (a == "--case") {
      o.case_name = v;
    } else if (a == "--set") {
      o.set = v;
    } else if (a == "--repeats") {
      o.repeats = std::stoi(v);
    } else if (a == "--depth") {
      o.settings.anderson_depth = std::stoi(v);
    } else if (a == "--guess") {
      o.settings.initial_guess = online::initial_guess_from_string(v);
    } else if (a == "--tolerance") {
      o.settings.kacanov = solve::KacanovSettings{1.0, std::stod(v), 500};
    } else if (a == "--max-steps") {
      if (!o.settings.kacanov) o.settings.kacanov = solve::KacanovSettings{1.0, 1e-8, 500};
      o.settings.kacanov->max_iterations = std::stoi(v);
    } else if (a == "--preconditioned") {
      o.settings.preconditioned = v != "off";
    } else if (a == "--estimate") {
      o.settings.error_estimate = v != "off";
    } else if (a == "--iteration") {
      o.settings.iteration = online::online_iteration_from_string(v);
    } else if (a == "--dump") {
      o.dump = v;
    } else {
      throw Error("unknown option '" + a + "'");
    }
  }
  require(!o.model.empty() && !o.case_name.empty() && o.repeats >= 1,
          "usage: bench_online_points --model FILE --case NAME [--set SET] [--repeats K] [--dump FILE] "
          "[--depth D] [--guess G] [--iteration I] [--tolerance T] [--max-steps K] [--estimate off] "
          "[--preconditioned off]");
  return o;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void dump_vector(std::ostream& os, const Eigen::VectorXd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) os << ' ' << v(i);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options opt = parse(argc, argv);
    const model::ReducedModel model = io::read_reduced_model_file(opt.model);
    const std::vector<cases::Mu> points = cases::builtin_case_spec(opt.case_name).set(opt.set);
    const auto t_build = Clock::now();
    online::OnlineSolver solver(model);
    const double build_s = std::chrono::duration<double>(Clock::now() - t_build).count();
    std::ofstream dump;
    if (!opt.dump.empty()) dump.open(opt.dump);
    dump << std::setprecision(17);
    std::vector<double> times, steps;
    int failed = 0;
    for (const cases::Mu& mu : points) {
      std::vector<double> t;
      online::OnlineSolution s;
      for (int k = 0; k < opt.repeats; ++k) {
        const auto t0 = Clock::now();
        s = solver.solve(mu, opt.settings);
        t.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
      }
      times.push_back(median(t));
      steps.push_back(s.iterations);
      failed += s.converged() ? 0 : 1;
      if (dump.is_open()) {
        dump << s.iterations << ' ' << times.back() << ' ' << s.estimate.energy;
        dump_vector(dump, s.u_hat);
        dump_vector(dump, s.lambda_hat);
        dump << '\n';
      }
    }
    std::cout << "solver built in " << 1e3 * build_s << " ms\n";
    std::cout << "points " << points.size() << ", N " << solver.N() << ", R " << solver.R() << ", failed " << failed
              << "\nonline median " << 1e6 * median(times) << " us, worst "
              << 1e6 * *std::max_element(times.begin(), times.end()) << " us\nsteps median " << median(steps)
              << ", max " << *std::max_element(steps.begin(), steps.end()) << "\n";
  } catch (const Error& e) {
    std::cerr << "bench_online_points: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
