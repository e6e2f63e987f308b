#pragma once
// Angle-greedy (paper Section 5, after Algorithm 2): line 5 of Algorithm 2 with the LINEAR
// projection onto W_{n-1} = span{lambda(mu_1), ..., lambda(mu_{n-1})} in the Lambda norm. The
// generators are the selected snapshots; the cone actually used online is their span+, whose
// (true) projection error is reported beside the steering linear error (Fig. 19).
#include <Eigen/Core>
#include <vector>

#include "contactrb/offline/dual_cone.hpp"
#include "contactrb/offline/greedy.hpp"

namespace contactrb::offline {

// evaluate(): |lambda(mu) - Pi_{W_n}(lambda(mu))|_Lambda for every snapshot (0 for a selected one).
// Keeps the residuals of all snapshots and a Lambda-orthonormal basis of W_n (Gram-Schmidt with
// one re-orthogonalization), so extend() costs O(R_hf P) and evaluate() O(R_hf P).
// Borrows `snapshots` (R_hf x P), which must outlive the object.
class AngleGreedyProblem final : public GreedyProblem {
 public:
  explicit AngleGreedyProblem(const Eigen::MatrixXd& snapshots, const Eigen::VectorXd& weights = {});
  // The snapshots are borrowed: a temporary would dangle.
  AngleGreedyProblem(const Eigen::MatrixXd&& snapshots, const Eigen::VectorXd& weights = {}) = delete;
  int training_size() const override { return static_cast<int>(residuals_.cols()); }
  Eigen::VectorXd evaluate() override;
  void extend(int index) override;
  Eigen::VectorXd reference_norms() const override { return norms_; }

  const std::vector<int>& selected() const { return selected_; }
  const Eigen::MatrixXd& generators() const { return generators_; }

 private:
  const Eigen::MatrixXd& snapshots_;
  Eigen::VectorXd weights_;    // empty: identity
  Eigen::MatrixXd residuals_;  // lambda(mu) - Pi_{W_n} lambda(mu), one column per snapshot
  Eigen::MatrixXd basis_;      // Lambda-orthonormal basis of W_n
  Eigen::MatrixXd generators_;
  Eigen::VectorXd norms_;
  std::vector<int> selected_;
};

// The angle-greedy from the empty space: the linear error steers the selection, the stopping
// test (58) (absolute or relative) reads the TRUE cone-projection error of the selection
// (errors / relative_errors), so ToleranceReached means that the cone used online reaches eps_DU.
// When the linear errors are exhausted (every snapshot in W_n) first, the status is Exhausted and
// errors.back() is the cone error actually reached. linear_errors are always filled;
// settings.cone_history = false (timing the algorithm alone) skips the cone errors and is
// allowed only with tolerance 0 (a fixed size or exhaustion); throws contactrb::Error otherwise.
// seconds: the selection; history_seconds: the cone projections.
DualConeResult build_angle_greedy(const Eigen::MatrixXd& snapshots, const DualConeSettings& settings = {});

}  // namespace contactrb::offline
