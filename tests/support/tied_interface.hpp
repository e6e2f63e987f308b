#pragma once
// The tied interface (every slave node glued to a master point) as an equality-constrained
// linear system, the independent reference of the large-friction tests: [A_00 C'; C 0] [u_0; mu]
// = [b; 0], one row of C per tie, a tie being a list of (global DOF, coefficient) whose sum of
// coefficient times displacement vanishes. Returns the total displacement, or an empty vector
// when a tie touches a constrained DOF or the system is singular.
#include <Eigen/SparseLU>
#include <utility>
#include <vector>

#include "contactrb/fem/dirichlet.hpp"

namespace test_support {

using Tie = std::vector<std::pair<int, double>>;

template <class Solver>
Eigen::VectorXd tied_displacement(const Solver& solver, const std::vector<Tie>& ties) {
  const contactrb::fem::DofMap& dofs = solver.dofs();
  const Eigen::SparseMatrix<double> A00 = dofs.restrict_matrix(solver.stiffness());
  const Eigen::VectorXd b = dofs.restrict(solver.load() - solver.stiffness() * dofs.lift());
  std::vector<int> free_index(static_cast<std::size_t>(dofs.num_dofs()), -1);
  for (int i = 0; i < dofs.num_free(); ++i) free_index[static_cast<std::size_t>(dofs.free_dofs()[static_cast<std::size_t>(i)])] = i;
  const int n = dofs.num_free(), m = static_cast<int>(ties.size());
  std::vector<Eigen::Triplet<double>> trip;
  for (int j = 0; j < A00.outerSize(); ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator a(A00, j); a; ++a) trip.emplace_back(a.row(), a.col(), a.value());
  }
  for (int t = 0; t < m; ++t) {
    for (const auto& [dof, coefficient] : ties[static_cast<std::size_t>(t)]) {
      const int fi = free_index[static_cast<std::size_t>(dof)];
      if (fi < 0) return {};
      trip.emplace_back(n + t, fi, coefficient);
      trip.emplace_back(fi, n + t, coefficient);
    }
  }
  Eigen::SparseMatrix<double> kkt(n + m, n + m);
  kkt.setFromTriplets(trip.begin(), trip.end());
  const Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(kkt);
  if (lu.info() != Eigen::Success) return {};
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
  rhs.head(n) = b;
  return dofs.lift() + dofs.extend(lu.solve(rhs).head(n));
}

}  // namespace test_support
