#pragma once
// The multiplier scale of the relative KKT reports (HFKKT, FrictionKKT): the largest multiplier,
// floored by the rounding of the forces the multipliers balance (docs/theory.md, "Semi-smooth
// Newton", step 6).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>

namespace contactrb::hf {

struct MultiplierScale {
  double largest = 0.0;  // max_r |lambda_r|
  // eps | |A_00| |u_0| + |b| |_inf / min_r |I_r|: the rounding of the nodal forces A_00 u_0 - b
  // that the multipliers balance (K_0' lambda), as a pressure on the smallest support |I_r| > 0.
  // A multiplier computed from forces of that size cannot be told from zero below it. Where the
  // floor is below tolerance x max |lambda| (on the loaded built-in cases: under 1e-12 of it) no
  // convergence decision changes.
  double floor = 0.0;
  double value() const { return std::max({largest, floor, 1e-300}); }
  // A pressure residual relative to the scale; one within the floor counts as zero. Without the
  // floor a problem with no load (a rigid translation) has multipliers of round-off size and a
  // dual residual of order one that no Newton step can reduce.
  double relative(double pressure) const { return pressure <= floor ? 0.0 : pressure / value(); }
};

MultiplierScale multiplier_scale(const Eigen::SparseMatrix<double>& A00, const Eigen::VectorXd& b,
                                 const Eigen::VectorXd& u0, const Eigen::VectorXd& lambda,
                                 const Eigen::VectorXd& weight);

}  // namespace contactrb::hf
