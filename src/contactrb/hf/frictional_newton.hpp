#pragma once
// One load step of the frictional solver (hf/friction.hpp; docs/solvers.md, "Friction"): the
// semi-smooth Newton iteration on (u_0, lambda, lambda_t) from the state at the end of the
// previous step. Internal to the hf module.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "contactrb/hf/friction.hpp"
#include "contactrb/hf/newton_iterate.hpp"
#include "contactrb/solve/selected_inverse.hpp"

namespace contactrb::hf {

// The algebra of one load step: the Newton problem's views (A_00, b, DOFs, geometry).
template <int Dim>
using FrictionAlgebra = BasicNewtonProblem<Dim>;

// The state a step starts from and returns.
template <int Dim>
struct FrictionState {
  Eigen::VectorXd u;         // total displacement (num_dofs)
  Eigen::VectorXd lambda;    // R
  Eigen::VectorXd lambda_t;  // (Dim - 1) R
};

template <int Dim>
struct FrictionStepResult {
  FrictionStepReport report;
  Eigen::VectorXd u0;
  FrictionState<Dim> state;
  Eigen::VectorXd slip;      // (Dim - 1) R: slip of the slave relative to the master in the step (length)
  std::vector<SlipState> nodes;
  FrictionKKT kkt;
};

// The rows that carry friction in a step from `previous`: the candidates in contact at u_prev
// (lambda_r > 0) or touching (a weighted gap d_r of round-off size: two bodies meshed in contact).
template <int Dim>
std::vector<char> frictional_rows(const FrictionAlgebra<Dim>& algebra, const FrictionState<Dim>& previous,
                                  const contact::ProjectionOptions& projection);

// previous: the end of the previous step (u_prev of the slip increments); start: the first
// iterate (the previous state, or a predictor of it); inverse: A_00 factorized (the systems
// condensed on the contact DOFs), or nullptr (one sparse LU of the whole system per iteration).
template <int Dim>
FrictionStepResult<Dim> solve_friction_step(const FrictionAlgebra<Dim>& algebra, const FrictionState<Dim>& previous,
                                            const FrictionState<Dim>& start, solve::SelectedInverse* inverse,
                                            const FrictionSettings& settings);
extern template FrictionStepResult<2> solve_friction_step(const FrictionAlgebra<2>&, const FrictionState<2>&,
                                                          const FrictionState<2>&, solve::SelectedInverse*,
                                                          const FrictionSettings&);
extern template FrictionStepResult<3> solve_friction_step(const FrictionAlgebra<3>&, const FrictionState<3>&,
                                                          const FrictionState<3>&, solve::SelectedInverse*,
                                                          const FrictionSettings&);
extern template std::vector<char> frictional_rows(const FrictionAlgebra<2>&, const FrictionState<2>&,
                                                  const contact::ProjectionOptions&);
extern template std::vector<char> frictional_rows(const FrictionAlgebra<3>&, const FrictionState<3>&,
                                                  const contact::ProjectionOptions&);

}  // namespace contactrb::hf
