#pragma once
// One V-cycle of algebraic multigrid (hypre's BoomerAMG, sequential: one process, MPI_COMM_SELF)
// on a symmetric positive definite sparse matrix, as a preconditioner of the Krylov solves of
// the Newton systems (solve/saddle_point_krylov.hpp; docs/solvers.md, "AMG-preconditioned
// Krylov solve"). Elasticity is treated as a system: the unknowns carry their displacement
// component (BoomerAMG's dof_func), coarsened and interpolated per component. Like Eigen's
// solvers: compute() returns a status, apply() requires Success. A build without hypre
// (CONTACTRB_WITH_AMG=OFF or libhypre-dev missing) answers Unavailable.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

namespace contactrb::solve {

enum class AmgStatus { Success, Unavailable, SetupFailed, InvalidInput };
const char* to_string(AmgStatus status);
AmgStatus amg_status_from_string(const std::string& name);  // throws contactrb::Error
// True when the build has hypre (CONTACTRB_WITH_AMG and libhypre-dev found).
bool amg_available();

// The smoother of the V-cycle: one l1 Gauss-Seidel sweep forward on the way down and one
// backward on the way up (hypre's relax types 13 and 14, its own default), or one symmetric
// sweep (forward then backward, relax type 8) each way: twice the sweeps per cycle.
enum class AmgSmoother { ForwardBackward, Symmetric };
const char* to_string(AmgSmoother smoother);
AmgSmoother amg_smoother_from_string(const std::string& name);  // throws contactrb::Error

// BoomerAMG's options for 3D elasticity (hypre's users manual, "BoomerAMG": HMIS coarsening,
// extended+i interpolation with at most 4 entries per row, l1 Gauss-Seidel smoothing). The
// strength threshold 0.25: faster than the 0.5 often advised in 3D, on hertz-3d levels 2 and 3
// (docs/performance.md, "Why the defaults are what they are", "AMG options").
struct AmgSettings {
  double strong_threshold = 0.25;
  int max_interpolation_entries = 4;
  int aggressive_levels = 1;  // levels of aggressive coarsening (less memory and setup in 3D)
  AmgSmoother smoother = AmgSmoother::ForwardBackward;
};

class AmgPreconditioner {
 public:
  AmgPreconditioner();
  ~AmgPreconditioner();
  AmgPreconditioner(AmgPreconditioner&&) noexcept;
  AmgPreconditioner& operator=(AmgPreconditioner&&) noexcept;

  // The multigrid hierarchy of A (square, symmetric). component[i] in [0, components): the
  // displacement component of unknown i (empty: a scalar problem). InvalidInput: not square,
  // empty, a non-finite entry, or component of the wrong size or range.
  AmgStatus compute(const Eigen::SparseMatrix<double>& A, const std::vector<int>& component, int components,
                    const AmgSettings& settings = {});
  AmgStatus status() const;
  // One V-cycle from zero on A x = r. Throws contactrb::Error unless status() == Success and r
  // has the matrix's size.
  Eigen::VectorXd apply(const Eigen::VectorXd& r) const;
  double setup_seconds() const;
  int levels() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace contactrb::solve
