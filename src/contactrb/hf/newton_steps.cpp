#include "contactrb/hf/newton_steps.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "contactrb/common/error.hpp"

namespace contactrb::hf {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
inline std::size_t sz(int i) { return static_cast<std::size_t>(i); }
}  // namespace

NewtonSolve::NewtonSolve(const NewtonProblem& p, const NewtonSettings& s)
    : p_(p),
      s_(s),
      t_(s.tuning),
      n_(p.dofs->num_free()),
      N_(p.dofs->num_dofs()),
      R_(static_cast<int>(p.quadrature->weight.size())),
      global_to_free_(sz(N_), -1),
      movable_(sz(N_), 0),
      evaluate_(p, s),
      system_(p, s),
      previous_active_(sz(R_), 0),
      newton_phase_(t_.inner_passes == NewtonInnerPasses::Consistent) {
  for (int i = 0; i < n_; ++i) {
    const int g = p.dofs->free_dofs()[sz(i)];
    global_to_free_[sz(g)] = i;
    movable_[sz(g)] = 1;
  }
  for (const std::vector<int>* nodes : {&p.pair->slave, &p.pair->master}) {
    for (int node : *nodes) {
      for (int c = 0; c < 2; ++c) {
        const int fi = global_to_free_[sz(2 * node + c)];
        if (fi >= 0) contact_free_.push_back(fi);
      }
    }
  }
  std::sort(contact_free_.begin(), contact_free_.end());
  contact_free_.erase(std::unique(contact_free_.begin(), contact_free_.end()), contact_free_.end());
}

bool NewtonSolve::start(const Eigen::VectorXd& u0, const Eigen::VectorXd& lambda) {
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

bool NewtonSolve::finish(solve::KacanovStatus status, std::string message) {
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
bool NewtonSolve::keep_iterating(int k) {
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

SystemPoint NewtonSolve::iterate_point() const {
  return SystemPoint{&system_.z(), &lin_.top, &st_.u0, &st_.maps.d, &st_.lambda};
}

std::vector<Eigen::Triplet<double>> NewtonSolve::free_hessian(const Eigen::SparseMatrix<double>& H) const {
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
bool NewtonSolve::linearize() {
  kacanov_phase_ = !newton_phase_;
  const auto t0 = Clock::now();
  contact::ContactLinearization lin;
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
bool NewtonSolve::solve_system(const std::vector<char>& act, bool frozen) {
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
bool NewtonSolve::solve_newton_system(const std::vector<char>& act) {
  if (!singular_consistent_ && solve_system(act, false)) return true;
  if (!singular_consistent_) {
    singular_consistent_ = true;
    it_.frozen = true;
  }
  return solve_system(act, true);
}

// The predicted active set: the complementarity function of the LINEARIZED gap, d + D du
// (consistent) or d - K du (frozen), with the step's multipliers. Returns the rows that changed.
int NewtonSolve::predict_active(std::vector<char>& out, bool frozen) const {
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
bool NewtonSolve::solve_on_active_set() {
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
// solution"). Then the whole step.
void NewtonSolve::branch_passes() {
  if (!pass_frozen_ && t_.max_branch_passes > 0 && it_.residual <= t_.branch_passes_below &&
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
bool NewtonSolve::branch_pass() {
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

// docs/theory.md, "Semi-smooth Newton", step 3: the Kacanov phase ends after an iteration whose
// frozen passes found the active set at once (switch_passes): the iterate is near enough for
// Newton.
void NewtonSolve::switch_phase() {
  if (kacanov_phase_ && passes_ <= t_.switch_passes) newton_phase_ = true;
  previous_active_ = is_active_;
}

// |F|^2 at the full step (u_0 + du, lambda of the step), out: its iterate; infinite when the
// geometry cannot be evaluated there.
double NewtonSolve::full_step_merit2(NewtonIterate& out) const {
  try {
    out = evaluate_(st_.u0 + step_.du, step_.lambda);
  } catch (const Error&) {
    return std::numeric_limits<double>::infinity();
  }
  return finite(out) ? out.merit * out.merit : std::numeric_limits<double>::infinity();
}

// The exact frozen-geometry step (the Kacanov phase's): passes from the iterate's own active set
// (du = 0). False when a system is singular.
bool NewtonSolve::frozen_step(std::vector<char>& frozen_active) {
  step_.du.setZero();
  step_.lambda = st_.lambda;
  predict_active(frozen_active, true);
  bool solved = solve_system(frozen_active, true);
  for (int pass = 1; solved && pass < t_.max_inner_iterations && predict_active(frozen_active, true) != 0; ++pass) {
    solved = solve_system(frozen_active, true);
  }
  if (solved) system_.complete(step_, at_);
  return solved;
}

// docs/theory.md, "Semi-smooth Newton", step 4, the Kacanov safeguard (Newton phase, iterations
// without branch passes: the iterate's maps are then those of u itself). The Newton step is good
// only where the slave nodes' remaining slip is below the master segment length (the contact
// forces are distributed by the hat functions of xi, whose slope jumps by |lambda_r| / h at each
// master vertex); further out a full Newton step can raise the merit where the exact frozen step
// lowers it, and backtracked Newton steps then crawl. So when the full Newton step does not
// reduce the merit to kacanov_safeguard x its value, the frozen step is computed as well and the
// full step with the smaller merit goes first into the line search (docs/performance.md, "Why
// the defaults are what they are", "Newton: Kacanov safeguard").
void NewtonSolve::kacanov_safeguard() {
  if (kacanov_phase_ || pass_frozen_ || it_.branch_passes != 0 || !(t_.kacanov_safeguard > 0.0)) return;
  const double phi_now = st_.merit * st_.merit;
  NewtonIterate newton_trial;
  const double phi_newton = full_step_merit2(newton_trial);
  if (!(phi_newton <= t_.kacanov_safeguard * t_.kacanov_safeguard * phi_now)) {
    const NewtonStep newton = step_;
    std::vector<char> frozen_active(sz(R_), 0);
    NewtonIterate frozen_trial;
    double phi_frozen = std::numeric_limits<double>::infinity();
    if (frozen_step(frozen_active)) phi_frozen = full_step_merit2(frozen_trial);
    if (phi_frozen < phi_newton) {
      it_.kacanov_step = true;
      previous_active_ = frozen_active;
      full_trial_ = std::move(frozen_trial);
      have_full_trial_ = true;
    } else {
      step_ = newton;
      failure_.clear();  // a singular frozen system here only means: keep the Newton step
    }
  }
  if (!have_full_trial_ && std::isfinite(phi_newton)) {
    full_trial_ = std::move(newton_trial);
    have_full_trial_ = true;
  }
}

// docs/theory.md, "Semi-smooth Newton", step 4, chord corrections (Newton phase, when the step
// is a Newton step; off by default: docs/performance.md, "Why the defaults are what they are",
// "Newton: chord corrections off"). The full step's trial (u_1, lambda_1) is corrected with the
// iterate's Jacobian J on the same active rows,
//   J [dv; lambda_2] = -F(u_1, lambda_1),
// i.e. the Newton system written at u_1 with K_0, D, H of the iterate:
//   [A_00 + H, K_A'; -D_A, 0] [dv; lambda_2] = [b - A_00 u_1 + (K_0 - K_0(u_1))' lambda_1; d_A(u_1)].
// On a smooth residual the error after the pair of solves is O(e^3) instead of O(e^2)
// (Shamanskii's method). A correction is kept only when it lowers the merit of the full step;
// the line search then starts from the corrected step (and backtracks along the plain Newton
// direction).
void NewtonSolve::chord_corrections() {
  if (kacanov_phase_ || it_.kacanov_step || t_.chord_steps <= 0) return;
  system_.complete(step_, at_);
  if (!have_full_trial_) {
    try {
      full_trial_ = evaluate_(st_.u0 + step_.du, step_.lambda);
      have_full_trial_ = finite(full_trial_);
    } catch (const Error&) {
      have_full_trial_ = false;
    }
  }
  for (int c = 0; c < t_.chord_steps && have_full_trial_ && full_trial_.kkt() > s_.tolerance; ++c) {
    const NewtonStep keep = step_;
    if (!chord_correction()) {
      step_ = keep;
      break;
    }
    if (c == 0) plain_ = keep;
    ++it_.chord_steps;
  }
}

// One chord correction from full_trial_; true when it lowered the merit (full_trial_ and step_
// are then the corrected ones).
bool NewtonSolve::chord_correction() {
  // f = (K_0 - K_0(u_1))' lambda_1, on the few contact DOFs of both geometries.
  const Eigen::VectorXd extra = (st_.K0 - full_trial_.K0).transpose() * full_trial_.lambda;
  std::vector<int> in;
  std::vector<double> values;
  for (int i = 0; i < n_; ++i) {
    if (extra(i) != 0.0) {
      in.push_back(i);
      values.push_back(extra(i));
    }
  }
  const Eigen::Map<const Eigen::VectorXd> f_in(values.data(), static_cast<Eigen::Index>(values.size()));
  // ActiveSchur: the systems read z_chord = A_00^-1 (b + f) on the read DOFs and on H's DOFs
  // (E lies in them); the whole step is formed below in one substitution.
  Eigen::VectorXd z_chord, top_chord;
  if (system_.schur()) {
    z_chord = system_.z();
    if (!in.empty()) {
      std::vector<int> out = lin_.read_dofs;
      for (const auto& t : lin_.H) {
        out.push_back(t.row());
        out.push_back(t.col());
      }
      std::sort(out.begin(), out.end());
      out.erase(std::unique(out.begin(), out.end()), out.end());
      z_chord += system_.inverse().solve_sparse(in, f_in, &out);
    }
  } else {
    top_chord = *p_.b - *p_.A00 * full_trial_.u0 + extra;
  }
  at_ = SystemPoint{&z_chord, &top_chord, &full_trial_.u0, &full_trial_.maps.d, &full_trial_.lambda};
  const bool solved = solve_newton_system(is_active_);
  at_ = iterate_point();
  failure_.clear();  // a singular system here only means: keep the step as it was
  if (!solved) return false;
  if (!step_.complete) {
    // u_1 + dv = z - A_00^-1 (P_E y_E - f): the step from u_0 in one substitution.
    std::vector<std::pair<int, double>> rhs;
    for (std::size_t a = 0; a < step_.E.size(); ++a) rhs.emplace_back(step_.E[a], step_.yE(static_cast<Eigen::Index>(a)));
    for (std::size_t a = 0; a < in.size(); ++a) rhs.emplace_back(in[a], -values[a]);
    std::sort(rhs.begin(), rhs.end());
    std::vector<int> idx;
    std::vector<double> val;
    for (const auto& [i, v] : rhs) {
      if (!idx.empty() && idx.back() == i) {
        val.back() += v;
      } else {
        idx.push_back(i);
        val.push_back(v);
      }
    }
    const Eigen::Map<const Eigen::VectorXd> y(val.data(), static_cast<Eigen::Index>(val.size()));
    step_.du = system_.z() - system_.inverse().solve_sparse(idx, y) - st_.u0;
    step_.complete = true;
  } else {
    step_.du = full_trial_.u0 + step_.du - st_.u0;  // SaddleLU: dv itself
  }
  NewtonIterate chord_trial;
  try {
    chord_trial = evaluate_(st_.u0 + step_.du, step_.lambda);
  } catch (const Error&) {
    return false;
  }
  if (!(finite(chord_trial) && chord_trial.merit < full_trial_.merit)) return false;
  full_trial_ = std::move(chord_trial);
  return true;
}

// docs/theory.md, "Semi-smooth Newton", step 5: Armijo backtracking on the merit 1/2 |F|^2; a
// full step that does not decrease it is taken at most max_free_steps times in all
// (docs/performance.md, "Why the defaults are what they are", "Newton: no free steps"). The
// trials: the full step of step 2's passes; then, when the passes moved the active set, the
// plain semi-smooth Newton direction (a descent direction of the merit, which the passes' one
// need not be), backtracked; then the step's direction backtracked (with chord corrections
// kept: the plain Newton direction's). Without a decrease down to min_step the best trial is
// taken (the iteration cap ends a stall).
bool NewtonSolve::line_search() {
  it_.factorize_s = seconds_since(t_systems_);
  const auto t_search = Clock::now();
  const double phi0 = st_.merit * st_.merit;
  const Eigen::VectorXd dlambda = step_.lambda - st_.lambda;
  const Eigen::VectorXd dlambda_first = passes_ > 1 ? Eigen::VectorXd(first_.lambda - st_.lambda) : Eigen::VectorXd();
  const Eigen::VectorXd dlambda_plain = it_.chord_steps > 0 ? Eigen::VectorXd(plain_.lambda - st_.lambda) : Eigen::VectorXd();
  struct Trial {
    NewtonStep* step;
    const Eigen::VectorXd* dl;
    double t_first, t_last;
    bool full;  // the step itself: its full trial may be evaluated already, and may be a free step
  };
  std::vector<Trial> trials{{&step_, &dlambda, 1.0, 1.0, true}};
  if (passes_ > 1) trials.push_back({&first_, &dlambda_first, 1.0, t_.min_step, false});
  if (it_.chord_steps > 0) {
    trials.push_back({&plain_, &dlambda_plain, 0.5, t_.min_step, false});
  } else {
    trials.push_back({&step_, &dlambda, 0.5, t_.min_step, true});
  }
  NewtonIterate best;
  double best_phi = std::numeric_limits<double>::infinity();
  double best_t = 0.0;
  for (const Trial& tr : trials) {
    if (tr.step == &first_) system_.complete(first_, at_);
    for (double t = tr.t_first; t >= tr.t_last; t *= 0.5) {
      NewtonIterate trial;
      if (have_full_trial_ && tr.full && t == 1.0) {
        trial = std::move(full_trial_);  // evaluated in step 4
        have_full_trial_ = false;
      } else {
        try {
          trial = evaluate_(st_.u0 + t * tr.step->du, st_.lambda + t * *tr.dl);
        } catch (const Error&) {
          continue;  // the geometry cannot be evaluated there: shorten the step
        }
      }
      if (!finite(trial)) continue;
      const double phi = trial.merit * trial.merit;
      const bool decrease = phi <= (1.0 - 2.0 * t_.armijo * t) * phi0;
      const bool free_step = t == 1.0 && tr.full && free_steps_ < t_.max_free_steps;
      if (decrease || free_step) {
        if (!decrease) ++free_steps_;
        it_.step = t;
        st_ = std::move(trial);
        return record(t_search);
      }
      if (phi < best_phi) {
        best_phi = phi;
        best_t = t;
        best = std::move(trial);
      }
    }
  }
  if (!std::isfinite(best_phi)) {
    return finish(solve::KacanovStatus::StepFailed,
                  "semi-smooth Newton iteration " + std::to_string(k_) +
                      ": no damped step can be evaluated (the contact geometry fails at every trial); " +
                      residual_text(st_));
  }
  it_.step = best_t;
  st_ = std::move(best);
  return record(t_search);
}

bool NewtonSolve::record(std::chrono::steady_clock::time_point t_search) {
  it_.search_s = seconds_since(t_search);
  res_.history.push_back(it_);
  res_.iterations = k_ + 1;
  return true;
}

}  // namespace contactrb::hf
