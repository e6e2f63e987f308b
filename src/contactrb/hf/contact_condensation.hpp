#pragma once
// Factorization of A_00 (stiffness on the free DOFs) and the block
// S = (A_00^-1)[c, c] on the contact-boundary DOFs c, which the dual contact QP needs
// (Q = K_c S K_c'). With A_00 = P' L L' P, S = Y' Y where Y = L^-1 P E_c: only FORWARD
// solves, and the column of Y for a unit vector e_r is supported on the path from r to the
// root of the elimination tree, so each costs the nonzeros of L along that path instead
// of a full dense back-solve (docs/solvers.md, "HF contact solver").
#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

namespace contactrb::hf {

class ContactCondensation {
 public:
  // A00: symmetric positive definite (free DOFs); contact: distinct indices into its rows.
  // Throws contactrb::Error if A00 is not positive definite.
  ContactCondensation(const Eigen::SparseMatrix<double>& A00, const std::vector<int>& contact);

  // A00^-1 b.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  // (A00^-1)[contact, contact], in the order of `contact`.
  const Eigen::MatrixXd& contact_inverse() const { return S_; }

 private:
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> llt_;
  Eigen::MatrixXd S_;
};

}  // namespace contactrb::hf
