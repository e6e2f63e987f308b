#pragma once
// The parameter functions of the affine decomposition (paper (46), (49)), kept apart from
// the assembly of the parameter-independent terms (affine_assembly.hpp, offline only), as
// in rbOOmit: the online stage evaluates these small objects and nothing else.
//
//   A(mu)   = sum_j theta^a_j(mu) A_j        (stiffness, J^a terms)
//   f(mu)   = sum_j theta^f_j(mu) f_j        (body loads, J^f terms)
//   u_D(mu) = sum_j theta^D_j(mu) u_D,j      (Dirichlet lift, J^D terms)
//
// Every theta of our parameter kinds is a monomial c (mu / s)^p, stored as three numbers
// so that a reduced model can be written to a file and evaluated without any case data.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace contactrb::cases {

struct CaseSpec;

// theta(mu) = coefficient * (mu / scale)^power.
struct ThetaMonomial {
  double coefficient = 1.0;
  double scale = 1.0;
  int power = 0;
  double operator()(double mu) const;
};

struct AffineThetas {
  std::vector<ThetaMonomial> a;     // J^a
  std::vector<ThetaMonomial> f;     // J^f (empty: f = 0)
  std::vector<ThetaMonomial> lift;  // J^D (empty: u_D = 0)
};

// (theta_1(mu), ..., theta_J(mu)).
Eigen::VectorXd evaluate(const std::vector<ThetaMonomial>& thetas, double mu);

// The theta functions of a case; the term order matches assemble_affine_terms.
//  a: one term, theta = 1. A body scaled uniformly by s in 2D keeps its stiffness matrix:
//     grad phi scales by 1/s, the area by s^2 (the J^a = 1 of docs/cases.md).
//  f: one term per body with a non-zero load: |det M_i(mu)| = s_i^2 (paper (48)).
//  lift: theta = 1 (the constant parts a) and, if some value depends on mu, theta = mu
//     (the parts b).
AffineThetas theta_functions(const CaseSpec& spec);

}  // namespace contactrb::cases
