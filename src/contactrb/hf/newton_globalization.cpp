// The globalization of the semi-smooth Newton step (docs/theory.md, "Semi-smooth Newton",
// steps 4 and 5): the Kacanov safeguard and the chord corrections of the full step, then the
// line search on the merit. Member functions of NewtonSolve (newton_steps.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/hf/newton_steps.hpp"

namespace contactrb::hf {

using newton_detail::Clock;
using newton_detail::seconds_since;
using newton_detail::sz;

// |F|^2 at the full step (u_0 + du, lambda of the step), out: its iterate; infinite when the
// geometry cannot be evaluated there.
template <int Dim>
double NewtonSolve<Dim>::full_step_merit2(NewtonIterate<Dim>& out) const {
  try {
    out = evaluate_(st_.u0 + step_.du, step_.lambda);
  } catch (const Error&) {
    return std::numeric_limits<double>::infinity();
  }
  return finite(out) ? out.merit * out.merit : std::numeric_limits<double>::infinity();
}

// The exact frozen-geometry step (the Kacanov phase's): passes from the iterate's own active set
// (du = 0). False when a system is singular.
template <int Dim>
bool NewtonSolve<Dim>::frozen_step(std::vector<char>& frozen_active) {
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
template <int Dim>
void NewtonSolve<Dim>::kacanov_safeguard() {
  if (kacanov_phase_ || pass_frozen_ || it_.branch_passes != 0 || !(t_.kacanov_safeguard > 0.0)) return;
  const double phi_now = st_.merit * st_.merit;
  NewtonIterate<Dim> newton_trial;
  const double phi_newton = full_step_merit2(newton_trial);
  if (!(phi_newton <= t_.kacanov_safeguard * t_.kacanov_safeguard * phi_now)) {
    const NewtonStep newton = step_;
    std::vector<char> frozen_active(sz(R_), 0);
    NewtonIterate<Dim> frozen_trial;
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
template <int Dim>
void NewtonSolve<Dim>::chord_corrections() {
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
template <int Dim>
bool NewtonSolve<Dim>::chord_correction() {
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
  NewtonIterate<Dim> chord_trial;
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
template <int Dim>
bool NewtonSolve<Dim>::line_search() {
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
  NewtonIterate<Dim> best;
  double best_phi = std::numeric_limits<double>::infinity();
  double best_t = 0.0;
  for (const Trial& tr : trials) {
    if (tr.step == &first_) system_.complete(first_, at_);
    for (double t = tr.t_first; t >= tr.t_last; t *= 0.5) {
      NewtonIterate<Dim> trial;
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

template <int Dim>
bool NewtonSolve<Dim>::record(std::chrono::steady_clock::time_point t_search) {
  it_.search_s = seconds_since(t_search);
  res_.history.push_back(it_);
  res_.iterations = k_ + 1;
  return true;
}

// The members defined here (newton_steps.cpp instantiates the others).
template double NewtonSolve<2>::full_step_merit2(NewtonIterate<2>&) const;
template bool NewtonSolve<2>::frozen_step(std::vector<char>&);
template void NewtonSolve<2>::kacanov_safeguard();
template void NewtonSolve<2>::chord_corrections();
template bool NewtonSolve<2>::chord_correction();
template bool NewtonSolve<2>::line_search();
template bool NewtonSolve<2>::record(std::chrono::steady_clock::time_point);
template double NewtonSolve<3>::full_step_merit2(NewtonIterate<3>&) const;
template bool NewtonSolve<3>::frozen_step(std::vector<char>&);
template void NewtonSolve<3>::kacanov_safeguard();
template void NewtonSolve<3>::chord_corrections();
template bool NewtonSolve<3>::chord_correction();
template bool NewtonSolve<3>::line_search();
template bool NewtonSolve<3>::record(std::chrono::steady_clock::time_point);

}  // namespace contactrb::hf
