#include "contactrb/offline/greedy.hpp"

#include <chrono>
#include <cmath>
#include <string>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::offline {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

Eigen::VectorXd relative(const Eigen::VectorXd& errors, const Eigen::VectorXd& norms) {
  Eigen::VectorXd rel = Eigen::VectorXd::Zero(errors.size());
  for (Eigen::Index i = 0; i < errors.size(); ++i)
    if (norms(i) > 0.0) rel(i) = errors(i) / norms(i);
  return rel;
}

// First index of the maximum (NaN-free input).
Eigen::Index argmax(const Eigen::VectorXd& v) {
  Eigen::Index best = 0;
  for (Eigen::Index i = 1; i < v.size(); ++i)
    if (v(i) > v(best)) best = i;
  return best;
}
}  // namespace

const char* to_string(GreedyStatus status) {
  switch (status) {
    case GreedyStatus::ToleranceReached: return "tolerance reached";
    case GreedyStatus::MaxSize: return "maximum size reached";
    case GreedyStatus::Exhausted: return "training set exhausted";
  }
  return "unknown";
}

GreedyStatus greedy_status_from_string(const std::string& name) {
  using enum GreedyStatus;
  return enum_from_string(name, "greedy status", std::array{ToleranceReached, MaxSize, Exhausted});
}

void check_settings(const GreedySettings& s) {
  require(std::isfinite(s.tolerance) && s.tolerance >= 0.0,
          "greedy: tolerance must be finite and >= 0, got " + number_text(s.tolerance));
  require(s.max_size >= -1, "greedy: max_size must be >= -1 (-1: no limit), got " + std::to_string(s.max_size));
  require(std::isfinite(s.exhaustion_tolerance) && s.exhaustion_tolerance >= 0.0,
          "greedy: exhaustion_tolerance must be finite and >= 0, got " + number_text(s.exhaustion_tolerance));
}

GreedyResult run_greedy(GreedyProblem& problem, const GreedySettings& settings) {
  check_settings(settings);
  const auto t_start = Clock::now();
  GreedyResult result;
  const int P = problem.training_size();
  const Eigen::VectorXd norms = problem.reference_norms();
  require(norms.size() == P, "greedy: reference_norms has size " + std::to_string(norms.size()) +
                                 " but the training set has size " + std::to_string(P));

  auto t0 = Clock::now();
  Eigen::VectorXd errors = problem.evaluate();
  result.evaluate_seconds += since(t0);
  require(errors.size() == P && errors.allFinite(),
          "greedy: evaluate() returned " + std::to_string(errors.size()) + " errors (must be " +
              std::to_string(P) + " finite values)");
  const double initial = P > 0 ? errors.maxCoeff() : 0.0;

  while (true) {
    const Eigen::VectorXd rel = relative(errors, norms);
    const double max_abs = P > 0 ? errors.maxCoeff() : 0.0;
    const double max_rel = P > 0 ? rel.maxCoeff() : 0.0;
    result.max_errors.push_back(max_abs);
    result.max_relative_errors.push_back(max_rel);
    const Eigen::VectorXd& criterion = settings.relative ? rel : errors;
    const double max_crit = settings.relative ? max_rel : max_abs;
    const int n = static_cast<int>(result.selected.size());
    if (max_crit <= settings.tolerance) {
      result.status = GreedyStatus::ToleranceReached;
      break;
    }
    if (settings.max_size >= 0 && n >= settings.max_size) {
      result.status = GreedyStatus::MaxSize;
      break;
    }
    if (P == 0 || n >= P || max_abs <= settings.exhaustion_tolerance * initial) {
      result.status = GreedyStatus::Exhausted;
      break;
    }
    // In relative mode every error of the empty approximation is 1 (the argmax would be index 0):
    // the first pick is argmax of the absolute error, (56) of Algorithm 2.
    const int next = static_cast<int>(argmax(settings.relative && n == 0 ? errors : criterion));
    t0 = Clock::now();
    problem.extend(next);
    result.extend_seconds += since(t0);
    result.selected.push_back(next);
    t0 = Clock::now();
    errors = problem.evaluate();
    result.evaluate_seconds += since(t0);
    require(errors.size() == P && errors.allFinite(), "greedy: evaluate() returned non-finite errors");
  }
  result.seconds = since(t_start);
  return result;
}

}  // namespace contactrb::offline
