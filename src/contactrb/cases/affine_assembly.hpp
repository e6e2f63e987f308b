#pragma once
// Offline assembly of the parameter-independent terms of the affine decomposition
// (paper (46), (49)) on the reference mesh; their parameter functions are in theta.hpp.
//
//   A(mu) = sum_j theta^a_j(mu) A_j,  f(mu) = sum_j theta^f_j(mu) f_j,
//   u_D(mu) = sum_j theta^D_j(mu) u_D,j
//
// with the terms in the order of theta_functions(spec). All are global (num_dofs, before
// the Dirichlet elimination), in the DOF numbering of the reference mesh, which is that of
// every Omega(mu).
#include <Eigen/Core>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::cases {

struct AffineTerms {
  std::vector<fem::SparseMatrix> A;
  std::vector<Eigen::VectorXd> f;
  std::vector<Eigen::VectorXd> lift;
};

//  A_1 = the stiffness on the reference mesh (J^a = 1: uniform scaling of a body in 2D
//        leaves its stiffness matrix unchanged, so A(mu) = A_1 for every mu);
//  f_j = int_{Omega_i} l_i . w on the reference body i (one per body with a load);
//  u_D,1 = lift of the constant parts a, u_D,2 = lift of the parts b (if any).
// Throws contactrb::Error for an invalid spec or a Dirichlet group missing from the mesh.
AffineTerms assemble_affine_terms(const CaseSpec& spec, const mesh::Mesh& reference);

// sum_j theta_j terms_j (theta.size() == terms.size(); throws otherwise). An empty list
// gives an empty matrix / a zero vector of size `size`.
fem::SparseMatrix combine(const std::vector<fem::SparseMatrix>& terms, const Eigen::VectorXd& theta);
Eigen::VectorXd combine(const std::vector<Eigen::VectorXd>& terms, const Eigen::VectorXd& theta, Eigen::Index size);

}  // namespace contactrb::cases
