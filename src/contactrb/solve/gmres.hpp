#pragma once
// Right-preconditioned GMRES (Saad, "Iterative Methods for Sparse Linear Systems", Alg. 9.5):
// x = P^-1 t, t minimizing |b - A P^-1 t| over the Krylov space of A P^-1 and b, so the true
// residual of A x = b is what is minimized and tested. Arnoldi by modified Gram-Schmidt applied
// twice (the solution is wanted to ~1e-13, where one pass loses orthogonality), Givens rotations
// for the small least-squares problem, restarts from the current x. For the Newton systems of
// the Newton phase (hf/semismooth_newton.hpp), preconditioned by the frozen-geometry system.
#include <Eigen/Core>
#include <functional>

namespace contactrb::solve {

using LinearOperator = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

struct GmresResult {
  Eigen::VectorXd x;
  int iterations = 0;              // matrix-vector products with A
  double relative_residual = 0.0;  // |b - A x| / |b|, recomputed from x at the end
  bool converged = false;          // relative_residual <= tolerance
};

// A, P_inverse: square operators of b.size(). Stops when the relative residual is <= tolerance
// or after max_iterations products in all (restart every `restart`). A non-finite product or
// breakdown ends the iteration with converged == false.
GmresResult gmres(const LinearOperator& A, const LinearOperator& P_inverse, const Eigen::VectorXd& b, double tolerance,
                  int max_iterations, int restart = 60);

}  // namespace contactrb::solve
