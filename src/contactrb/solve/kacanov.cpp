#include "contactrb/solve/kacanov.hpp"

#include <cmath>
#include <sstream>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::solve {

void check_settings(const KacanovSettings& s) {
  require(std::isfinite(s.alpha) && s.alpha > 0.0 && s.alpha <= 1.0,
          "Kacanov relaxation alpha must be in (0, 1] (got " + number_text(s.alpha) + ")");
  require(std::isfinite(s.tolerance) && s.tolerance > 0.0,
          "Kacanov tolerance must be > 0 (got " + number_text(s.tolerance) + ")");
  require(s.max_iterations >= 1,
          "Kacanov max_iterations must be >= 1 (got " + std::to_string(s.max_iterations) + ")");
}

const char* to_string(KacanovStatus status) {
  switch (status) {
    case KacanovStatus::Converged: return "converged";
    case KacanovStatus::MaxIterations: return "max_iterations";
    case KacanovStatus::StepFailed: return "step_failed";
    case KacanovStatus::NonFinite: return "non_finite";
  }
  return "unknown";
}

KacanovStatus kacanov_status_from_string(const std::string& name) {
  using enum KacanovStatus;
  return enum_from_string(name, "Kacanov status", std::array{Converged, MaxIterations, StepFailed, NonFinite});
}

double relative_increment(const Eigen::VectorXd& current, const Eigen::VectorXd& previous) {
  const double diff = (current - previous).norm();
  const double ref = previous.norm();
  if (diff == 0.0) return 0.0;
  // A change away from a zero vector is an infinite relative change: never "converged" (an
  // absolute fallback would depend on the units, and on alpha through the relaxed iterate).
  return ref > 0.0 ? diff / ref : INFINITY;
}

KacanovResult kacanov(const KacanovStep& step, Eigen::VectorXd u, Eigen::VectorXd lambda,
                      const KacanovSettings& settings) {
  check_settings(settings);
  KacanovResult result;
  const double a = settings.alpha;
  for (int k = 1; k <= settings.max_iterations; ++k) {
    KacanovIteration it;
    std::string message;
    if (!step(u, lambda, result.u_bar, result.lambda_bar, it.step_iterations, message)) {
      result.status = KacanovStatus::StepFailed;
      result.iterations = k;
      result.u = std::move(u);
      result.lambda = std::move(lambda);
      result.message = "Kacanov iteration " + std::to_string(k) + " failed: " + message;
      return result;
    }
    // A NaN increment fails every comparison, so max(du, NaN) could pass the test below: a
    // non-finite step ends the iteration with its own status instead.
    if (!result.u_bar.allFinite() || !result.lambda_bar.allFinite()) {
      result.status = KacanovStatus::NonFinite;
      result.iterations = k;
      result.u = std::move(u);
      result.lambda = std::move(lambda);
      result.message = std::string("Kacanov iteration ") + std::to_string(k) + ": the linearized solution is not finite (" +
                       (result.u_bar.allFinite() ? "multipliers" : "displacement") +
                       "): the data overflow double precision";
      return result;
    }
    // (63) on the UNRELAXED step: |u_bar^k - u^{k-1}| / |u^{k-1}| (same for lambda). The relaxed
    // increment u^k - u^{k-1} = alpha (u_bar^k - u^{k-1}) is alpha times smaller, so testing it
    // would make the test easier as alpha falls (at alpha = 1e-4 it stopped after one step).
    const bool same_size = lambda.size() == result.lambda_bar.size();
    it.du = relative_increment(result.u_bar, u);
    it.dlambda = same_size ? relative_increment(result.lambda_bar, lambda) : INFINITY;
    result.history.push_back(it);
    Eigen::VectorXd u_new = a * result.u_bar + (1.0 - a) * u;
    Eigen::VectorXd lambda_new = same_size ? Eigen::VectorXd(a * result.lambda_bar + (1.0 - a) * lambda)
                                           : Eigen::VectorXd(a * result.lambda_bar);
    u = std::move(u_new);
    lambda = std::move(lambda_new);
    if (std::max(it.du, it.dlambda) <= settings.tolerance) {
      result.status = KacanovStatus::Converged;
      result.iterations = k;
      result.u = std::move(u);
      result.lambda = std::move(lambda);
      return result;
    }
  }
  const KacanovIteration& last = result.history.back();
  std::ostringstream os;
  os << "Kacanov did not converge in " << settings.max_iterations
     << " iterations (last relative increments: displacement " << last.du << ", multipliers "
     << last.dlambda << ", tolerance " << settings.tolerance << ")";
  result.status = KacanovStatus::MaxIterations;
  result.iterations = settings.max_iterations;
  result.u = std::move(u);
  result.lambda = std::move(lambda);
  result.message = os.str();
  return result;
}

}  // namespace contactrb::solve
