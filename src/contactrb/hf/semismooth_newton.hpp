#pragma once
// Semi-smooth Newton (primal-dual active set) solver of the HF contact problem
// (docs/theory.md, "Semi-smooth Newton", steps 1-6; docs/solvers.md, "Semi-smooth Newton").
// It solves the same equations as the fixed point of Kacanov (paper (12)):
//   A_00 u_0 - b + K_0(u)' lambda = 0,
//   min(lambda_r, c_r d_r(u)) = 0,   d(u) = g(u) - K(u) u,   u = u_D + u_0,
// (the second line is lambda >= 0, d >= 0, lambda_r d_r = 0: (26) and its complementarity),
// by Newton's method on the nonsmooth system: the active set A = {r : lambda_r - c_r d_r > 0}
// is read off the complementarity function at each iterate, and the geometry is linearized
// consistently (contact/contact_linearization.hpp: D = d'(u), H = (K(u)' lambda)'). Each
// iteration solves the saddle-point system of the active rows,
//   [ A_00 + H    K_A' ] [ du       ]   [ b - A_00 u_0 ]
//   [ -D_A        0    ] [ lambda_A ] = [ d_A          ],     lambda = 0 off A,
// (NewtonLinearSolver): by default reduced EXACTLY to the few DOFs E that H, K_A, D_A touch,
// with A_00 factorized once per solve and the block (A_00^-1)[E, E] from sparse substitutions
// (solve/selected_inverse.hpp), the reduced system solved by GMRES preconditioned by the
// frozen-geometry one (solve/gmres.hpp; a dense LU as the fallback); or by a sparse LU of the
// whole saddle point (solve/sparse_lu.hpp). No dense K A^-1 K' over all candidate rows is
// ever formed (docs/solvers.md, "Newton linear algebra").
// Globalization: a Kacanov phase first (NewtonInnerPasses::Frozen): from the start, each step
// solves the frozen-geometry linearization (H = 0, D = -K, a convex QP) exactly by active-set
// passes, until those passes find the active set at once; then Newton steps. Every step is
// followed by a backtracking line search on the merit 1/2 |F|^2 (F with the complementarity
// rows in force units, |I_r| min(lambda_r, c_r d_r)); optionally a bounded number of full steps
// without a decrease (max_free_steps). In the Newton phase a full step that does not halve the
// merit is compared with the exact frozen-geometry step, and the better one is tried first
// (kacanov_safeguard). Optionally a Newton step's full trial is then corrected with the
// iterate's Jacobian (chord_steps, kept while the merit falls).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/mesh/mesh.hpp"
#include "contactrb/solve/amg_preconditioner.hpp"
#include "contactrb/solve/selected_inverse.hpp"
#include "contactrb/solve/kacanov.hpp"
#include "contactrb/solve/saddle_point_krylov.hpp"
#include "contactrb/solve/selected_inverse.hpp"
#include "contactrb/solve/sparse_lu.hpp"

namespace contactrb::hf {

// ActiveSchur: A_00 = L L' once per solve (CHOLMOD), then per system a dense one of size
//   |E| + |A| (E: the free DOFs of the active rows and of H; docs/solvers.md, "Newton linear
//   algebra"), |A| with the frozen geometry, GMRES on it in the Newton phase; SaddleLU: one sparse
//   LU of the (n + |A|)-square saddle point per system (kept to compare).
//   Amg: the whole saddle point by GMRES, preconditioned by one BoomerAMG V-cycle on A_00 and a
//   sparse approximation of the Schur complement of the active rows (solve/saddle_point_krylov.hpp;
//   docs/solvers.md, "AMG-preconditioned Krylov solve"): no factorization of A_00, for the 3D meshes
//   whose Cholesky factor does not fit. Auto: Amg in 3D from NewtonSettings::amg_from_free_dofs
//   free DOFs on (when the build has hypre), ActiveSchur otherwise (resolved_linear_solver).
enum class NewtonLinearSolver { ActiveSchur, SaddleLU, Amg, Auto };
const char* to_string(NewtonLinearSolver solver);
NewtonLinearSolver newton_linear_solver_from_string(const std::string& name);  // "schur" | "lu" | "amg" | "auto"

// Frozen (default): a Kacanov phase first. Each iteration solves the frozen-geometry
// linearization exactly (active-set passes on a convex QP: an undamped Kacanov step) until one
// pass finds the active set at once; the following iterations are semi-smooth Newton steps with
// the consistent linearization (passes on it when the set still moves). Consistent: Newton
// steps from the start; from u = u_D their consistent passes can cycle on fine meshes
// (docs/performance.md, "Why the defaults are what they are", "Newton: Kacanov phase first").
enum class NewtonInnerPasses { Frozen, Consistent };
const char* to_string(NewtonInnerPasses passes);
NewtonInnerPasses newton_inner_passes_from_string(const std::string& name);  // "frozen" | "consistent"

// The tuning of the method: every knob with the reason of its default (docs/performance.md,
// "Why the defaults are what they are", the sub-heading named at each knob; the steps are those
// of docs/theory.md, "Semi-smooth Newton"). A user sets NewtonSettings; these stay as they are
// unless a study of the method needs otherwise (bench/bench_hf_scaling.cpp has an option for
// most of them).
struct NewtonTuning {
  // Step 5, the line search: Armijo constant and the smallest damping factor tried (halving).
  double armijo = 1e-4;
  double min_step = 1.0 / 1024.0;
  // Step 5: full steps accepted without a merit decrease, in all. 0: with free steps the
  // active set of fine meshes ping-pongs ("Newton: no free steps").
  int max_free_steps = 0;
  // Step 2: active-set passes on the linearized problem per iteration (systems).
  int max_inner_iterations = 20;
  // Step 2: the Kacanov phase first ("Newton: Kacanov phase first").
  NewtonInnerPasses inner_passes = NewtonInnerPasses::Frozen;
  // Step 3, branch passes per Newton-phase iteration (pointwise rows): when the step moves
  // slave nodes to other branches of the piecewise smooth contact maps (closest segment,
  // clamped wedge at a vertex), it is solved again on the maps at u continued on the branches
  // it lands on. 0: off. Only in the iterations whose KKT residual is at most
  // branch_passes_below: the last, quadratic steps, where a kink crossing costs a whole
  // iteration ("Newton: branch passes near the solution").
  int max_branch_passes = 2;
  double branch_passes_below = 1e-5;
  // Step 4, the Kacanov safeguard (Newton phase, iterations without branch passes): when the
  // full Newton step leaves the merit above kacanov_safeguard x the iterate's, the exact
  // frozen-geometry step (the Kacanov phase's) is computed too and the full step with the
  // smaller merit is taken. 0: off ("Newton: Kacanov safeguard").
  double kacanov_safeguard = 0.5;
  // Step 2: passes on the consistent linearization per Newton-phase iteration (systems, <=
  // max_inner_iterations). Their LCP is not monotone: where they do not settle in a few passes
  // the step is the safeguard's anyway ("Newton: consistent passes capped").
  int max_newton_passes = 4;
  // Step 3: the Kacanov phase ends after an iteration whose frozen passes settled in at most
  // this many systems (1: the active set was found at once; "Newton: consistent passes capped").
  int switch_passes = 1;
  // Step 4, chord corrections per Newton-phase iteration (systems): the full Newton step's trial
  // is corrected with the iterate's Jacobian (same active rows), each kept only when it lowers
  // the merit. 0: off; fewer linearizations but more systems, slower where time matters
  // ("Newton: chord corrections off").
  int chord_steps = 0;
  // ActiveSchur: a reduced system whose reciprocal condition estimate is below this is treated
  // as singular (the frozen-geometry fallback of step 2), like a zero pivot of the sparse LU.
  double min_rcond = 1e-14;
  // ActiveSchur, Newton phase: GMRES preconditioned by the frozen-geometry system, from the
  // iterate, to this residual of the equilibrated reduced system relative to the iterate's; the
  // dense LU when it does not converge in krylov_max_iterations products (0: always the dense
  // LU; "Newton: GMRES in the Newton phase").
  int krylov_max_iterations = 100;
  double krylov_tolerance = 1e-13;
  // ActiveSchur: OpenBLAS threads for the BLAS-3 parts (the supernodal factorization of A_00, the
  // selected-inverse blocks) when A_00 has at least blas_threads_from rows, then one thread for
  // the rest of the solve and, from 2, the full backward substitutions on two threads
  // (SelectedInverse::set_substitution_threads); below blas_threads_from and with 0, the BLAS's
  // own count (OPENBLAS_NUM_THREADS) everywhere. The count is process-wide (solve/blas_threads.hpp):
  // leave 0 when solves run in parallel threads ("BLAS threads").
  int blas_threads = 0;
  int blas_threads_from = 200000;
  // ActiveSchur: the frozen systems of the first iteration (a cold start's active set is the
  // unloaded overlap, far larger than the final one) take their dual matrix K_A A_00^-1 K_A' from
  // one sparse substitution per active row (SelectedInverse::row_block) instead of the block G of
  // A_00^-1 on every DOF the rows touch; G then from the second iteration on, on the smaller set.
  // In problems of this dimension and above: 3D, where it pays, not 2D, where it does not
  // ("Newton: the first frozen systems on the constraint rows").
  int frozen_rows_from_dimension = 3;
};

// Amg: the forcing term eta_k of an inexact Newton step, the GMRES tolerance of the systems of
// iteration k relative to the residual at the iterate (newton_forcing_term; docs/solvers.md,
// "AMG-preconditioned Krylov solve"): `max` in the Kacanov phase, Eisenstat and Walker's choice 2
// (SIAM J. Sci. Comput. 17, 1996, (2.6) with the safeguard of Section 3) in the Newton phase,
// bounded by `max` above and by SaddlePointKrylovSettings::tolerance below; max equal to that
// tolerance: a constant forcing term.
struct NewtonForcing {
  double max = 3e-2;      // the loosest tolerance (the Kacanov phase's)
  double gamma = 0.9;     // eta^A = gamma (r_k / r_k-1)^exponent
  double exponent = 2.0;
};

// What a user sets: the tolerance, the iteration cap, the linear solver; the method's tuning
// apart (NewtonTuning).
struct NewtonSettings {
  double tolerance = 1e-10;  // on HFKKT::max() (relative, hf_solver.hpp), at the nonlinear geometry
  int max_iterations = 50;
  NewtonLinearSolver linear_solver = NewtonLinearSolver::ActiveSchur;
  // Auto: the AMG Krylov solve in 3D from this many free DOFs on (docs/performance.md, "Why the
  // defaults are what they are", "Newton: AMG in 3D from 40 000 free DOFs").
  int amg_from_free_dofs = 40000;
  solve::AmgSettings amg;                   // Amg: the V-cycle on A_00
  solve::SaddlePointKrylovSettings krylov;  // Amg: GMRES on each Newton system (tolerance: the tightest forcing term)
  NewtonForcing krylov_forcing;             // Amg: the forcing terms of the inexact Newton
  solve::SparseLUBackend lu = solve::SparseLUBackend::Umfpack;  // SaddleLU only
  // ActiveSchur: the fill-reducing ordering of A_00 (solve/selected_inverse.hpp;
  // docs/performance.md, "Why the defaults are what they are", "Fill-reducing ordering").
  solve::FactorOrdering ordering = solve::FactorOrdering::Auto;
  // Step 1: analytic (default) or finite differences, and the projection's options
  // ("Newton: analytic linearization"); both in 3D too (docs/solvers.md, "Three dimensions").
  contact::LinearizationOptions linearization;
  NewtonTuning tuning;
  // ActiveSchur: the result keeps the solve's factor of A_00 (NewtonResult::a00_factor), for a
  // caller that needs entries of A_00^-1 at the same mu (hf::HFSetupOptions::keep_newton_factor).
  bool keep_factor = false;
};
// Throws contactrb::Error for a non-positive tolerance, max_iterations < 1, an armijo
// outside (0, 1/2), a min_step outside (0, 1], a negative kacanov_safeguard or
// max_newton_passes < 1 (and the other bounds of NewtonTuning, named in the messages).
void check_settings(const NewtonSettings& settings);
// The forcing term of an iteration (NewtonForcing). Kacanov phase: `max` (its frozen-geometry
// steps converge linearly, at the rate of the geometry update, however exactly they are solved).
// Newton phase: Eisenstat and Walker's gamma (r_k / r_k-1)^exponent, at least
// gamma eta_k-1^exponent when that exceeds 0.1 (the tightest in the first Newton-phase iteration:
// previous_residual <= 0), and at least 0.5 tolerance / r_k (no tighter than the Newton tolerance
// needs: Kelley, "Iterative Methods for Linear and Nonlinear Equations", 1995, (6.20)); clamped to
// [krylov.tolerance, krylov_forcing.max]. r: the KKT residuals of the iterates.
double newton_forcing_term(const NewtonSettings& settings, bool newton_phase, double residual, double previous_residual,
                           double previous_eta);
// The linear solver a problem of this dimension and size gets: Auto resolved (ActiveSchur,
// SaddleLU or Amg), the others as they are.
NewtonLinearSolver resolved_linear_solver(const NewtonSettings& settings, int dimension, int free_dofs);

struct NewtonIteration {
  double residual = 0.0;   // HFKKT::max() at the iterate, before the step
  double merit = 0.0;      // |F| (force units)
  int active = 0;          // |A| of the step
  int changed = 0;         // rows that entered or left A (first inner pass)
  int factorizations = 0;  // systems solved (inner active-set passes)
  int reduced_size = 0;    // ActiveSchur: |E| of the last pass
  bool frozen = false;     // the consistent Jacobian was singular: frozen-geometry fallback step
  double step = 0.0;       // damping factor taken
  int colours = 0;         // colours of the finite-difference linearization (0: analytic)
  int branch_passes = 0;   // systems re-solved on the branches of the step (NewtonTuning::max_branch_passes)
  bool kacanov_step = false;  // Newton phase: the safeguard took the exact frozen-geometry step
  int chord_steps = 0;        // chord corrections kept (NewtonTuning::chord_steps)
  double linearize_s = 0.0, factorize_s = 0.0;
  double search_s = 0.0;   // line search: the trial iterates' contact maps and residuals
  double block_s = 0.0;    // ActiveSchur: the G blocks (selected-inverse columns, Gram products), in factorize_s
  int krylov = 0;          // GMRES products (ActiveSchur: Newton phase; Amg: every system)
  double forcing = 0.0;    // Amg: the GMRES tolerance of the iteration's systems (newton_forcing_term)
};

// What the Newton linear systems need of an HF problem (views; the HF solver owns them): the
// algebra alone, the same in every dimension.
struct NewtonAlgebra {
  const fem::DofMap* dofs = nullptr;
  const Eigen::SparseMatrix<double>* A00 = nullptr;  // free x free
  const Eigen::VectorXd* b = nullptr;                // f_0 - (A u_D)_0
  // ActiveSchur: the ordering and symbolic analysis of A_00 made ahead (hf::HFSolver, on another
  // thread; the call may wait for it), or nullptr / empty: analysed in the solve. Used when its
  // ordering is NewtonSettings::ordering's and A_00 has its pattern (else ignored).
  std::function<const solve::FactorAnalysis*()> a00_analysis;
};

// What the solver needs of an HF problem: the algebra and the contact geometry of a dimension.
template <int Dim>
struct BasicNewtonProblem : NewtonAlgebra {
  const mesh::SimplexMesh<Dim>* mesh = nullptr;
  const contact::ContactPairOf<Dim>* pair = nullptr;
  const contact::ContactQuadrature* quadrature = nullptr;
};
using NewtonProblem = BasicNewtonProblem<2>;
using NewtonProblem3 = BasicNewtonProblem<3>;

// Wall seconds of the once-per-solve work (ActiveSchur): CHOLMOD's ordering + symbolic analysis
// of A_00, its numeric factorization, z = A_00^-1 b; and the initial evaluation.
// analysis_ahead: the analysis came from NewtonProblem::a00_analysis (analyze_s is then its own
// wall time on its thread, beside the assembly, and analysis_wait_s the solve's wait for it).
struct NewtonTimings {
  double analyze_s = 0.0, numeric_s = 0.0, rhs_s = 0.0, initial_s = 0.0;
  bool analysis_ahead = false;
  double analysis_wait_s = 0.0;
  long factor_nonzeros = 0;  // nnz(L)
  int blas_threads = 1;      // BLAS threads of the factorization
  NewtonLinearSolver linear_solver = NewtonLinearSolver::ActiveSchur;  // resolved (never Auto)
  int amg_levels = 0;        // Amg: levels of the hierarchy (its setup in numeric_s)
};

struct NewtonResult {
  solve::KacanovStatus status = solve::KacanovStatus::StepFailed;  // Converged, MaxIterations, StepFailed, NonFinite
  std::string message;
  int iterations = 0;
  std::vector<NewtonIteration> history;
  NewtonTimings timings;
  Eigen::VectorXd u0;      // free part
  Eigen::VectorXd lambda;  // R
  double stationarity = 0.0, primal = 0.0, dual = 0.0, complementarity = 0.0;  // final HFKKT
  // NewtonSettings::keep_factor with ActiveSchur: the factor of A_00 the solve used (its cached
  // columns of the inverse included); null otherwise.
  std::shared_ptr<solve::SelectedInverse> a00_factor;
};

// u0_start (num_free) and lambda_start (R): the initial guess (zeros: u = u_D, lambda = 0).
// 3D: no branch passes (docs/solvers.md, "Three dimensions").
template <int Dim>
NewtonResult semismooth_newton(const BasicNewtonProblem<Dim>& problem, const Eigen::VectorXd& u0_start,
                               const Eigen::VectorXd& lambda_start, const NewtonSettings& settings);
extern template NewtonResult semismooth_newton(const BasicNewtonProblem<2>&, const Eigen::VectorXd&,
                                               const Eigen::VectorXd&, const NewtonSettings&);
extern template NewtonResult semismooth_newton(const BasicNewtonProblem<3>&, const Eigen::VectorXd&,
                                               const Eigen::VectorXd&, const NewtonSettings&);

}  // namespace contactrb::hf
