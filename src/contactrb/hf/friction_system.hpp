#pragma once
// The generalized Newton system of a friction step (docs/solvers.md, "Friction", step 2), in the
// unknowns du (the n free DOFs) and mu = (lambda, lambda_t) (R + (Dim - 1) R multipliers, the
// multipliers themselves, not their corrections):
//   (A_00 + H) du + B' mu = b - A_00 u_0,       B = [K_0; T_0],
//   rows_i (du, mu) = rhs_i                      (one constraint row per multiplier).
// Schur (A_00 factorized, solve::SelectedInverse): the multipliers whose row is mu_i = 0 (open
// rows) drop out; with E the free DOFs the other rows and H touch, w = du[E] and
// G = (A_00^-1)[E, E], the dense system of size |E| + (kept multipliers)
//   [ I + G H_E   G B_E' ] [ w    ]   [ z_E - u_0,E ]
//   [ rows on E          ] [ mu_k ] = [ rhs_k       ],   z = A_00^-1 b,
// then du = z - A_00^-1 P_E (H_E w + B_E' mu_k) - u_0 (the condensation of the frictionless
// Newton's ActiveSchur). SaddleLU (no factorization of A_00, e.g. a body that only friction
// holds): one sparse LU of the whole system; also when the reduced system is singular (a rigid
// mode of A_00 at round-off, which CHOLMOD factorizes). Internal to the hf module.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "contactrb/hf/newton_iterate.hpp"
#include "contactrb/solve/selected_inverse.hpp"
#include "contactrb/solve/sparse_lu.hpp"

namespace contactrb::hf {

struct FrictionJacobian {
  const Eigen::SparseMatrix<double>* A00 = nullptr;
  std::vector<Eigen::Triplet<double>> H;     // free x free (empty: frozen geometry)
  RowSparse B;                                // (R + M R) x n
  // Row n + i is multiplier i's; columns < n: du, n + i: multiplier i.
  std::vector<Eigen::Triplet<double>> rows;
  Eigen::VectorXd rhs;                        // R + M R
  std::vector<char> zero;                     // multiplier i's row is mu_i = 0 (rhs 0)
  Eigen::VectorXd top;                        // b - A_00 u_0
};

struct FrictionSystemResult {
  bool solved = false;
  bool singular = false;  // the system is singular (not an input error)
  std::string message;
  Eigen::VectorXd du, mu;
};

// inverse == nullptr: the sparse LU. z: A_00^-1 b (Schur only); u0: the iterate.
FrictionSystemResult solve_friction_system(const FrictionJacobian& J, solve::SelectedInverse* inverse,
                                           const Eigen::VectorXd& z, const Eigen::VectorXd& u0,
                                           solve::SparseLUBackend lu, double min_rcond);

}  // namespace contactrb::hf
