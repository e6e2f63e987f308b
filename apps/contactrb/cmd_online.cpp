// `contactrb online`: reduced solves (paper Algorithm 1) from a model file written by
// `contactrb offline` (docs/user-guide.md, "online"). One --mu: one JSON object on stdout.
// --batch FILE (or - for stdin): one mu per line, one JSON line per input line, in order; a bad
// line (not a number, outside the domain) is answered by {"line": k, "error": "..."} and the
// others are still answered. The model is loaded and the solver set up once.
// Exit codes: 0 all answered and converged; 1 a user error (or, in batch mode, some bad line);
// 3 some solve did not converge (and, in batch mode, no bad line).
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "commands.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/rb/online_solver.hpp"
#include "contactrb/rb/reduced_model.hpp"

namespace contactrb::app {

namespace {

constexpr int kExitNotConverged = 3;

struct OnlineOptions {
  std::string model;
  std::optional<double> mu;
  std::string batch;
  int n = -1, r = -1, mk = -1, mg = -1;
  std::optional<double> alpha;
  std::optional<double> tolerance;
};

nlohmann::json to_json(const Eigen::VectorXd& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v(i));
  return a;
}

nlohmann::json solution_json(double mu, const rb::OnlineSolver& solver, const rb::OnlineSolution& s) {
  nlohmann::json j;
  j["mu"] = mu;
  j["converged"] = s.converged();
  j["status"] = solve::to_string(s.status);
  if (!s.message.empty()) j["message"] = s.message;
  j["iterations"] = s.iterations;
  j["energy"] = s.energy;
  j["contact_force"] = s.contact_force;
  j["time_s"] = s.time_s;
  j["sizes"] = {{"N", solver.N()}, {"R", solver.R()}, {"Mk", solver.Mk()}, {"Mg", solver.Mg()}};
  j["u_hat"] = to_json(s.u_hat);
  j["lambda_hat"] = to_json(s.lambda_hat);
  return j;
}

// A batch line as a number: surrounding blanks allowed, nothing else. Throws Error.
double parse_mu(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  require(first != std::string::npos, "empty line (expected one parameter value)");
  const auto last = line.find_last_not_of(" \t\r");
  const std::string text = line.substr(first, last - first + 1);
  errno = 0;
  char* end = nullptr;
  const double mu = std::strtod(text.c_str(), &end);
  require(end != text.c_str() && *end == '\0' && errno != ERANGE, "'" + text + "' is not a number");
  require(!std::isnan(mu), "'" + text + "' is not a number (NaN)");
  return mu;
}

int run_batch(const OnlineOptions& opt, rb::OnlineSolver& solver, const rb::OnlineSettings& settings) {
  std::ifstream file;
  std::istream* in = &std::cin;
  if (opt.batch != "-") {
    file.open(opt.batch);
    require(file.good(), "cannot open batch file '" + opt.batch + "'");
    in = &file;
  }
  int bad = 0, not_converged = 0, k = 0;
  std::string line;
  while (std::getline(*in, line)) {
    ++k;
    nlohmann::json j;
    try {
      const double mu = parse_mu(line);
      const rb::OnlineSolution s = solver.solve(mu, settings);
      j = {{"line", k}};
      j.update(solution_json(mu, solver, s));
      if (!s.converged()) ++not_converged;
    } catch (const Error& e) {
      j = {{"line", k}, {"error", e.what()}};
      ++bad;
    }
    std::cout << j.dump() << std::endl;  // flushed: answers stream through pipes
  }
  if (bad > 0) {
    std::cerr << "contactrb: error: " << bad << " of " << k << " batch lines could not be answered\n";
    return 1;
  }
  if (not_converged > 0) {
    std::cerr << "contactrb: error: " << not_converged << " of " << k << " online solves did not converge\n";
    return kExitNotConverged;
  }
  return 0;
}

int run_online(const OnlineOptions& opt) {
  require(opt.n == -1 || opt.n >= 1, "--n must be >= 1 (got " + std::to_string(opt.n) + ")");
  require(opt.r == -1 || opt.r >= 0, "--r must be >= 0 (got " + std::to_string(opt.r) + ")");
  require(opt.mk == -1 || opt.mk >= 0, "--mk must be >= 0 (got " + std::to_string(opt.mk) + ")");
  require(opt.mg == -1 || opt.mg >= 0, "--mg must be >= 0 (got " + std::to_string(opt.mg) + ")");
  const rb::ReducedModel model = io::read_reduced_model_file(opt.model);
  const auto above = [&opt](const char* flag, int value, int max) {
    require(value <= max, std::string(flag) + " = " + std::to_string(value) + " is above the maximum " +
                              std::to_string(max) + " stored in '" + opt.model + "'");
  };
  above("--n", opt.n, model.N_max);
  above("--r", opt.r, model.R_max);
  above("--mk", opt.mk, model.Mk_max);
  above("--mg", opt.mg, model.Mg_max);
  rb::OnlineSettings settings;
  if (opt.alpha || opt.tolerance) {
    solve::KacanovSettings k{model.kacanov_alpha, model.kacanov_tolerance, model.kacanov_max_iterations};
    if (opt.alpha) k.alpha = *opt.alpha;
    if (opt.tolerance) k.tolerance = *opt.tolerance;
    solve::check_settings(k);
    settings.kacanov = k;
  }
  rb::OnlineSolver solver(model, rb::OnlineSizes{opt.n, opt.r, opt.mk, opt.mg});
  if (!opt.mu) {
    require(!opt.batch.empty(), "--batch needs a file name, or - for stdin");
    return run_batch(opt, solver, settings);
  }

  const rb::OnlineSolution s = solver.solve(*opt.mu, settings);
  std::cout << solution_json(*opt.mu, solver, s).dump() << "\n";
  if (!s.converged()) {
    std::cerr << "contactrb: error: " << s.message << "\n";
    return kExitNotConverged;
  }
  return 0;
}

}  // namespace

Command add_online_command(CLI::App& app) {
  auto opt = std::make_shared<OnlineOptions>();
  CLI::App* sub = app.add_subcommand("online", "Reduced solves from a model file (one --mu, or --batch for many)");
  sub->add_option("--model", opt->model, "Reduced model file written by `contactrb offline`")->required();
  CLI::Option_group* what = sub->add_option_group("query", "Parameter values (exactly one)");
  what->add_option("--mu", opt->mu, "One parameter value (inside the model's domain)");
  what->add_option("--batch", opt->batch, "File with one parameter value per line, or - for stdin");
  what->require_option(1);
  sub->add_option("--n", opt->n, "Primal size N (default: the model's N_max)");
  sub->add_option("--r", opt->r, "Dual size R (default: R_max)");
  sub->add_option("--mk", opt->mk, "EIM size of kappa (default: Mk_max)");
  sub->add_option("--mg", opt->mg, "EIM size of gamma (default: Mg_max)");
  sub->add_option("--alpha", opt->alpha, "Kacanov relaxation in (0, 1] (default: the snapshots')");
  sub->add_option("--tol", opt->tolerance, "Kacanov tolerance eps_KA, > 0 (default: the snapshots')");
  return {sub, [opt] { return run_online(*opt); }};
}

}  // namespace contactrb::app
