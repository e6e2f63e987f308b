#pragma once
// The steps of the semi-smooth Newton solver (docs/theory.md, "Semi-smooth Newton", steps 1-6),
// over the state of one solve: the iterate, the factorization of A_00, the linearization at
// the iterate, the step and its trials. semismooth_newton() (semismooth_newton.cpp) is the
// driver; steps 1-3 and 6 are in newton_steps.cpp, steps 4 and 5 in newton_globalization.cpp.
// Internal to the hf module.
#include <Eigen/Core>
#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/hf/newton_iterate.hpp"
#include "contactrb/hf/newton_linear_system.hpp"
#include "contactrb/hf/semismooth_newton.hpp"
#include "contactrb/solve/blas_threads.hpp"

namespace contactrb::hf {

// Shared by the step files (newton_steps.cpp, newton_globalization.cpp).
namespace newton_detail {
using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
inline std::size_t sz(int i) { return static_cast<std::size_t>(i); }
}  // namespace newton_detail

// Each step returning bool returns false when the solve has ended there (status and message in
// result()). Dim = 2, 3: the contact geometry's dimension (the algebra is the same).
template <int Dim>
class NewtonSolve {
 public:
  NewtonSolve(const BasicNewtonProblem<Dim>& problem, const NewtonSettings& settings);
  // The initial iterate and the once-per-solve factorization of A_00 (ActiveSchur).
  bool start(const Eigen::VectorXd& u0, const Eigen::VectorXd& lambda);
  bool keep_iterating(int k);     // step 6: convergence test at the iterate
  bool linearize();               // step 1
  bool solve_on_active_set();     // step 2
  void branch_passes();           // step 3
  void switch_phase();            // step 3
  void kacanov_safeguard();       // step 4
  void chord_corrections();       // step 4
  bool line_search();             // step 5
  NewtonResult result() {
    if (s_.keep_factor) res_.a00_factor = system_.release_inverse();
    return std::move(res_);
  }

 private:
  bool finish(solve::KacanovStatus status, std::string message);
  SystemPoint iterate_point() const;
  std::vector<Eigen::Triplet<double>> free_hessian(const Eigen::SparseMatrix<double>& H) const;
  bool solve_system(const std::vector<char>& act, bool frozen);
  bool solve_newton_system(const std::vector<char>& act);
  int predict_active(std::vector<char>& out, bool frozen) const;
  bool branch_pass();
  double full_step_merit2(NewtonIterate<Dim>& out) const;
  bool frozen_step(std::vector<char>& frozen_active);
  bool chord_correction();
  bool record(std::chrono::steady_clock::time_point t_search);

  const BasicNewtonProblem<Dim>& p_;
  const NewtonSettings& s_;
  const NewtonTuning& t_;
  const int n_, N_, R_;
  std::vector<int> global_to_free_;
  std::vector<char> movable_;
  std::vector<int> contact_free_;  // the free DOFs of the slave and master nodes, ascending
  const NewtonEvaluator<Dim> evaluate_;
  NewtonLinearSystem system_;
  std::optional<solve::ScopedBlasThreads> serial_blas_;
  NewtonResult res_;
  NewtonIterate<Dim> st_;                 // the iterate
  std::vector<char> previous_active_;  // the active set of the previous step
  double previous_residual_ = 0.0;     // the KKT residual of the previous iterate (0: none)
  double forcing_ = 0.0;               // Amg: the forcing term of the previous iteration
  bool newton_phase_ = false;
  int free_steps_ = 0;
  // The iteration under way.
  int k_ = 0;
  NewtonIteration it_;
  bool kacanov_phase_ = false;
  bool singular_consistent_ = false;  // the consistent Jacobian was found singular
  bool pass_frozen_ = false;          // the passes of step 2 ran on the frozen linearization
  std::chrono::steady_clock::time_point t_systems_;  // start of the linear algebra of the iteration
  NewtonLinearization lin_;
  SystemPoint at_{};                  // where the systems are written
  std::vector<char> is_active_;
  NewtonStep step_;                   // the step
  NewtonStep first_;                  // step 2's first system: the plain semi-smooth Newton step
  int passes_ = 0;
  std::string failure_;               // a frozen system was singular: the step fails
  NewtonIterate<Dim> full_trial_;          // the full step, evaluated (step 4): the line search's first trial
  bool have_full_trial_ = false;
  NewtonStep plain_;                  // the Newton step before the chord corrections kept
};

extern template class NewtonSolve<2>;
extern template class NewtonSolve<3>;

}  // namespace contactrb::hf
