#include "contactrb/hf/multiplier_scale.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace contactrb::hf {

MultiplierScale multiplier_scale(const Eigen::SparseMatrix<double>& A00, const Eigen::VectorXd& b,
                                 const Eigen::VectorXd& u0, const Eigen::VectorXd& lambda,
                                 const Eigen::VectorXd& weight) {
  MultiplierScale s;
  s.largest = lambda.size() > 0 ? lambda.cwiseAbs().maxCoeff() : 0.0;
  double support = std::numeric_limits<double>::infinity();
  for (const double w : weight) {
    if (w > 0.0) support = std::min(support, w);
  }
  if (!std::isfinite(support)) return s;
  Eigen::VectorXd abs_forces = b.cwiseAbs();  // |A_00| |u_0| + |b|, row by row
  for (Eigen::Index j = 0; j < A00.outerSize(); ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A00, j); it; ++it) {
      abs_forces(it.row()) += std::abs(it.value()) * std::abs(u0(j));
    }
  }
  const double force = abs_forces.size() > 0 ? abs_forces.maxCoeff() : 0.0;
  s.floor = std::numeric_limits<double>::epsilon() * force / support;
  return s;
}

}  // namespace contactrb::hf
