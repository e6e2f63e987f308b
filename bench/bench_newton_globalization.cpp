// The Newton solver's globalization switches, each on and off on the mesh where it matters
// (docs/theory.md, "Semi-smooth Newton", step 4; docs/performance.md, "Why the defaults are what
// they are", "Newton: Kacanov safeguard" and "Newton: chord corrections off"):
//   - the Kacanov safeguard (NewtonTuning::kacanov_safeguard, on by default) on hertz-a level 5
//     at mu 0.45: without it the backtracked Newton steps crawl (>= 15 iterations, >= 5 damped);
//     with it the frozen step is taken where the Newton step raises the merit (<= 10 iterations,
//     all full steps);
//   - the chord corrections (NewtonTuning::chord_steps, off by default) on hertz-a level 4 at
//     mu 0.45: 2 corrections per iteration end the solve in <= 8 iterations, 9 without.
// Both solves of a pair reach the same answer (u to 1e-9, lambda to 1e-8, relative).
//
//   bench_newton_globalization [--switch safeguard|chord|both] [--level L (default: 5 for the
//                              safeguard, 4 for the chords)] [--mu 0.45] [--case hertz-a]
//
// One CSV line per solve on stdout: case, level, mu, switch, value, iterations, status, damped
// steps, safeguard steps, chord corrections kept, KKT residual, contact force, and the relative
// differences of u and lambda to the first solve of the pair (the default setting's).
#include <algorithm>
#include <cstdio>
#include <string>

#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/hf/hf_solver.hpp"

using namespace contactrb;

namespace {

double relative(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).norm() / std::max(b.norm(), 1e-300); }

void report(const std::string& name, int level, double mu, const char* knob, double value, const hf::HFSolution& sol,
            const hf::HFSolution& reference) {
  int damped = 0, safeguard = 0, chords = 0;
  for (const hf::NewtonIteration& it : sol.newton_history) {
    damped += it.step < 1.0 ? 1 : 0;
    safeguard += it.kacanov_step ? 1 : 0;
    chords += it.chord_steps;
  }
  std::printf("%s,%d,%g,%s,%g,%d,%s,%d,%d,%d,%.2e,%.12g,%.2e,%.2e\n", name.c_str(), level, mu, knob, value,
              sol.iterations, solve::to_string(sol.status), damped, safeguard, chords, sol.kkt.max(), sol.contact_force,
              relative(sol.u, reference.u), relative(sol.lambda, reference.lambda));
}

// The default tuning, then the knob set to `other`.
template <class Set>
void compare(const std::string& name, int level, double mu, const char* knob, double tolerance, double value,
             double other, Set set) {
  const hf::HFSolver solver(cases::make_problem(name, mu, level, contact::Discretization::Collocation));
  hf::HFSettings s;
  s.method = hf::HFMethod::Newton;
  s.newton.tolerance = tolerance;
  set(s.newton.tuning, value);
  const hf::HFSolution first = solver.solve(s);
  report(name, level, mu, knob, value, first, first);
  set(s.newton.tuning, other);
  report(name, level, mu, knob, other, solver.solve(s), first);
}

}  // namespace

int main(int argc, char** argv) {
  std::string which = "both", name = "hertz-a";
  int level = -1;
  double mu = 0.45;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "missing value after %s\n", a.c_str());
      return 2;
    }
    const std::string v = argv[++i];
    if (a == "--switch") which = v;
    else if (a == "--level") level = std::stoi(v);
    else if (a == "--mu") mu = std::stod(v);
    else if (a == "--case") name = v;
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (which != "both" && which != "safeguard" && which != "chord") {
    std::fprintf(stderr, "unknown --switch %s (safeguard, chord or both)\n", which.c_str());
    return 2;
  }
  std::printf("case,level,mu,switch,value,iterations,status,damped,safeguard_steps,chord_corrections,kkt,force,"
              "u_difference,lambda_difference\n");
  try {
    const hf::NewtonTuning defaults;
    if (which != "chord") {
      compare(name, level >= 0 ? level : 5, mu, "kacanov_safeguard", 1e-12, defaults.kacanov_safeguard, 0.0,
              [](hf::NewtonTuning& t, double x) { t.kacanov_safeguard = x; });
    }
    if (which != "safeguard") {
      compare(name, level >= 0 ? level : 4, mu, "chord_steps", 1e-10, defaults.chord_steps, 2.0,
              [](hf::NewtonTuning& t, double x) { t.chord_steps = static_cast<int>(x); });
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
