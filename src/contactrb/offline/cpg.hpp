#pragma once
// Cone-Projected Greedy (CPG), paper Algorithm 2: select first argmax |lambda(mu)|_Lambda (56),
// then argmax |lambda(mu) - Pi_{K_{n-1}}(lambda(mu))|_Lambda (57), until (58) (absolute or
// relative) or a fixed R. The generators are the selected snapshots themselves.
#include <Eigen/Core>
#include <vector>

#include "contactrb/offline/cone_projection.hpp"
#include "contactrb/offline/dual_cone.hpp"
#include "contactrb/offline/greedy.hpp"

namespace contactrb::offline {

// The evaluate / extend steps of Algorithm 2. Borrows `snapshots` (R_hf x P), which must
// outlive the object. evaluate() returns the cone-projection error of every snapshot onto the
// cone of the selected ones (exactly 0 for a selected snapshot); each projection is warm-started
// from the same snapshot's previous passive set.
class CPGProblem final : public GreedyProblem {
 public:
  CPGProblem(const Eigen::MatrixXd& snapshots, const Eigen::VectorXd& weights = {},
             const solve::QPSettings& qp = {});
  // The snapshots are borrowed: a temporary would dangle.
  CPGProblem(const Eigen::MatrixXd&& snapshots, const Eigen::VectorXd& weights = {},
             const solve::QPSettings& qp = {}) = delete;
  int training_size() const override { return static_cast<int>(snapshots_.cols()); }
  Eigen::VectorXd evaluate() override;
  void extend(int index) override;
  Eigen::VectorXd reference_norms() const override { return norms_; }

  const std::vector<int>& selected() const { return selected_; }
  const Eigen::MatrixXd& generators() const { return projector_.generators(); }
  int qp_failures() const { return qp_failures_; }

 private:
  const Eigen::MatrixXd& snapshots_;
  ConeProjector projector_;
  Eigen::VectorXd norms_;
  std::vector<int> selected_;
  std::vector<std::vector<int>> passive_;
  int qp_failures_ = 0;
};

// Algorithm 2 from the empty cone. Throws contactrb::Error for invalid input (negative or
// non-finite snapshots, mismatched weights, invalid settings).
DualConeResult build_cpg(const Eigen::MatrixXd& snapshots, const DualConeSettings& settings = {});

}  // namespace contactrb::offline
