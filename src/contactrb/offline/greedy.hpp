#pragma once
// Weak-greedy driver shared by the dual-cone greedies (CPG, Algorithm 2; angle-greedy) and the
// EIM greedy: a problem exposes two steps, *evaluate* (the error of every training element
// against the current approximation) and *extend* (add one training element), and
// run_greedy() alternates them until a stopping test holds (the protocol of pyMOR's
// weak_greedy; see docs/rb.md).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace contactrb::offline {

enum class GreedyStatus {
  ToleranceReached,  // max criterion <= tolerance, e.g. (58)
  MaxSize,           // the requested size (fixed R or M) was reached first
  Exhausted          // nothing left to add: max error <= exhaustion_tolerance * initial max error,
                     // or every training element is selected
};
const char* to_string(GreedyStatus status);
GreedyStatus greedy_status_from_string(const std::string& name);  // throws contactrb::Error

struct GreedySettings {
  // Stop when max_mu criterion(mu) <= tolerance; criterion = error (absolute, (58)) or
  // error / reference norm (relative: (58) divided by |lambda(mu)|; 0 where the norm is 0).
  double tolerance = 0.0;
  bool relative = false;
  // Stop after this many extensions; -1: no limit but the training set size.
  int max_size = -1;
  // Stop (Exhausted) when the absolute max error is <= exhaustion_tolerance times the error
  // before the first extension: what is left is round-off, selecting it would only add noise.
  double exhaustion_tolerance = 1e-12;
};
// Throws contactrb::Error unless tolerance >= 0, max_size >= -1, exhaustion_tolerance >= 0.
void check_settings(const GreedySettings& settings);

class GreedyProblem {
 public:
  virtual ~GreedyProblem() = default;
  virtual int training_size() const = 0;
  // Error of every training element against the current approximation (size training_size()).
  virtual Eigen::VectorXd evaluate() = 0;
  // Add training element `index` to the approximation.
  virtual void extend(int index) = 0;
  // Norms dividing the errors in the relative criterion (size training_size()).
  virtual Eigen::VectorXd reference_norms() const = 0;
};

struct GreedyResult {
  GreedyStatus status = GreedyStatus::Exhausted;
  std::vector<int> selected;                 // training indices, in selection order
  std::vector<double> max_errors;            // [k]: max_mu error after k extensions (size selected + 1)
  std::vector<double> max_relative_errors;   // [k]: max_mu error / reference norm (0 where the norm is 0)
  double evaluate_seconds = 0.0;
  double extend_seconds = 0.0;
  double seconds = 0.0;                      // total wall time of run_greedy
};

// Alternates evaluate / extend from the problem's current state. Extends by argmax of the
// criterion, except the first extension of a relative run, which takes argmax of the absolute
// error ((56): the relative errors of an empty approximation are all 1). Ties in the argmax go
// to the smallest index (deterministic).
GreedyResult run_greedy(GreedyProblem& problem, const GreedySettings& settings);

}  // namespace contactrb::offline
