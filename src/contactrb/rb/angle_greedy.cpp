#include "contactrb/rb/angle_greedy.hpp"

#include <chrono>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/rb/cone_projection.hpp"
#include "contactrb/rb/cpg.hpp"

namespace contactrb::rb {

namespace {
// A selected residual below this fraction of its snapshot's norm is round-off: the snapshot
// already lies in W_n and adds no direction (it is still kept as a generator).
constexpr double kRoundoffResidual = 1e-14;
}  // namespace

AngleGreedyProblem::AngleGreedyProblem(const Eigen::MatrixXd& snapshots, const Eigen::VectorXd& weights)
    : snapshots_(snapshots), weights_(weights), residuals_(snapshots), basis_(snapshots.rows(), 0), generators_(snapshots.rows(), 0),
      norms_(snapshots.cols()) {
  check_dual_snapshots("AngleGreedyProblem", snapshots, weights);
  for (Eigen::Index p = 0; p < snapshots.cols(); ++p) norms_(p) = weighted_norm(snapshots.col(p), weights);
}

Eigen::VectorXd AngleGreedyProblem::evaluate() {
  Eigen::VectorXd errors(residuals_.cols());
  for (Eigen::Index p = 0; p < residuals_.cols(); ++p) errors(p) = weighted_norm(residuals_.col(p), weights_);
  for (int s : selected_) errors(s) = 0.0;  // lies in W_n
  return errors;
}

void AngleGreedyProblem::extend(int index) {
  require(index >= 0 && index < training_size(), "AngleGreedyProblem::extend: index " + std::to_string(index) +
                                                     " outside the training set of size " +
                                                     std::to_string(training_size()));
  const Eigen::Index R = generators_.cols();
  generators_.conservativeResize(Eigen::NoChange, R + 1);
  generators_.col(R) = snapshots_.col(index);
  selected_.push_back(index);
  // New direction: the selected residual, re-orthogonalized once against the basis.
  Eigen::VectorXd q = residuals_.col(index);
  auto mdot = [&](const Eigen::VectorXd& a, const auto& b) {
    return weights_.size() ? (a.array() * weights_.array() * b.array()).sum() : a.dot(b);
  };
  for (Eigen::Index j = 0; j < basis_.cols(); ++j) q -= mdot(q, basis_.col(j)) * basis_.col(j);
  const double nq = weighted_norm(q, weights_);
  const double n0 = norms_(index);
  if (nq > kRoundoffResidual * n0 && nq > 0.0) {
    q /= nq;
    const Eigen::Index k = basis_.cols();
    basis_.conservativeResize(Eigen::NoChange, k + 1);
    basis_.col(k) = q;
    const Eigen::VectorXd Mq = weights_.size() ? Eigen::VectorXd(weights_.cwiseProduct(q)) : q;
    const Eigen::RowVectorXd coeff = Mq.transpose() * residuals_;
    residuals_.noalias() -= q * coeff;
  }
  residuals_.col(index).setZero();
}

DualConeResult build_angle_greedy(const Eigen::MatrixXd& snapshots, const DualConeSettings& settings) {
  check_settings(settings.greedy);
  const auto t0 = std::chrono::steady_clock::now();
  AngleGreedyProblem problem(snapshots, settings.weights);
  const GreedyResult g = run_greedy(problem, settings.greedy);
  DualConeResult out;
  out.method = DualConeMethod::AngleGreedy;
  out.status = g.status;
  out.selected = g.selected;
  out.generators = problem.generators();
  out.linear_errors = g.max_errors;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (settings.cone_history) {
    // True cone-projection errors of the same nested selection (Fig. 19, "real" curve).
    const auto t1 = std::chrono::steady_clock::now();
    CPGProblem cone(snapshots, settings.weights, settings.qp);
    const Eigen::VectorXd norms = cone.reference_norms();
    auto record = [&](const Eigen::VectorXd& e) {
      double rel = 0.0;
      for (Eigen::Index p = 0; p < e.size(); ++p)
        if (norms(p) > 0.0) rel = std::max(rel, e(p) / norms(p));
      out.errors.push_back(e.size() ? e.maxCoeff() : 0.0);
      out.relative_errors.push_back(rel);
    };
    record(cone.evaluate());
    for (int s : g.selected) {
      cone.extend(s);
      record(cone.evaluate());
    }
    out.qp_failures = cone.qp_failures();
    out.history_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  }
  return out;
}

}  // namespace contactrb::rb
