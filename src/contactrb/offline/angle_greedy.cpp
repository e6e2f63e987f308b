#include "contactrb/offline/angle_greedy.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/offline/cone_projection.hpp"
#include "contactrb/offline/cpg.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::offline {

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

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Largest e(p) / norms(p) over the p with a nonzero norm (0 if none).
double max_relative(const Eigen::VectorXd& e, const Eigen::VectorXd& norms) {
  double rel = 0.0;
  for (Eigen::Index p = 0; p < e.size(); ++p)
    if (norms(p) > 0.0) rel = std::max(rel, e(p) / norms(p));
  return rel;
}

// First index of the largest criterion value: e(p), or e(p) / norms(p) when relative.
int argmax_criterion(const Eigen::VectorXd& e, const Eigen::VectorXd& norms, bool relative) {
  int best = 0;
  double best_value = -1.0;
  for (Eigen::Index p = 0; p < e.size(); ++p) {
    const double v = relative ? (norms(p) > 0.0 ? e(p) / norms(p) : 0.0) : e(p);
    if (v > best_value) {
      best_value = v;
      best = static_cast<int>(p);
    }
  }
  return best;
}
}  // namespace

DualConeResult build_angle_greedy(const Eigen::MatrixXd& snapshots, const DualConeSettings& settings) {
  const GreedySettings& gs = settings.greedy;
  check_settings(gs);
  require(settings.cone_history || gs.tolerance == 0.0,
          "angle-greedy: the stopping test (58) reads the true cone-projection errors, so cone_history = false "
          "needs tolerance 0 (a fixed size), got tolerance " + number_text(gs.tolerance));
  DualConeResult out;
  out.method = DualConeMethod::AngleGreedy;
  auto t0 = Clock::now();
  AngleGreedyProblem problem(snapshots, settings.weights);
  const Eigen::VectorXd norms = problem.reference_norms();
  const int P = problem.training_size();
  Eigen::VectorXd linear = problem.evaluate();
  out.seconds += since(t0);
  const double initial = P > 0 ? linear.maxCoeff() : 0.0;
  // The cone actually used online is span+ of the selection; (58) is about ITS error (the
  // linear error only steers the selection and can be far below it, e.g. 0.01 against 0.037).
  std::unique_ptr<CPGProblem> cone;
  Eigen::VectorXd cone_errors;
  const auto record_cone = [&] {
    t0 = Clock::now();
    cone_errors = cone->evaluate();
    out.errors.push_back(P > 0 ? cone_errors.maxCoeff() : 0.0);
    out.relative_errors.push_back(max_relative(cone_errors, norms));
    out.history_seconds += since(t0);
  };
  if (settings.cone_history) {
    t0 = Clock::now();
    cone = std::make_unique<CPGProblem>(snapshots, settings.weights, settings.qp);
    out.history_seconds += since(t0);
    record_cone();
  }
  while (true) {
    out.linear_errors.push_back(P > 0 ? linear.maxCoeff() : 0.0);
    const int n = static_cast<int>(out.selected.size());
    if (cone && (gs.relative ? out.relative_errors.back() : out.errors.back()) <= gs.tolerance) {
      out.status = GreedyStatus::ToleranceReached;
      break;
    }
    if (gs.max_size >= 0 && n >= gs.max_size) {
      out.status = GreedyStatus::MaxSize;
      break;
    }
    // Nothing left to steer by: every snapshot lies in W_n (up to round-off). The cone error may
    // still be above eps_DU; the status says that eps_DU was not reached.
    if (P == 0 || n >= P || out.linear_errors.back() <= gs.exhaustion_tolerance * initial) {
      out.status = GreedyStatus::Exhausted;
      break;
    }
    // Line 5 of Algorithm 2 with the linear projection; the first pick is (56) in both modes
    // (every relative error of the empty space is 1).
    t0 = Clock::now();
    const int next = argmax_criterion(linear, norms, gs.relative && n > 0);
    problem.extend(next);
    out.selected.push_back(next);
    linear = problem.evaluate();
    out.seconds += since(t0);
    if (cone) {
      t0 = Clock::now();
      cone->extend(next);
      out.history_seconds += since(t0);
      record_cone();
    }
  }
  out.generators = problem.generators();
  if (cone) out.qp_failures = cone->qp_failures();
  return out;
}

}  // namespace contactrb::offline
