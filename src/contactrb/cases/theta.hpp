#pragma once
// The parameter functions of the affine decomposition (paper (46), (49)), kept apart from
// the assembly of the parameter-independent terms (affine_assembly.hpp, offline only), as
// in rbOOmit: the online stage evaluates these small objects and nothing else.
//
//   A(mu)   = sum_j theta^a_j(mu) A_j        (stiffness, J^a terms)
//   f(mu)   = sum_j theta^f_j(mu) f_j        (body and traction loads, J^f terms)
//   u_D(mu) = sum_j theta^D_j(mu) u_D,j      (Dirichlet lift, J^D terms)
//
// Every theta of our parameter kinds is a product of monomials in single parameters,
// c prod_k (mu_k / s_k)^p_k (the product structure of the kinds, docs/cases.md), stored as
// numbers so that a reduced model can be written to a file and evaluated without any case data.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace contactrb::cases {

struct CaseSpec;

// One factor (mu_parameter / scale)^power.
struct ThetaFactor {
  int parameter = 0;
  double scale = 1.0;
  int power = 0;
};

// theta(mu) = coefficient * prod_factors (mu_k / s_k)^p_k.
struct ThetaMonomial {
  double coefficient = 1.0;
  std::vector<ThetaFactor> factors;
  double operator()(const Eigen::VectorXd& mu) const;
};

struct AffineThetas {
  std::vector<ThetaMonomial> a;     // J^a
  std::vector<ThetaMonomial> f;     // J^f (empty: f = 0)
  std::vector<ThetaMonomial> lift;  // J^D (empty: u_D = 0)
};

// (theta_1(mu), ..., theta_J(mu)).
Eigen::VectorXd evaluate(const std::vector<ThetaMonomial>& thetas, const Eigen::VectorXd& mu);

// Throws contactrb::Error naming `what` for a factor whose parameter index is outside
// [0, num_parameters), a zero or non-finite scale or coefficient.
void check_thetas(const AffineThetas& thetas, int num_parameters, const std::string& what);

// The theta functions of a case; the term order matches assemble_affine_terms. Defined in
// case_thetas.cpp, part of contactrb::cases (offline): the online library does not have it.
//  a: one term, theta = 1, when no body has a young-modulus parameter (a body scaled
//     uniformly by s in 2D keeps its stiffness matrix: grad phi scales by 1/s, the area by
//     s^2, the J^a = 1 of docs/cases.md); otherwise one term per body, theta = E_i = mu_k for
//     a body with a young-modulus parameter (its A_i assembled with E = 1), 1 for the other.
//  f: per body with a non-zero load: s_i^2 (|det M_i(mu)|, paper (48)) times mu_k of its
//     body-force parameter, if any; then per traction: s_i (the length of a boundary edge of a
//     uniformly scaled body) times mu_k of its traction parameter, if any.
//  lift: theta = 1 (the constant parts a), then theta = mu_k for every dirichlet-scale
//     parameter k that some value depends on (the parts b of the values that name it).
AffineThetas theta_functions(const CaseSpec& spec);

}  // namespace contactrb::cases
