#pragma once
// Empirical interpolation (EIM) greedy in the ell-infinity norm on a snapshot matrix
// F (rows: interpolation index set, columns: training parameters), Section 4.3 (51)-(52) and
// task (T1) of Section 5. It serves gamma (rows: constraints) and kappa (rows: flattened pairs
// (constraint, contact-surface DOF), see eim_flatten.hpp).
//   step 1: (mu_1, x_1) = argmax |F|, q_1 = f(mu_1) / f(mu_1)(x_1);
//   step m+1: r = f - I_m[f], (mu, x) = argmax |r|, q_{m+1} = r(mu) / r(mu)(x).
// B_ij = q_j(x_i) (52) is lower triangular with unit diagonal; its LU factors are kept (Remark 4).
#include <Eigen/Core>
#include <Eigen/LU>
#include <vector>

#include "contactrb/offline/greedy.hpp"

namespace contactrb::offline {

struct EIMSettings {
  // eps_EIM: stop when max_{mu, x} |r| <= tolerance (absolute) or <= tolerance * max |F|
  // (relative: to the largest |entry| of the function over the training set).
  double tolerance = 1e-6;
  bool relative = false;
  int max_size = -1;        // M_max; -1: no limit but the training set size
  // Exhausted when max |r| <= rank_tolerance * max |F| (the rest is round-off: a new function
  // would be noise and B would lose its conditioning).
  double rank_tolerance = 1e-12;
};
// Throws contactrb::Error for a negative or non-finite tolerance, max_size < -1 or a bad rank_tolerance.
void check_settings(const EIMSettings& settings);

struct EIMResult {
  GreedyStatus status = GreedyStatus::Exhausted;
  std::vector<int> magic_points;  // row indices x_1 .. x_M of F
  std::vector<int> selected;      // column (training parameter) indices mu_1 .. mu_M
  Eigen::MatrixXd Q;              // rows x M, q_j (Q(x_j, j) = 1, Q(x_i, j) = 0 for i < j)
  Eigen::MatrixXd B;              // M x M, B = Q(magic_points, :)
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;  // of B (Remark 4); empty when M = 0
  // errors[m] = max_{mu, x} |F - I_m F| on the training set, m = 0 .. M (errors[0] = max |F|);
  // each step at most doubles it (|q|_inf = 1); usually decreasing, not provably monotone.
  std::vector<double> errors;
  double threshold = 0.0;  // the absolute stopping threshold used (tolerance, or tolerance * max |F|)
  double seconds = 0.0;

  int size() const { return static_cast<int>(magic_points.size()); }
  // Coefficients phi of (51) from the values f(x_1) .. f(x_m) at the first m magic points:
  // B_m phi = values (m = values.size() <= M; m < M uses the leading block, lower triangular).
  Eigen::VectorXd interpolate(const Eigen::VectorXd& values_at_magic_points) const;
  // The interpolant Q_m phi (rows of F), m = phi.size().
  Eigen::VectorXd evaluate(const Eigen::VectorXd& coefficients) const;
  // Values of a full column f at the magic points (a convenience for tests and offline use).
  Eigen::VectorXd restrict(const Eigen::VectorXd& f) const;
};

// F: rows x P, finite. Throws contactrb::Error for invalid input.
EIMResult eim(const Eigen::MatrixXd& F, const EIMSettings& settings = {});

// The evaluate / extend steps of the EIM greedy: evaluate() = max_x |r(mu, x)| per column;
// extend(mu) picks x = argmax_x |r(mu, x)| (first index on ties) and updates all residuals by
// r <- r - q r(x, :). Borrows nothing (keeps the residual matrix).
class EIMProblem final : public GreedyProblem {
 public:
  explicit EIMProblem(const Eigen::MatrixXd& F);
  int training_size() const override { return static_cast<int>(residual_.cols()); }
  Eigen::VectorXd evaluate() override;
  void extend(int index) override;
  Eigen::VectorXd reference_norms() const override { return norms_; }

  const std::vector<int>& magic_points() const { return magic_; }
  const Eigen::MatrixXd& basis() const { return Q_; }

 private:
  Eigen::MatrixXd residual_;
  Eigen::MatrixXd Q_;
  Eigen::VectorXd norms_;  // max_x |f(mu, x)|
  std::vector<int> magic_;
};

}  // namespace contactrb::offline
