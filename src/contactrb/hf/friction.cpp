// Frictional contact along a load path (docs/solvers.md, "Friction"): the driver over the load
// steps; one step's Newton iteration is frictional_newton.cpp.
#include "contactrb/hf/friction.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/hf/frictional_newton.hpp"

namespace contactrb::hf {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

const char* to_string(FrictionLaw law) {
  switch (law) {
    case FrictionLaw::Tresca: return "tresca";
    case FrictionLaw::Coulomb: return "coulomb";
  }
  return "unknown";
}

FrictionLaw friction_law_from_string(const std::string& name) {
  return enum_from_string(name, "friction law", std::array{FrictionLaw::Tresca, FrictionLaw::Coulomb});
}

const char* to_string(FrictionStatus status) {
  switch (status) {
    case FrictionStatus::Converged: return "converged";
    case FrictionStatus::MaxIterations: return "max-iterations";
    case FrictionStatus::FullSliding: return "full-sliding";
    case FrictionStatus::StepFailed: return "step-failed";
    case FrictionStatus::NonFinite: return "non-finite";
  }
  return "unknown";
}

FrictionStatus friction_status_from_string(const std::string& name) {
  return enum_from_string(name, "friction status",
                          std::array{FrictionStatus::Converged, FrictionStatus::MaxIterations, FrictionStatus::FullSliding,
                                     FrictionStatus::StepFailed, FrictionStatus::NonFinite});
}

const char* to_string(FrictionLinearSolver solver) {
  switch (solver) {
    case FrictionLinearSolver::Schur: return "schur";
    case FrictionLinearSolver::SaddleLU: return "lu";
  }
  return "unknown";
}

FrictionLinearSolver friction_linear_solver_from_string(const std::string& name) {
  if (name == "schur") return FrictionLinearSolver::Schur;
  if (name == "lu") return FrictionLinearSolver::SaddleLU;
  throw Error("unknown friction linear solver '" + name + "' (expected schur or lu)");
}

const char* to_string(SlipState state) {
  switch (state) {
    case SlipState::Open: return "open";
    case SlipState::Stick: return "stick";
    case SlipState::Slip: return "slip";
  }
  return "unknown";
}

double FrictionKKT::max() const { return std::max(normal.max(), friction); }

bool friction_is_off(const FrictionSettings& s) { return s.law == FrictionLaw::Coulomb && s.coefficient == 0.0; }

void check_settings(const FrictionSettings& s) {
  require(std::isfinite(s.coefficient) && s.coefficient >= 0.0,
          "friction coefficient must be >= 0 (got " + number_text(s.coefficient) + ")");
  require(std::isfinite(s.threshold) && s.threshold >= 0.0,
          "Tresca slip threshold must be >= 0 (got " + number_text(s.threshold) + ")");
  require(std::isfinite(s.tolerance) && s.tolerance > 0.0,
          "friction tolerance must be > 0 (got " + number_text(s.tolerance) + ")");
  require(s.max_iterations >= 1, "friction max_iterations must be >= 1 (got " + std::to_string(s.max_iterations) + ")");
  require(std::isfinite(s.max_slip) && s.max_slip > 0.0,
          "friction max_slip must be > 0 (got " + number_text(s.max_slip) + ")");
}

namespace {

template <int Dim>
BasicContactProblem<Dim> with_step(BasicContactProblem<Dim> problem, const BasicLoadStep<Dim>& step) {
  problem.dirichlet = step.dirichlet;
  problem.tractions = step.tractions;
  return problem;
}

FrictionStatus friction_status(solve::KacanovStatus status) {
  switch (status) {
    case solve::KacanovStatus::Converged: return FrictionStatus::Converged;
    case solve::KacanovStatus::MaxIterations: return FrictionStatus::MaxIterations;
    case solve::KacanovStatus::StepFailed: return FrictionStatus::StepFailed;
    case solve::KacanovStatus::NonFinite: return FrictionStatus::NonFinite;
  }
  return FrictionStatus::StepFailed;
}

// Friction off: the frictionless solver on the last step, its answer unchanged; every node in
// contact slips (|t| = 0 = f p).
template <int Dim>
BasicFrictionalSolution<Dim> frictionless_answer(const BasicContactProblem<Dim>& problem,
                                                 const BasicLoadStep<Dim>& last, const HFSettings& settings) {
  const BasicHFSolver<Dim> solver(with_step(problem, last), setup_options_for(settings));
  const BasicHFSolution<Dim> h = solver.solve(settings);
  constexpr int M = Dim - 1;
  const auto R = h.lambda.size();
  BasicFrictionalSolution<Dim> sol;
  sol.status = friction_status(h.status);
  sol.converged = h.converged;
  sol.message = h.message;
  sol.u = h.u;
  sol.u0 = h.u0;
  sol.lambda = h.lambda;
  sol.lambda_t = Eigen::VectorXd::Zero(M * R);
  sol.slip = Eigen::VectorXd::Zero(M * R);
  sol.state.assign(static_cast<std::size_t>(R), SlipState::Open);
  for (Eigen::Index r = 0; r < R; ++r) {
    if (h.lambda(r) > 0.0) sol.state[static_cast<std::size_t>(r)] = SlipState::Slip;
  }
  sol.kkt.normal = h.kkt;
  sol.contact_force = h.contact_force;
  sol.tangential_force = Eigen::VectorXd::Zero(M);
  sol.slip_nodes = h.active_constraints;
  FrictionStepReport rep;
  rep.status = sol.status;
  rep.message = h.message;
  rep.iterations = h.iterations;
  rep.slip = h.active_constraints;
  rep.open = static_cast<int>(R) - h.active_constraints;
  rep.normal_force = h.contact_force;
  rep.tangential_force = sol.tangential_force;
  rep.time_s = h.time_s;
  sol.steps.push_back(std::move(rep));
  sol.time_s = h.time_s;
  return sol;
}

// The algebra of one load step on the assembled stiffness: its DOF map (lift), A_00 and b.
template <int Dim>
struct StepAlgebra {
  fem::DofMap dofs;
  Eigen::SparseMatrix<double> A00;
  Eigen::VectorXd b;
};

template <int Dim>
StepAlgebra<Dim> step_algebra(const BasicHFSolver<Dim>& solver, const Eigen::VectorXd& body_forces,
                              const BasicLoadStep<Dim>& step, std::size_t index) {
  const mesh::SimplexMesh<Dim>& mesh = solver.problem().mesh;
  StepAlgebra<Dim> a;
  for (const fem::DirichletCondition& c : step.dirichlet) {
    require((!c.ux || std::isfinite(*c.ux)) && (!c.uy || std::isfinite(*c.uy)) && (!c.uz || std::isfinite(*c.uz)),
            "friction: load step " + std::to_string(index + 1) + ": Dirichlet data on group '" + c.group +
                "' is not finite");
  }
  a.dofs = fem::DofMap(mesh, step.dirichlet);
  require(a.dofs.free_dofs() == solver.dofs().free_dofs(),
          "friction: load step " + std::to_string(index + 1) +
              " prescribes other DOFs than the first step (every step must prescribe the same components of the "
              "same groups)");
  Eigen::VectorXd f = body_forces;
  for (const fem::SurfaceLoad<Dim>& t : step.tractions) {
    require(mesh.has_boundary(t.group) && t.vector.allFinite() && std::isfinite(t.pressure),
            "friction: load step " + std::to_string(index + 1) + ": traction on '" + t.group +
                "' is not a finite load on a boundary group");
    f += fem::traction_load(mesh, t);
  }
  a.A00 = a.dofs.restrict_matrix(solver.stiffness());
  a.b = a.dofs.restrict(f - solver.stiffness() * a.dofs.lift());
  return a;
}

// Where a step's Newton iteration starts: the previous state (its free displacements; the
// prescribed ones are the step's). From a state without contact (the first step), the
// frictionless answer of the step instead, which finds the contact zone: from an open gap or a
// point contact (one touching row) the states of every row would change at once. Bodies that
// touch at rest over more than one row (meshed in contact: the contact zone is there) start from
// rest, their touching rows sticking from the first iterate: the frictionless answer would have
// them all slid, which the iteration must undo (block-on-block-3d level 1: 6 iterations from
// rest, 8 after the frictionless solve; docs/solvers.md, "Friction").
// A body held by the contact alone (`floating`) starts from the previous state too: without
// friction its position is undetermined, and the frictionless solver refuses the problem.
template <int Dim>
FrictionState<Dim> start_of_step(const BasicHFSolver<Dim>& solver, const FrictionAlgebra<Dim>& algebra,
                                 const BasicLoadStep<Dim>& step, const FrictionState<Dim>& previous,
                                 const FrictionSettings& friction, const HFSettings& frictionless, bool floating) {
  if (floating || (previous.lambda.array() > 0.0).any()) return previous;
  const std::vector<char> touching = frictional_rows(algebra, previous, friction.linearization.projection);
  if (std::count(touching.begin(), touching.end(), 1) > 1) return previous;
  HFSettings newton = frictionless;
  newton.method = HFMethod::Newton;
  const BasicHFSolver<Dim> step_solver(with_step(solver.problem(), step), setup_options_for(newton));
  const BasicHFSolution<Dim> h = step_solver.solve(newton);
  if (!h.converged) return previous;
  return FrictionState<Dim>{h.u, h.lambda, previous.lambda_t};
}

template <int Dim>
void set_final(BasicFrictionalSolution<Dim>& sol, const FrictionStepResult<Dim>& last) {
  sol.u = last.state.u;
  sol.u0 = last.u0;
  sol.lambda = last.state.lambda;
  sol.lambda_t = last.state.lambda_t;
  sol.state = last.nodes;
  sol.kkt = last.kkt;
  sol.contact_force = last.report.normal_force;
  sol.tangential_force = last.report.tangential_force;
  sol.stick_nodes = last.report.stick;
  sol.slip_nodes = last.report.slip;
}

// A converged step with every row open while a body is held by the contact alone: that body's
// rigid motion is free, so its position is no answer (it slid off the other body by steps below
// max_slip, and its residual is zero in every position).
void flag_slid_free(FrictionStepReport& report) {
  if (report.status != FrictionStatus::Converged || report.stick + report.slip > 0) return;
  report.status = FrictionStatus::FullSliding;
  report.message = "converged with no node in contact (" + std::to_string(report.open) +
                   " open) while a body is held by the contact alone: it slid free, no equilibrium";
}

}  // namespace

template <int Dim>
BasicFrictionalSolution<Dim> solve_load_path(const BasicContactProblem<Dim>& problem,
                                             const std::vector<BasicLoadStep<Dim>>& path,
                                             const FrictionSettings& friction, const HFSettings& frictionless,
                                             const LoadStepObserver<Dim>& observer) {
  const auto t0 = Clock::now();
  require(!path.empty(), "friction: the load path has no step");
  check_settings(friction);
  if (friction_is_off(friction)) {
    BasicFrictionalSolution<Dim> sol = frictionless_answer(problem, path.back(), frictionless);
    if (observer && sol.converged) observer(path.size() - 1, sol);
    return sol;
  }
  require(problem.discretization == contact::Discretization::Collocation,
          std::string("friction needs the collocation rows, not '") + contact::to_string(problem.discretization) + "'");
  const BasicHFSolver<Dim> solver(with_step(problem, path.front()));  // assembles A, the pair, the quadrature
  const mesh::SimplexMesh<Dim>& mesh = solver.problem().mesh;
  Eigen::VectorXd body_forces = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (std::size_t body = 0; body < problem.body_loads.size(); ++body) {
    body_forces += fem::body_load(mesh, static_cast<int>(body), problem.body_loads[body]);
  }
  constexpr int M = Dim - 1;
  const auto R = solver.quadrature().weight.size();
  FrictionState<Dim> state{Eigen::VectorXd::Zero(mesh.num_dofs()), Eigen::VectorXd::Zero(R),
                           Eigen::VectorXd::Zero(M * R)};
  BasicFrictionalSolution<Dim> sol;
  sol.slip = Eigen::VectorXd::Zero(M * R);
  // A_00 is that of every step (the same free DOFs): factorized once for the path. Not SPD (a
  // body held by the contact alone): the whole system by a sparse LU at each iteration. A body
  // the Dirichlet conditions leave free makes A_00 singular, though a factorization may pass at
  // round-off: it is told from the mesh and the conditions (fem/floating_bodies.hpp).
  const bool floating = !solver.floating_bodies().empty();
  std::optional<solve::SelectedInverse> inverse;
  if (friction.linear_solver == FrictionLinearSolver::Schur && !floating) {
    inverse.emplace();
    if (inverse->compute(solver.dofs().restrict_matrix(solver.stiffness()), friction.ordering) !=
        solve::SelectedInverseStatus::Success) {
      inverse.reset();
    }
  }
  for (std::size_t i = 0; i < path.size(); ++i) {
    const auto t_step = Clock::now();
    const StepAlgebra<Dim> a = step_algebra(solver, body_forces, path[i], i);
    FrictionAlgebra<Dim> np;
    np.mesh = &mesh;
    np.pair = &solver.pair();
    np.quadrature = &solver.quadrature();
    np.dofs = &a.dofs;
    np.A00 = &a.A00;
    np.b = &a.b;
    const FrictionState<Dim> start = start_of_step(solver, np, path[i], state, friction, frictionless, floating);
    FrictionStepResult<Dim> step = solve_friction_step(np, state, start, inverse ? &*inverse : nullptr, friction);
    if (floating) flag_slid_free(step.report);
    step.report.time_s = seconds_since(t_step);  // FrictionStepReport::time_s: the whole step
    sol.steps.push_back(step.report);
    sol.slip += step.slip;
    state = step.state;
    set_final(sol, step);
    sol.status = step.report.status;
    if (step.report.status != FrictionStatus::Converged) {
      sol.message = "load step " + std::to_string(i + 1) + " of " + std::to_string(path.size()) + ": " + step.report.message;
      break;
    }
    if (observer) observer(i, sol);
  }
  sol.converged = sol.status == FrictionStatus::Converged;
  sol.time_s = seconds_since(t0);
  return sol;
}

template BasicFrictionalSolution<2> solve_load_path(const BasicContactProblem<2>&, const std::vector<BasicLoadStep<2>>&,
                                                    const FrictionSettings&, const HFSettings&,
                                                    const LoadStepObserver<2>&);
template BasicFrictionalSolution<3> solve_load_path(const BasicContactProblem<3>&, const std::vector<BasicLoadStep<3>>&,
                                                    const FrictionSettings&, const HFSettings&,
                                                    const LoadStepObserver<3>&);

}  // namespace contactrb::hf
