#include "contactrb/offline/cpg.hpp"

#include "contactrb/model/reduced_model.hpp"

#include <chrono>
#include <string>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::offline {

const char* to_string(DualConeMethod method) {
  switch (method) {
    case DualConeMethod::CPG: return "cpg";
    case DualConeMethod::AngleGreedy: return "angle";
    case DualConeMethod::NMF: return "nmf";
    case DualConeMethod::Rows: return model::kRowCone;
    case DualConeMethod::Registered: return model::kRegisteredCone;
  }
  return "unknown";
}

DualConeMethod dual_cone_method_from_string(const std::string& name) {
  using enum DualConeMethod;
  return enum_from_string(name, "dual cone method", std::array{CPG, AngleGreedy, NMF, Rows, Registered});
}

void check_dual_snapshots(const char* who, const Eigen::MatrixXd& snapshots, const Eigen::VectorXd& weights) {
  require(snapshots.allFinite(), std::string(who) + ": the multiplier snapshots (" +
                                     std::to_string(snapshots.rows()) + "x" + std::to_string(snapshots.cols()) +
                                     ") have non-finite entries");
  require(snapshots.size() == 0 || snapshots.minCoeff() >= 0.0,
          std::string(who) + ": the multiplier snapshots must be >= 0 (pressures), min entry is " +
              number_text(snapshots.size() ? snapshots.minCoeff() : 0.0));
  require(weights.size() == 0 || weights.size() == snapshots.rows(),
          std::string(who) + ": the Lambda weights have size " + std::to_string(weights.size()) +
              " but the snapshots have " + std::to_string(snapshots.rows()) + " rows (must be empty or match)");
  require(weights.allFinite() && (weights.size() == 0 || weights.minCoeff() >= 0.0),
          std::string(who) + ": the Lambda weights must be finite and >= 0");
}

CPGProblem::CPGProblem(const Eigen::MatrixXd& snapshots, const Eigen::VectorXd& weights,
                       const solve::QPSettings& qp)
    : snapshots_(snapshots), projector_(snapshots.rows(), weights, qp), norms_(snapshots.cols()),
      passive_(static_cast<std::size_t>(snapshots.cols())) {
  check_dual_snapshots("CPGProblem", snapshots, weights);
  for (Eigen::Index p = 0; p < snapshots.cols(); ++p) norms_(p) = weighted_norm(snapshots.col(p), weights);
}

Eigen::VectorXd CPGProblem::evaluate() {
  const Eigen::Index P = snapshots_.cols();
  Eigen::VectorXd errors(P);
  for (Eigen::Index p = 0; p < P; ++p) {
    const ConeProjection pr = projector_.project(snapshots_.col(p), passive_[static_cast<std::size_t>(p)]);
    if (pr.status != solve::QPStatus::Solved) ++qp_failures_;
    errors(p) = pr.error;
    passive_[static_cast<std::size_t>(p)] = pr.passive;
  }
  for (int s : selected_) errors(s) = 0.0;  // a generator lies in its cone
  return errors;
}

void CPGProblem::extend(int index) {
  require(index >= 0 && index < training_size(), "CPGProblem::extend: index " + std::to_string(index) +
                                                     " outside the training set of size " +
                                                     std::to_string(training_size()));
  projector_.add_generator(snapshots_.col(index));
  selected_.push_back(index);
}

DualConeResult build_cpg(const Eigen::MatrixXd& snapshots, const DualConeSettings& settings) {
  check_settings(settings.greedy);
  const auto t0 = std::chrono::steady_clock::now();
  CPGProblem problem(snapshots, settings.weights, settings.qp);
  const GreedyResult g = run_greedy(problem, settings.greedy);
  DualConeResult out;
  out.method = DualConeMethod::CPG;
  out.status = g.status;
  out.generators = problem.generators();
  out.selected = g.selected;
  out.errors = g.max_errors;
  out.relative_errors = g.max_relative_errors;
  out.qp_failures = problem.qp_failures();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace contactrb::offline
