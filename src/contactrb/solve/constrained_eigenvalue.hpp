#pragma once
// The positive part of the largest eigenvalue of a symmetric pencil on the null space of
// constraint rows,
//   theta = max(0, max { x'M x / x'S x : D x = 0 }),
// from C = S^-1 (dense, symmetric positive definite), M (sparse, symmetric, of any sign) and D
// (sparse rows). The offline geometric term (offline/geometric_term.hpp) asks for it with C a
// block of A(mu)^-1 and M the geometric stiffness: S is then a Schur complement that never has
// to be formed.
//
// The eigenvalues of the pencil on ker D are those of C_D M, with
//   C_D = C - C D' (D C D')^-1 D C,
// the inverse of S on ker D (the solution operator of the saddle point [S D'; D 0]). C_D M maps
// into ker D and is self-adjoint there in the S inner product, and the S products it needs are
// read from M and the multipliers: for x = C_D y, S x = y - D' mu with mu = (D C D')^-1 D C y,
// and <C_D M q, p>_S = p'M q for p, q in ker D. Lanczos in that inner product (Parlett, "The Symmetric
// Eigenvalue Problem", ch. 13) with full reorthogonalization (classical Gram-Schmidt, twice) from
// a start in the range of C_D M, so only the rank of M bounds the Krylov dimension. It stops when
// the Ritz residual |C_D M x - theta x|_S / |x|_S of the largest Ritz value is at most
// `tolerance` times the largest |Ritz value| (the residual bounds the distance of theta to an
// eigenvalue of the pencil), or when the Krylov space is invariant (theta exact). Each step costs
// one product with C (2 m^2 flops), one with M and the reorthogonalization (4 m j).
//
// The positive part: the iteration sees the range of C_D M only, where the eigenvalues are the
// nonzero ones; 0 is one too as soon as rank M < dim ker D (M of low rank, as a geometric
// stiffness), and is the answer whenever M is negative semi-definite on ker D.
//
// Dependent constraint rows: D C D' is then singular, and its pseudo-inverse (eigenvalues below
// kDependentRows times the largest dropped) keeps the same null space of D.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace contactrb::solve {

struct ConstrainedEigenvalueSettings {
  // Ritz residual relative to the spectral scale; the eigenvalue error is at most this (and of
  // the order of its square over the gap to the next eigenvalue).
  double tolerance = 1e-12;
  int max_iterations = 0;  // Lanczos steps; 0: the dimension m (the space is exhausted by then)
};

struct ConstrainedEigenvalueResult {
  double value = 0.0;      // theta >= 0 (0 when M is negative semi-definite on ker D)
  int iterations = 0;      // Lanczos steps (products with C)
  double residual = 0.0;   // the Ritz residual of theta, relative to the spectral scale
  bool converged = false;  // residual <= tolerance or an invariant Krylov space
};

inline constexpr double kDependentRows = 1e-12;

// C: m x m; M: m x m; D: a x m (a may be 0: no constraint). Throws contactrb::Error on sizes
// that do not match or a C that is not positive definite on the constraint rows.
ConstrainedEigenvalueResult largest_constrained_eigenvalue(const Eigen::MatrixXd& C,
                                                           const Eigen::SparseMatrix<double>& M,
                                                           const Eigen::SparseMatrix<double, Eigen::RowMajor>& D,
                                                           const ConstrainedEigenvalueSettings& settings = {});

}  // namespace contactrb::solve
