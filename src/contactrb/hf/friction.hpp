#pragma once
// Frictional contact, Tresca and Coulomb, along a quasi-static load path (docs/solvers.md,
// "Friction"). Unknowns: the free displacement u_0, one normal multiplier lambda_r (a pressure,
// >= 0, the frictionless solver's) and Dim - 1 tangential multipliers lambda_t,r (the traction on
// the slave along the master tangents tau, contact/tangential_rows.hpp) per slave node. Each load
// step solves, by a semi-smooth Newton method on the Alart-Curnier complementarity functions,
//   A_00 u_0 - b + K_0(u)' lambda + T_0(u)' lambda_t = 0,
//   min(lambda_r, c_r d_r(u)) = 0,                       d = g(u) - K(u) u   (the normal law)
//   lambda_t,r - P_{B(s_r)}(lambda_t,r + c_r delta_r) = 0, delta_r = -|I_r| slip_r(u)
// with B(s) the ball of radius s (2D: [-s, s]; 3D: the disk, P(x) = x or s x / |x|), s_r = the
// Tresca threshold or f lambda_r on rows in contact, 0 on open rows; slip_r is the motion of the
// slave node over the master's material points since u_prev, the displacement at the end of the
// previous step (contact::tangential_slip), so the slip history is carried from step to step. A
// row that closes during a step carries friction from the next step on.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/traction.hpp"
#include "contactrb/hf/contact_problem.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/solve/selected_inverse.hpp"
#include "contactrb/solve/sparse_lu.hpp"

namespace contactrb::hf {

enum class FrictionLaw { Tresca, Coulomb };
const char* to_string(FrictionLaw law);
FrictionLaw friction_law_from_string(const std::string& name);  // "tresca" | "coulomb"

// FullSliding: the Newton system is singular or the iterates slip without bound while no node
// sticks (e.g. a tangential force Q >= f P on a body that only friction holds): no equilibrium.
enum class FrictionStatus { Converged, MaxIterations, FullSliding, StepFailed, NonFinite };
const char* to_string(FrictionStatus status);
FrictionStatus friction_status_from_string(const std::string& name);

enum class SlipState : signed char { Open, Stick, Slip };
const char* to_string(SlipState state);  // "open" | "stick" | "slip"

// Schur (default): A_00 factorized once per path (CHOLMOD), each Newton system condensed on the
// contact DOFs of the rows in contact (a small dense LU); when A_00 is not SPD (a body that only
// the contact holds), SaddleLU instead. SaddleLU: one sparse LU of the whole system per iteration.
enum class FrictionLinearSolver { Schur, SaddleLU };
const char* to_string(FrictionLinearSolver solver);
FrictionLinearSolver friction_linear_solver_from_string(const std::string& name);  // "schur" | "lu"

struct FrictionSettings {
  FrictionLaw law = FrictionLaw::Coulomb;
  double coefficient = 0.0;  // Coulomb: f >= 0
  double threshold = 0.0;    // Tresca: the slip threshold s >= 0 (a traction)
  double tolerance = 1e-10;  // on FrictionKKT::max()
  int max_iterations = 50;   // per load step
  // An iterate whose slip increment at some node exceeds max_slip x the diameter of the mesh
  // has left small sliding: divergence (FullSliding when no node sticks).
  double max_slip = 1.0;
  contact::LinearizationOptions linearization;  // the normal rows' consistent linearization
  FrictionLinearSolver linear_solver = FrictionLinearSolver::Schur;
  solve::FactorOrdering ordering = solve::FactorOrdering::Auto;  // Schur: of A_00
  solve::SparseLUBackend lu = solve::SparseLUBackend::Umfpack;   // SaddleLU
};
// Coulomb with f = 0: the frictionless solver answers (solve_load_path).
bool friction_is_off(const FrictionSettings& settings);
// Throws contactrb::Error naming the first setting out of range.
void check_settings(const FrictionSettings& settings);

// The data of one load step: they replace the problem's Dirichlet values and surface loads.
// Every step prescribes the same components of the same groups (the free DOFs do not change).
template <int Dim>
struct BasicLoadStep {
  std::vector<fem::DirichletCondition> dirichlet;
  std::vector<fem::SurfaceLoad<Dim>> tractions;
};
using LoadStep = BasicLoadStep<2>;
using LoadStep3 = BasicLoadStep<3>;

// The frictionless report (HFKKT) with the residual of the friction law: max_r |C_t,r| / max
// lambda (C_t the tangential complementarity function above, a traction).
struct FrictionKKT {
  HFKKT normal;
  double friction = 0.0;
  double max() const;
};

struct FrictionStepReport {
  FrictionStatus status = FrictionStatus::StepFailed;
  std::string message;
  int iterations = 0;
  std::vector<double> residuals;  // FrictionKKT::max() at each iterate, the last one included
  int stick = 0, slip = 0, open = 0;
  double normal_force = 0.0;      // sum_r lambda_r |I_r|
  Eigen::VectorXd tangential_force;  // Dim - 1: sum_r lambda_t,r |I_r| (on the slave, along tau)
  double time_s = 0.0;  // wall clock of the whole step: its algebra, the frictionless solve it may start from, the iteration
};

template <int Dim>
struct BasicFrictionalSolution {
  FrictionStatus status = FrictionStatus::StepFailed;
  bool converged = false;
  std::string message;
  std::vector<FrictionStepReport> steps;  // one per load step solved
  Eigen::VectorXd u, u0;   // the state at the end of the path (num_dofs, num_free)
  Eigen::VectorXd lambda;  // R: contact pressures
  Eigen::VectorXd lambda_t;  // (Dim - 1) R: tangential tractions on the slave along tau
  Eigen::VectorXd slip;      // (Dim - 1) R: slip of the slave node relative to the master along tau, summed over the path
  std::vector<SlipState> state;  // R
  FrictionKKT kkt;
  double contact_force = 0.0;
  Eigen::VectorXd tangential_force;  // Dim - 1
  int stick_nodes = 0, slip_nodes = 0;
  double time_s = 0.0;
};
using FrictionalSolution = BasicFrictionalSolution<2>;
using FrictionalSolution3 = BasicFrictionalSolution<3>;

// Called after each converged load step with the step's index in the path (from 0) and the
// state at its end (the fields of BasicFrictionalSolution as set after that step).
template <int Dim>
using LoadStepObserver = std::function<void(std::size_t step, const BasicFrictionalSolution<Dim>& state)>;

// Solves the load steps in order, each from the state at the end of the previous one (the first
// from u = 0, no slip). Friction off (friction_is_off): the frictionless solver
// (BasicHFSolver::solve with `frictionless`) on the last step alone, the answer bit for bit
// (without friction the answer has no history; `observer` sees that last step only). Stops at
// the first step that fails, with its status. Throws contactrb::Error for an empty path, a step
// whose Dirichlet data do not free the same DOFs, an invalid problem or settings, or a
// discretization other than collocation.
template <int Dim>
BasicFrictionalSolution<Dim> solve_load_path(const BasicContactProblem<Dim>& problem,
                                             const std::vector<BasicLoadStep<Dim>>& path,
                                             const FrictionSettings& friction, const HFSettings& frictionless = {},
                                             const LoadStepObserver<Dim>& observer = {});
extern template BasicFrictionalSolution<2> solve_load_path(const BasicContactProblem<2>&,
                                                           const std::vector<BasicLoadStep<2>>&,
                                                           const FrictionSettings&, const HFSettings&,
                                                           const LoadStepObserver<2>&);
extern template BasicFrictionalSolution<3> solve_load_path(const BasicContactProblem<3>&,
                                                           const std::vector<BasicLoadStep<3>>&,
                                                           const FrictionSettings&, const HFSettings&,
                                                           const LoadStepObserver<3>&);

}  // namespace contactrb::hf
