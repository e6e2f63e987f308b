#include "contactrb/hf/hf_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <mutex>
#include <sstream>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/fem/floating_bodies.hpp"
#include "contactrb/fem/sparsity.hpp"
#include "contactrb/fem/traction.hpp"
#include "contactrb/hf/contact_condensation.hpp"
#include "contactrb/hf/multiplier_scale.hpp"

namespace contactrb::hf {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// HFSetupOptions::amg_from_free_dofs: the Auto solve of this problem takes Amg.
bool amg_in_auto(const HFSetupOptions& options, int dimension, int free_dofs) {
  if (options.amg_from_free_dofs < 0) return false;
  NewtonSettings settings;
  settings.linear_solver = NewtonLinearSolver::Auto;
  settings.amg_from_free_dofs = options.amg_from_free_dofs;
  return resolved_linear_solver(settings, dimension, free_dofs) == NewtonLinearSolver::Amg;
}
}  // namespace

const char* to_string(HFMethod method) {
  switch (method) {
    case HFMethod::Newton: return "newton";
    case HFMethod::Kacanov: return "kacanov";
  }
  return "unknown";
}

HFMethod hf_method_from_string(const std::string& name) {
  return enum_from_string(name, "HF solver", std::array{HFMethod::Newton, HFMethod::Kacanov});
}

HFMethod default_method(int dimension, int level) {
  return dimension == 2 && level == 0 ? HFMethod::Kacanov : HFMethod::Newton;
}

double HFKKT::max() const { return std::max({stationarity, primal, dual, complementarity}); }

template <int Dim>
struct BasicHFSolver<Dim>::Impl {
  BasicContactProblem<Dim> problem;
  fem::DofMap dofs;
  contact::ContactPairOf<Dim> pair;
  contact::ContactQuadrature quadrature;
  Eigen::SparseMatrix<double> A;  // global
  Eigen::VectorXd f;              // global
  Eigen::SparseMatrix<double> A00_matrix;  // A restricted to the free DOFs
  Eigen::VectorXd b;              // f_0 - (A u_D)_0
  std::vector<int> contact_free;  // free indices of contact-boundary DOFs
  std::vector<int> free_to_contact;  // free index -> position in contact_free or -1
  double setup_time = 0.0;
  // Kacanov only, built on first use (ensure_condensation): the factorization of A_00 and
  // S = (A_00^-1)[c, c], z = A_00^-1 b and its contact entries z_c.
  mutable std::mutex condensation_mutex;
  mutable std::unique_ptr<ContactCondensation> A00;
  mutable Eigen::VectorXd z;
  mutable Eigen::VectorXd z_c;
  mutable double condensation_time = 0.0;
  std::vector<int> floating;  // bodies the Dirichlet conditions leave free (fem/floating_bodies.hpp)
  // HFSetupOptions::keep_newton_factor: the last Newton solve's factor of A_00 (under
  // condensation_mutex).
  bool keep_newton_factor = false;
  mutable std::shared_ptr<solve::SelectedInverse> newton_factor;

  void ensure_condensation() const {
    const std::lock_guard<std::mutex> lock(condensation_mutex);
    if (A00) return;
    const auto t0 = Clock::now();
    // S = (A_00^-1)[c, c] from the factorization with the contact DOFs ordered last.
    auto factor = std::make_unique<ContactCondensation>(A00_matrix, contact_free);
    z = factor->solve(b);
    const int nc = static_cast<int>(contact_free.size());
    z_c.resize(nc);
    for (int i = 0; i < nc; ++i) z_c(i) = z(contact_free[static_cast<std::size_t>(i)]);
    A00 = std::move(factor);
    condensation_time = seconds_since(t0);
  }

  // K restricted to contact free DOFs (R x nc) and the lifted gap g - K u_D.
  void restrict_rows(const contact::ConstraintRows& rows, RowSparse& Kc, Eigen::VectorXd& g_lift) const {
    const Eigen::VectorXd& lift = dofs.lift();
    g_lift = rows.g - rows.K * lift;
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(static_cast<std::size_t>(rows.K.nonZeros()));
    for (int r = 0; r < rows.K.outerSize(); ++r) {
      for (RowSparse::InnerIterator it(rows.K, r); it; ++it) {
        const int fi = global_to_free[static_cast<std::size_t>(it.col())];
        if (fi < 0) continue;
        const int ci = free_to_contact[static_cast<std::size_t>(fi)];
        if (ci < 0) throw Error("internal: constraint row touches a DOF outside the contact boundaries");
        trip.emplace_back(r, ci, it.value());
      }
    }
    Kc.resize(rows.K.rows(), static_cast<Eigen::Index>(contact_free.size()));
    Kc.setFromTriplets(trip.begin(), trip.end());
  }
  std::vector<int> global_to_free;

  Eigen::VectorXd total(const Eigen::VectorXd& u0) const { return dofs.lift() + dofs.extend(u0); }
  void finish(BasicHFSolution<Dim>& sol, Clock::time_point t0) const;
  BasicHFSolution<Dim> solve_newton(const NewtonSettings& settings, const Eigen::VectorXd& u0_start,
                          const Eigen::VectorXd& lambda_start, Clock::time_point t0) const;

  // HFSetupOptions::newton_analysis: the analysis of A_00's pattern, on its thread (the future),
  // then kept for every solve. Declared last: destroyed first, so that an unfinished analysis is
  // waited for before the mesh and the DOF map it reads go.
  mutable std::mutex analysis_mutex;
  mutable std::shared_ptr<const solve::FactorAnalysis> analysis;
  mutable std::future<solve::FactorAnalysis> analysis_future;
  // The analysis (waits for it the first time), nullptr when none was started or it failed (the
  // solve then analyses A_00 itself).
  const solve::FactorAnalysis* prepared_analysis() const {
    const std::lock_guard<std::mutex> lock(analysis_mutex);
    if (analysis_future.valid()) {
      try {
        analysis = std::make_shared<const solve::FactorAnalysis>(analysis_future.get());
      } catch (const std::exception&) {
        analysis.reset();  // e.g. out of memory on the analysis thread: analysed in the solve instead
      }
    }
    return analysis && analysis->valid() ? analysis.get() : nullptr;
  }
};

HFSetupOptions setup_options_for(const HFSettings& settings) {
  HFSetupOptions o;
  const NewtonLinearSolver linear = settings.newton.linear_solver;
  o.newton_analysis = settings.method == HFMethod::Newton &&
                      (linear == NewtonLinearSolver::ActiveSchur || linear == NewtonLinearSolver::Auto);
  o.ordering = settings.newton.ordering;
  if (linear == NewtonLinearSolver::Auto) o.amg_from_free_dofs = settings.newton.amg_from_free_dofs;
  return o;
}

template <int Dim>
BasicHFSolver<Dim>::BasicHFSolver(Problem problem, const HFSetupOptions& options) : impl_(std::make_unique<Impl>()) {
  const auto t0 = Clock::now();
  check_problem(problem);
  Impl& m = *impl_;
  m.problem = std::move(problem);
  m.keep_newton_factor = options.keep_newton_factor;
  const mesh::SimplexMesh<Dim>& mesh = m.problem.mesh;
  m.dofs = fem::DofMap(mesh, m.problem.dirichlet);
  require(m.dofs.num_free() > 0, "every DOF is prescribed: nothing to solve");
  // The nodal pattern of A (fem::stiffness), shared with the analysis thread below.
  std::shared_ptr<const fem::SimplexSparsity<Dim>> pattern;
  if (options.newton_analysis && !amg_in_auto(options, Dim, m.dofs.num_free())) {
    // The pattern of A_00 is the mesh's nodal pattern restricted to the free DOFs
    // (DofMap::restrict_matrix): known before any value, so its ordering and symbolic analysis
    // (hertz-a level 7: 4 s; the assembly and the rest of this constructor: 2.3 s) run beside
    // the assembly. The solve checks that A_00 has exactly this pattern before using it.
    pattern = std::make_shared<const fem::SimplexSparsity<Dim>>(mesh, fem::cells_of_body(mesh, -1));
    const solve::FactorOrdering ordering = options.ordering;
    m.analysis_future = std::async(std::launch::async, [pattern, &dofs = m.dofs, ordering] {
      std::vector<int> outer, inner;
      pattern->restricted_pattern(dofs.free_dofs(), outer, inner);
      return solve::FactorAnalysis::analyze(dofs.num_free(), std::move(outer), std::move(inner), ordering);
    });
  }
  m.pair = contact::make_contact_pair(mesh);
  m.quadrature = contact::make_quadrature(mesh, m.pair, m.problem.discretization);
  {
    // A slave boundary with no master facing it cannot make contact: almost surely a
    // mislabelled group (e.g. the two contact groups swapped or on far-apart bodies).
    const contact::PointwiseContactOf<Dim> pw = contact::project_slave_nodes(mesh, m.pair, m.dofs.lift());
    int candidates = 0;
    for (const auto& p : pw.projection) candidates += p.candidate ? 1 : 0;
    require(candidates > 0, "no node of the slave boundary faces the master boundary (" +
                                std::to_string(m.pair.slave.size()) +
                                " slave nodes, none projects inside the master " +
                                (Dim == 2 ? "polyline" : "surface") + "): check the 'slave' and 'master' groups");
  }
  m.A = pattern ? fem::stiffness(mesh, m.problem.materials, *pattern) : fem::stiffness(mesh, m.problem.materials);
  m.f = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (std::size_t body = 0; body < m.problem.body_loads.size(); ++body) {
    m.f += fem::body_load(mesh, static_cast<int>(body), m.problem.body_loads[body]);
  }
  for (const fem::SurfaceLoad<Dim>& t : m.problem.tractions) m.f += fem::traction_load(mesh, t);
  m.b = m.dofs.restrict(m.f - m.A * m.dofs.lift());
  m.global_to_free.assign(static_cast<std::size_t>(mesh.num_dofs()), -1);
  for (int i = 0; i < m.dofs.num_free(); ++i) {
    m.global_to_free[static_cast<std::size_t>(m.dofs.free_dofs()[static_cast<std::size_t>(i)])] = i;
  }
  m.free_to_contact.assign(static_cast<std::size_t>(m.dofs.num_free()), -1);
  std::vector<int> nodes = m.pair.slave;
  nodes.insert(nodes.end(), m.pair.master.begin(), m.pair.master.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  for (int node : nodes) {
    for (int c = 0; c < Dim; ++c) {
      const int fi = m.global_to_free[static_cast<std::size_t>(Dim * node + c)];
      if (fi < 0) continue;
      m.free_to_contact[static_cast<std::size_t>(fi)] = static_cast<int>(m.contact_free.size());
      m.contact_free.push_back(fi);
    }
  }
  m.A00_matrix = m.dofs.restrict_matrix(m.A);
  m.floating = fem::floating_bodies(mesh, m.dofs);
  m.setup_time = seconds_since(t0);
}

template <int Dim>
BasicHFSolver<Dim>::~BasicHFSolver() = default;
template <int Dim>
BasicHFSolver<Dim>::BasicHFSolver(BasicHFSolver&&) noexcept = default;
template <int Dim>
BasicHFSolver<Dim>& BasicHFSolver<Dim>::operator=(BasicHFSolver&&) noexcept = default;

template <int Dim>
const BasicContactProblem<Dim>& BasicHFSolver<Dim>::problem() const { return impl_->problem; }
template <int Dim>
const contact::ContactPairOf<Dim>& BasicHFSolver<Dim>::pair() const { return impl_->pair; }
template <int Dim>
const contact::ContactQuadrature& BasicHFSolver<Dim>::quadrature() const { return impl_->quadrature; }
template <int Dim>
const fem::DofMap& BasicHFSolver<Dim>::dofs() const { return impl_->dofs; }
template <int Dim>
const std::vector<int>& BasicHFSolver<Dim>::floating_bodies() const { return impl_->floating; }
template <int Dim>
const Eigen::SparseMatrix<double>& BasicHFSolver<Dim>::stiffness() const { return impl_->A; }
template <int Dim>
const Eigen::VectorXd& BasicHFSolver<Dim>::load() const { return impl_->f; }
template <int Dim>
std::optional<Eigen::MatrixXd> BasicHFSolver<Dim>::held_inverse_block(const std::vector<int>& idx) const {
  const Impl& m = *impl_;
  const std::lock_guard<std::mutex> lock(m.condensation_mutex);
  if (!m.A00 && m.newton_factor) {
    for (int fi : idx) {
      if (fi < 0 || fi >= m.dofs.num_free()) return std::nullopt;
    }
    return m.newton_factor->block(idx);
  }
  if (!m.A00) return std::nullopt;
  std::vector<Eigen::Index> at;
  at.reserve(idx.size());
  for (int fi : idx) {
    if (fi < 0 || fi >= m.dofs.num_free() || m.free_to_contact[static_cast<std::size_t>(fi)] < 0) return std::nullopt;
    at.push_back(m.free_to_contact[static_cast<std::size_t>(fi)]);
  }
  return Eigen::MatrixXd(m.A00->contact_inverse()(at, at));
}
template <int Dim>
double BasicHFSolver<Dim>::setup_time_s() const {
  const std::lock_guard<std::mutex> lock(impl_->condensation_mutex);
  return impl_->setup_time + impl_->condensation_time;
}

template <int Dim>
BasicHFSolution<Dim> BasicHFSolver<Dim>::solve(const HFSettings& settings) const {
  return solve(settings, HFInitialGuess{});
}

template <int Dim>
BasicHFSolution<Dim> BasicHFSolver<Dim>::solve(const HFSettings& settings, const HFInitialGuess& guess) const {
  const auto t0 = Clock::now();
  const Impl& m = *impl_;
  const mesh::SimplexMesh<Dim>& mesh = m.problem.mesh;
  const int R = static_cast<int>(m.quadrature.weight.size());
  require(guess.u.size() == 0 || guess.u.size() == mesh.num_dofs(),
          "HF initial guess: u has " + std::to_string(guess.u.size()) + " entries for " +
              std::to_string(mesh.num_dofs()) + " DOFs");
  require(guess.lambda.size() == 0 || guess.lambda.size() == R,
          "HF initial guess: lambda has " + std::to_string(guess.lambda.size()) + " entries for " +
              std::to_string(R) + " constraint rows");
  // Without friction only the Dirichlet conditions hold a body tangentially: a floating one makes
  // A_00 singular, which a sparse factorization may or may not notice at round-off.
  if (!m.floating.empty()) {
    const int b = m.floating.front();
    throw Error("body " + std::to_string(b) + " (" + (b == mesh::kSlaveBody ? "slave" : "master") +
                ") is not held by the Dirichlet conditions: one of its rigid motions moves none of its prescribed "
                "DOFs, and without friction nothing else holds it (prescribe more components, or solve with "
                "friction)");
  }
  const Eigen::VectorXd u0_start =
      guess.u.size() > 0 ? m.dofs.restrict(guess.u) : Eigen::VectorXd::Zero(m.dofs.num_free());
  const Eigen::VectorXd lambda_start = guess.lambda.size() > 0 ? guess.lambda : Eigen::VectorXd::Zero(R);
  if (settings.method == HFMethod::Newton) return m.solve_newton(settings.newton, u0_start, lambda_start, t0);

  solve::check_settings(settings.kacanov);
  m.ensure_condensation();
  BasicHFSolution<Dim> sol;
  sol.method = HFMethod::Kacanov;
  std::vector<int> warm;  // passive set of the previous QP
  contact::PointwiseContactOf<Dim> last_pointwise;
  contact::ConstraintRows last_rows;
  Eigen::VectorXd last_g_lift;
  RowSparse last_Kc;
  Eigen::VectorXd last_u0;

  // One linearized step (12): K, g frozen at the previous iterate u.
  solve::KacanovStep step = [&](const Eigen::VectorXd& u, const Eigen::VectorXd&, Eigen::VectorXd& u_bar,
                                Eigen::VectorXd& lambda_bar, int& inner, std::string& message) {
    contact::PointwiseContactOf<Dim> pw;
    try {
      pw = contact::project_slave_nodes(mesh, m.pair, u);
    } catch (const Error& e) {  // an iterate the geometry cannot handle (non-finite, overflowing)
      message = e.what();
      return false;
    }
    contact::ConstraintRows rows = contact::constraint_rows(mesh, m.pair, m.quadrature, pw, u);
    RowSparse Kc;
    Eigen::VectorXd g_lift;
    m.restrict_rows(rows, Kc, g_lift);
    // Dual QP: min 1/2 l' Q l - c' l, Q = K_0 A_00^-1 K_0', c = K_0 A_00^-1 b - (g - K u_D).
    const Eigen::MatrixXd KS = Kc * m.A00->contact_inverse();  // S = (A_00^-1)[c, c]
    Eigen::MatrixXd Q = KS * Kc.transpose();
    Q = 0.5 * (Q + Q.transpose());
    const Eigen::VectorXd c = Kc * m.z_c - g_lift;
    const solve::QPResult qp = solve::solve_nonnegative_qp(Q, c, settings.qp, warm);
    inner = qp.iterations;
    if (qp.status != solve::QPStatus::Solved) {
      message = std::string("contact QP ") + solve::to_string(qp.status) + ": " + qp.message;
      return false;
    }
    warm = qp.passive;
    lambda_bar = qp.x;
    // u_0 = A_00^-1 (b - K_0' lambda): one back-solve.
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m.dofs.num_free());
    const Eigen::VectorXd Kt_lambda_c = Kc.transpose() * lambda_bar;
    for (int i = 0; i < Kt_lambda_c.size(); ++i) rhs(m.contact_free[static_cast<std::size_t>(i)]) = Kt_lambda_c(i);
    last_u0 = m.z - m.A00->solve(rhs);
    u_bar = m.total(last_u0);
    last_pointwise = std::move(pw);
    last_rows = std::move(rows);
    last_g_lift = std::move(g_lift);
    last_Kc = std::move(Kc);
    return true;
  };

  const Eigen::VectorXd u_start = m.total(u0_start);
  solve::KacanovResult kr = solve::kacanov(step, u_start, lambda_start, settings.kacanov);
  sol.status = kr.status;
  sol.converged = kr.status == solve::KacanovStatus::Converged;
  sol.message = kr.message;
  sol.iterations = kr.iterations;
  sol.history = kr.history;
  if (kr.u_bar.size() == 0) {  // the very first step failed
    sol.u = u_start;
    sol.u0 = Eigen::VectorXd::Zero(m.dofs.num_free());
    sol.lambda = Eigen::VectorXd::Zero(R);
    sol.time_s = seconds_since(t0) + m.setup_time;
    return sol;  // (setup_time: the condensation built in this solve is inside seconds_since(t0))
  }
  sol.u = kr.u_bar;
  sol.u0 = last_u0;
  sol.lambda = kr.lambda_bar;
  sol.pointwise = std::move(last_pointwise);
  sol.rows = std::move(last_rows);

  // KKT residuals of (u_bar, lambda_bar) for the linearized problem it solved.
  Eigen::VectorXd Kt_lambda = Eigen::VectorXd::Zero(m.dofs.num_free());
  const Eigen::VectorXd Ktl_c = last_Kc.transpose() * sol.lambda;
  for (int i = 0; i < Ktl_c.size(); ++i) Kt_lambda(m.contact_free[static_cast<std::size_t>(i)]) = Ktl_c(i);
  const double force_scale = std::max({m.b.norm(), Kt_lambda.norm(), 1e-300});
  sol.kkt.stationarity = (m.A00_matrix * sol.u0 + Kt_lambda - m.b).norm() / force_scale;
  Eigen::VectorXd u0_c(static_cast<Eigen::Index>(m.contact_free.size()));
  for (int i = 0; i < u0_c.size(); ++i) u0_c(i) = sol.u0(m.contact_free[static_cast<std::size_t>(i)]);
  const Eigen::VectorXd slack = last_g_lift - last_Kc * u0_c;  // >= 0 when feasible
  // Gap scale that cannot cancel: |g|_inf and the largest row sum of |K_rj| |u_j| (with
  // matching meshes both g and K u vanish together at the solution).
  Eigen::VectorXd abs_u(static_cast<Eigen::Index>(m.contact_free.size()));
  for (int i = 0; i < abs_u.size(); ++i) abs_u(i) = std::abs(u0_c(i));
  const double row_scale = (last_Kc.cwiseAbs() * abs_u).maxCoeff();
  const double gap_scale = std::max({last_g_lift.cwiseAbs().maxCoeff(), row_scale, 1e-300});
  const MultiplierScale lambda_scale = multiplier_scale(m.A00_matrix, m.b, sol.u0, sol.lambda, m.quadrature.weight);
  sol.kkt.primal = std::max(0.0, -slack.minCoeff()) / gap_scale;
  sol.kkt.dual = lambda_scale.relative(std::max(0.0, -sol.lambda.minCoeff()));
  sol.kkt.complementarity =
      sol.lambda.cwiseProduct(slack).cwiseAbs().maxCoeff() / (lambda_scale.value() * gap_scale);

  m.finish(sol, t0);
  return sol;
}

// The report common to both methods: nonlinear feasibility, energy, force, finiteness.
template <int Dim>
void BasicHFSolver<Dim>::Impl::finish(BasicHFSolution<Dim>& sol, Clock::time_point t0) const {
  const mesh::SimplexMesh<Dim>& mesh = problem.mesh;
  // Nonlinear feasibility: geometry re-evaluated at the returned displacement.
  std::string geometry_failure;
  try {
    const contact::PointwiseContactOf<Dim> at_u = contact::project_slave_nodes(mesh, pair, sol.u);
    const Eigen::VectorXd violation = at_u.K * sol.u - at_u.g;
    sol.gap_violation = std::max(0.0, violation.maxCoeff());
  } catch (const Error& e) {  // the returned displacement overflows the projection
    sol.gap_violation = INFINITY;
    geometry_failure = e.what();
  }

  sol.energy = 0.5 * sol.u.dot(A * sol.u) - f.dot(sol.u);
  sol.contact_force = sol.lambda.dot(quadrature.weight);
  // Finite iterates can still give a non-finite result (u of 1e154: u'Au overflows; of 1e155:
  // the projection's squared distances). Not an answer: flagged, never "converged". (A solve
  // that already failed keeps its own status and message.)
  if (sol.converged && (!geometry_failure.empty() || !std::isfinite(sol.energy) ||
                        !std::isfinite(sol.contact_force) || !std::isfinite(sol.gap_violation))) {
    std::ostringstream os;
    if (!geometry_failure.empty()) {
      os << "the returned displacement cannot be checked against the contact geometry: " << geometry_failure;
    } else {
      os << "the solution is not finite (energy " << sol.energy << ", contact force " << sol.contact_force
         << ", gap violation " << sol.gap_violation << "): the data overflow double precision";
    }
    sol.status = solve::KacanovStatus::NonFinite;
    sol.converged = false;
    sol.message = os.str();
  }
  sol.active_constraints = static_cast<int>((sol.lambda.array() > 0.0).count());
  sol.time_s = seconds_since(t0) + setup_time;
}


template <int Dim>
BasicHFSolution<Dim> BasicHFSolver<Dim>::Impl::solve_newton(const NewtonSettings& settings,
                                                           const Eigen::VectorXd& u0_start,
                                                           const Eigen::VectorXd& lambda_start,
                                                           Clock::time_point t0) const {
  BasicNewtonProblem<Dim> np;
  np.mesh = &problem.mesh;
  np.pair = &pair;
  np.quadrature = &quadrature;
  np.dofs = &dofs;
  np.A00 = &A00_matrix;
  np.b = &b;
  np.a00_analysis = [this] { return prepared_analysis(); };
  NewtonSettings run = settings;
  run.keep_factor = keep_newton_factor;
  NewtonResult nr = semismooth_newton(np, u0_start, lambda_start, run);
  if (nr.a00_factor) {
    const std::lock_guard<std::mutex> lock(condensation_mutex);
    newton_factor = std::move(nr.a00_factor);
  }
  BasicHFSolution<Dim> sol;
  sol.method = HFMethod::Newton;
  sol.status = nr.status;
  sol.converged = nr.status == solve::KacanovStatus::Converged;
  sol.message = nr.message;
  sol.iterations = nr.iterations;
  sol.newton_history = nr.history;
  sol.newton_timings = nr.timings;
  sol.u0 = nr.u0;
  sol.u = total(nr.u0);
  sol.lambda = nr.lambda;
  sol.kkt.stationarity = nr.stationarity;
  sol.kkt.primal = nr.primal;
  sol.kkt.dual = nr.dual;
  sol.kkt.complementarity = nr.complementarity;
  try {  // the geometry of the returned u (Newton's K, g are those of u itself)
    sol.pointwise = contact::project_slave_nodes(problem.mesh, pair, sol.u);
    sol.rows = contact::constraint_rows(problem.mesh, pair, quadrature, sol.pointwise, sol.u);
  } catch (const Error&) {
    // finish() re-evaluates the geometry and reports the failure.
  }
  finish(sol, t0);
  return sol;
}

template class BasicHFSolver<2>;
template class BasicHFSolver<3>;

}  // namespace contactrb::hf
