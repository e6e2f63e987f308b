#pragma once
// Kacanov (secant) outer iteration (paper (12)) with relaxation and the stopping test (63).
// The driver sees vectors only: the caller provides one linearized step, which solves the
// saddle-point problem with K and g frozen at the previous iterate. The same driver serves
// the HF solver and the online reduced solver (Algorithm 1).
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace contactrb::solve {

struct KacanovSettings {
  double alpha = 0.3;       // relaxation: u^k = alpha u_bar + (1 - alpha) u^{k-1} (Section 6.2.2)
  double tolerance = 1e-3;  // eps_KA in (63)
  int max_iterations = 500;
};
// Throws contactrb::Error unless 0 < alpha <= 1, tolerance > 0 and max_iterations >= 1
// (all finite), naming the setting and its value.
void check_settings(const KacanovSettings& settings);

// NonFinite: a step returned NaN or inf (data whose magnitudes overflow double precision), or
// the caller found a non-finite result (energy, force); never reported as converged.
enum class KacanovStatus { Converged, MaxIterations, StepFailed, NonFinite };
const char* to_string(KacanovStatus status);
KacanovStatus kacanov_status_from_string(const std::string& name);  // throws contactrb::Error

// Stopping test (63), applied to the unrelaxed step so that it does not depend on alpha:
// max(|u_bar^k - u^{k-1}| / |u^{k-1}|, |lambda_bar^k - lambda^{k-1}| / |lambda^{k-1}|) <= eps_KA,
// with u_bar^k the linearized solution and u^{k-1} the previous relaxed iterate. At alpha = 1 it
// is (63) exactly; for alpha < 1 it is 1/alpha times stricter than (63) on the relaxed iterates.
struct KacanovIteration {
  double du = 0.0;       // |u_bar^k - u^{k-1}| / |u^{k-1}|
  double dlambda = 0.0;  // |lambda_bar^k - lambda^{k-1}| / |lambda^{k-1}|
  int step_iterations = 0;  // iterations of the inner solver (QP)
};

struct KacanovResult {
  KacanovStatus status = KacanovStatus::StepFailed;
  int iterations = 0;
  Eigen::VectorXd u;        // relaxed iterate u^k
  Eigen::VectorXd lambda;   // relaxed iterate lambda^k
  Eigen::VectorXd u_bar;    // last linearized solution (exact KKT point of the last step)
  Eigen::VectorXd lambda_bar;
  std::vector<KacanovIteration> history;
  std::string message;      // why it stopped, when not converged
};

// One linearized step: given the previous iterate (u, lambda), write the solution
// (u_bar, lambda_bar) of (12) with K, g evaluated at u. Returns false with `message` set
// when it fails; `inner_iterations` reports the inner solver's iterations.
using KacanovStep = std::function<bool(const Eigen::VectorXd& u, const Eigen::VectorXd& lambda,
                                       Eigen::VectorXd& u_bar, Eigen::VectorXd& lambda_bar,
                                       int& inner_iterations, std::string& message)>;

// Relative increment of (63); 0 when both vectors vanish, +infinity when only the previous
// one vanishes (a relative change from zero is unbounded: never counts as converged).
double relative_increment(const Eigen::VectorXd& current, const Eigen::VectorXd& previous);

KacanovResult kacanov(const KacanovStep& step, Eigen::VectorXd u0, Eigen::VectorXd lambda0,
                      const KacanovSettings& settings);

}  // namespace contactrb::solve
