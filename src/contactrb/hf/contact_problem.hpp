#pragma once
// One high-fidelity two-body contact problem at a fixed parameter value: the mesh of
// Omega(mu), materials, body loads, Dirichlet data and the constraint discretization.
#include <Eigen/Core>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/fem/traction.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::hf {

struct ContactProblem {
  mesh::Mesh mesh;                                // Omega(mu) = h(mu)(reference mesh)
  std::vector<fem::Material> materials;           // one per body
  std::vector<Eigen::Vector2d> body_loads;        // one per body, or empty (no load)
  std::vector<fem::TractionLoad> tractions;       // surface loads on boundary groups
  std::vector<fem::DirichletCondition> dirichlet;
  contact::Discretization discretization = contact::Discretization::Collocation;
};

// Throws contactrb::Error naming the first inconsistency (mesh invalid, one material per
// body, a missing Dirichlet or contact group, non-finite data).
void check_problem(const ContactProblem& problem);

}  // namespace contactrb::hf
