// The semi-smooth Newton solve's state and steps 1-3 and 6 (docs/theory.md, "Semi-smooth
// Newton"); steps 4 and 5 are in newton_globalization.cpp.
#include "contactrb/hf/newton_steps.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "contactrb/common/error.hpp"

namespace contactrb::hf {

using newton_detail::Clock;
using newton_detail::seconds_since;
using newton_detail::sz;

template <int Dim>
NewtonSolve<Dim>::NewtonSolve(const BasicNewtonProblem<Dim>& p, const NewtonSettings& s)
    : p_(p),
      s_(s),
      t_(s.tuning),
      n_(p.dofs->num_free()),
      N_(p.dofs->num_dofs()),
      R_(static_cast<int>(p.quadrature->weight.size())),
      global_to_free_(sz(N_), -1),
      movable_(sz(N_), 0),
      evaluate_(p, s),
      system_(p, s, Dim),
      previous_active_(sz(R_), 0),
      newton_phase_(t_.inner_passes == NewtonInnerPasses::Consistent) {
  for (int i = 0; i < n_; ++i) {
    const int g = p.dofs->free_dofs()[sz(i)];
    global_to_free_[sz(g)] = i;
    movable_[sz(g)] = 1;
  }
  for (const std::vector<int>* nodes : {&p.pair->slave, &p.pair->master}) {
    for (int node : *nodes) {
      for (int c = 0; c < Dim; ++c) {
        const int fi = global_to_free_[sz(Dim * node + c)];
        if (fi >= 0) contact_free_.push_back(fi);
      }
    }
  }
  std::sort(contact_free_.begin(), contact_free_.end());
  contact_free_.erase(std::unique(contact_free_.begin(), contact_free_.end()), contact_free_.end());
}

template <int Dim>
bool NewtonSolve<Dim>::start(const Eigen::VectorXd& u0, const Eigen::VectorXd& lambda) {
  const auto t_initial = Clock::now();
  try {
    st_ = evaluate_(u0, lambda);
  } catch (const Error& e) {
    res_.message = std::string("semi-smooth Newton: the initial guess cannot be evaluated: ") + e.what();
    res_.u0 = u0;
    res_.lambda = lambda;
    return false;
  }
  res_.timings.initial_s = seconds_since(t_initial);
  // When the solver sets the threads (NewtonTuning::blas_threads), everything but the two BLAS-3
  // parts runs with one OpenBLAS thread: the dense LUs of size |A| and the BLAS-2 calls of the
  // substitutions woke OpenBLAS's worker, which then spins (docs/performance.md, "Why the
  // defaults are what they are", "BLAS threads").
  serial_blas_.emplace(system_.blas_threads() > 0 ? 1 : 0);
  if (!system_.factorize(res_.timings, res_.message)) {
    res_.u0 = st_.u0;
    res_.lambda = st_.lambda;
    return false;
  }
  return true;
}

template <int Dim>
bool NewtonSolve<Dim>::finish(solve::KacanovStatus status, std::string message) {
  res_.status = status;
  res_.message = std::move(message);
  res_.u0 = st_.u0;
  res_.lambda = st_.lambda;
  res_.stationarity = st_.stationarity;
  res_.primal = st_.primal;
  res_.dual = st_.dual;
  res_.complementarity = st_.complementarity;
  return false;
}

// docs/theory.md, "Semi-smooth Newton", step 6: the KKT residuals of the iterate (HFKKT, at the
// geometry of u itself) against the tolerance; the iteration cap and a non-finite iterate end
// the solve with their status.
template <int Dim>
bool NewtonSolve<Dim>::keep_iterating(int k) {
  if (!finite(st_)) {
    return finish(solve::KacanovStatus::NonFinite,
                  "semi-smooth Newton iteration " + std::to_string(k) + ": the iterate is not finite (" +
                      residual_text(st_) + ")");
  }
  if (st_.kkt() <= s_.tolerance) return finish(solve::KacanovStatus::Converged, "");
  if (k >= s_.max_iterations) {
    std::ostringstream os;
    os << "semi-smooth Newton did not converge in " << k << " iterations (tolerance " << s_.tolerance << "); last "
       << residual_text(st_);
    return finish(solve::KacanovStatus::MaxIterations, os.str());
  }
  k_ = k;
  it_ = NewtonIteration{};
  it_.residual = st_.kkt();
  it_.merit = st_.merit;
  return true;
}

template <int Dim>
SystemPoint NewtonSolve<Dim>::iterate_point() const {
  return SystemPoint{&system_.z(), &lin_.top, &st_.u0, &st_.maps.d, &st_.lambda};
}

template <int Dim>
std::vector<Eigen::Triplet<double>> NewtonSolve<Dim>::free_hessian(const Eigen::SparseMatrix<double>& H) const {
  std::vector<Eigen::Triplet<double>> h_free;
  for (int j = 0; j < H.outerSize(); ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator h(H, j); h; ++h) {
      const int fr = global_to_free_[sz(static_cast<int>(h.row()))];
      const int fc = global_to_free_[sz(static_cast<int>(h.col()))];
      if (fr >= 0 && fc >= 0) h_free.emplace_back(fr, fc, h.value());
    }
  }
  return h_free;
}

// docs/theory.md, "Semi-smooth Newton", step 1: the consistent linearization of the geometry
// (D = d'(u), H = (K(u)' lambda)') at the iterate, in the Newton phase only: the Kacanov
// phase's frozen steps need K and d, already in the iterate's maps. Analytic by default
// (docs/performance.md, "Why the defaults are what they are", "Newton: analytic linearization").
template <int Dim>
bool NewtonSolve<Dim>::linearize() {
  kacanov_phase_ = !newton_phase_;
  const auto t0 = Clock::now();
  contact::ContactLinearizationOf<Dim> lin;
  if (!kacanov_phase_) {
    try {
      lin = contact::linearize_contact(*p_.mesh, *p_.pair, *p_.quadrature, st_.u, st_.lambda, movable_, st_.maps,
                                       s_.linearization);
    } catch (const Error& e) {
      return finish(solve::KacanovStatus::StepFailed, "semi-smooth Newton iteration " + std::to_string(k_) +
                                                          ": the contact maps cannot be linearized: " + e.what());
    }
  } else {
    lin.D.resize(R_, N_);
    lin.H.resize(N_, N_);
  }
  it_.colours = lin.colours;
  it_.linearize_s = seconds_since(t0);
  lin_.D0 = p_.dofs->restrict_columns(lin.D);
  if (system_.solver() == NewtonLinearSolver::Amg) {
    forcing_ = newton_forcing_term(s_, !kacanov_phase_, it_.residual, previous_residual_, forcing_);
    previous_residual_ = kacanov_phase_ ? 0.0 : it_.residual;  // the Newton phase's own ratios only
    it_.forcing = forcing_;
  }
  system_.begin_iteration(k_, forcing_);
  system_.set_read_dofs(st_.K0, lin_);
  t_systems_ = Clock::now();
  lin_.H = free_hessian(lin.H);
  // SaddleLU's right-hand side b - A_00 u_0 (ActiveSchur reads z instead).
  if (!system_.schur()) lin_.top = *p_.b - *p_.A00 * st_.u0;
  at_ = iterate_point();
  singular_consistent_ = false;
  failure_.clear();
  step_ = NewtonStep{};
  step_.du = Eigen::VectorXd::Zero(n_);
  step_.lambda = st_.lambda;
  have_full_trial_ = false;
  plain_ = NewtonStep{};
  return true;
}

// One system on the active rows `act` (step_ set). False when it is singular (failure_ says
// why when it was the frozen one).
template <int Dim>
bool NewtonSolve<Dim>::solve_system(const std::vector<char>& act, bool frozen) {
  std::vector<int> active;
  for (int r = 0; r < R_; ++r) {
    if (act[sz(r)]) active.push_back(r);
  }
  ++it_.factorizations;
  it_.active = static_cast<int>(active.size());
  std::string what;
  if (system_.solve(active, frozen, st_.K0, lin_, at_, step_, it_, what)) return true;
  if (frozen) failure_ = "semi-smooth Newton iteration " + std::to_string(k_) + ": " + what + "; " + residual_text(st_);
  return false;
}

// A system on the consistent Jacobian, falling back to the frozen one (for the rest of the
// iteration) when it is singular (e.g. a slave node at an open master end).
template <int Dim>
bool NewtonSolve<Dim>::solve_newton_system(const std::vector<char>& act) {
  if (!singular_consistent_ && solve_system(act, false)) return true;
  if (!singular_consistent_) {
    singular_consistent_ = true;
    it_.frozen = true;
  }
  return solve_system(act, true);
}

// The predicted active set: the complementarity function of the LINEARIZED gap, d + D du
// (consistent) or d - K du (frozen), with the step's multipliers. Returns the rows that changed.
template <int Dim>
int NewtonSolve<Dim>::predict_active(std::vector<char>& out, bool frozen) const {
  const Eigen::VectorXd& du = step_.du;
  const Eigen::VectorXd d_lin = frozen ? Eigen::VectorXd(st_.maps.d - st_.K0 * du) : Eigen::VectorXd(st_.maps.d + lin_.D0 * du);
  int changed = 0;
  for (int r = 0; r < R_; ++r) {
    // A non-candidate row (zero K row: no master faces the slave node) never binds.
    const bool candidate = st_.K0.outerIndexPtr()[r + 1] > st_.K0.outerIndexPtr()[r];
    const char a = candidate && step_.lambda(r) - evaluate_.c()(r) * d_lin(r) > 0.0 ? 1 : 0;
    if (a != out[sz(r)]) ++changed;
    out[sz(r)] = a;
  }
  return changed;
}

// docs/theory.md, "Semi-smooth Newton", step 2: the active set of the iterate (du = 0), the
// system on it, then primal-dual active-set passes while the set predicted from the linearized
// gap moves. Kacanov phase: on the frozen linearization, a strictly convex QP on which the
// passes settle (an undamped Kacanov step). Newton phase: the plain semi-smooth Newton step on
// the consistent linearization, then at most max_newton_passes passes on it (their LCP is not
// monotone; docs/performance.md, "Why the defaults are what they are", "Newton: Kacanov phase
// first" and "Newton: consistent passes capped").
template <int Dim>
bool NewtonSolve<Dim>::solve_on_active_set() {
  is_active_.assign(sz(R_), 0);
  predict_active(is_active_, false);
  for (int r = 0; r < R_; ++r) it_.changed += is_active_[sz(r)] != previous_active_[sz(r)];
  if (!(kacanov_phase_ ? solve_system(is_active_, true) : solve_newton_system(is_active_))) {
    return finish(solve::KacanovStatus::StepFailed, failure_);
  }
  first_ = step_;
  passes_ = 1;
  pass_frozen_ = kacanov_phase_ || singular_consistent_;
  const int max_passes = pass_frozen_ ? t_.max_inner_iterations : std::min(t_.max_inner_iterations, t_.max_newton_passes);
  while (passes_ < max_passes && predict_active(is_active_, pass_frozen_) != 0) {
    if (!(pass_frozen_ ? solve_system(is_active_, true) : solve_newton_system(is_active_))) {
      return finish(solve::KacanovStatus::StepFailed, failure_);
    }
    ++passes_;
  }
  return true;
}

// docs/theory.md, "Semi-smooth Newton", step 3: branch passes (Newton phase, pointwise rows,
// near the solution). The contact maps are piecewise smooth (the closest segment; a vertex's
// clamped wedge); a step that carries slave nodes across such a kink converges only linearly.
// When u + du lies on other branches than u, the step is solved again with the maps at u
// continued on the branches of u + du (contact::linearize_contact_on_branches): exact on
// piecewise linear maps; repeated while the branches move, at most max_branch_passes times
// (docs/performance.md, "Why the defaults are what they are", "Newton: branch passes near the
// solution"). Then the whole step. 2D only: the continuation on branches is 2D only
// (docs/solvers.md, "Three dimensions").
template <int Dim>
void NewtonSolve<Dim>::branch_passes() {
  if (contact::has_branch_continuation<Dim> && !pass_frozen_ && t_.max_branch_passes > 0 &&
      it_.residual <= t_.branch_passes_below &&
      p_.quadrature->discretization != contact::Discretization::LAC) {
    for (int pass = 0; pass < t_.max_branch_passes && branch_pass(); ++pass) {
      ++passes_;
      ++it_.branch_passes;
    }
  }
  system_.complete(step_, at_);
}

// One branch pass; false when the branches do not move (or cannot be evaluated, or the system
// is singular: the previous pass's step stays).
template <int Dim>
bool NewtonSolve<Dim>::branch_pass() {
  if constexpr (!contact::has_branch_continuation<Dim>) {
    return false;
  } else {
    // The projection at u + du reads du at the contact nodes only (beyond the read DOFs): the
    // backward substitution along their chains gives those entries bitwise as the complete step
    // would, without a substitution through all of L.
    Eigen::VectorXd du_contact = step_.du;
    if (!step_.complete) {
      const Eigen::VectorXd x = system_.inverse().solve_sparse(step_.E, step_.yE, &contact_free_);
      for (int fi : contact_free_) du_contact(fi) = system_.z()(fi) - x(fi) - st_.u0(fi);
    }
    contact::PointwiseContact next;
    try {
      next = contact::project_slave_nodes(*p_.mesh, *p_.pair, p_.dofs->lift() + p_.dofs->extend(st_.u0 + du_contact),
                                          s_.linearization.projection);
    } catch (const Error&) {
      return false;  // the full step cannot be evaluated: the line search shortens it
    }
    bool moved = false;
    for (std::size_t q = 0; q < next.projection.size() && !moved; ++q) {
      moved = !contact::same_branch(st_.maps.pointwise.projection[q], next.projection[q]);
    }
    if (!moved) return false;
    contact::ContactLinearization branch;
    try {
      branch = contact::linearize_contact_on_branches(*p_.mesh, *p_.pair, *p_.quadrature, st_.u, st_.lambda, movable_, next);
    } catch (const Error&) {
      return false;
    }
    // The step's system reads K, d (the iterate's maps) and D, H: all on the continued branches
    // now. The merit and the line search keep the maps of u itself (the trials are evaluated afresh).
    st_.maps = std::move(branch.maps);
    st_.K0 = p_.dofs->restrict_columns(st_.maps.rows.K);
    lin_.D0 = p_.dofs->restrict_columns(branch.D);
    lin_.H = free_hessian(branch.H);
    system_.set_read_dofs(st_.K0, lin_);
    return solve_newton_system(is_active_);
  }
}

// docs/theory.md, "Semi-smooth Newton", step 3: the Kacanov phase ends after an iteration whose
// frozen passes found the active set at once (switch_passes): the iterate is near enough for
// Newton.
template <int Dim>
void NewtonSolve<Dim>::switch_phase() {
  if (kacanov_phase_ && passes_ <= t_.switch_passes) newton_phase_ = true;
  previous_active_ = is_active_;
}

// The members defined here; those of newton_globalization.cpp are instantiated there.
template class NewtonSolve<2>;
template class NewtonSolve<3>;

}  // namespace contactrb::hf
