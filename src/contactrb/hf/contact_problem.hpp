#pragma once
// One high-fidelity two-body contact problem at a fixed parameter value: the mesh of
// Omega(mu), materials, body loads, Dirichlet data and the constraint discretization, in 2D
// (triangles) or 3D (tetrahedra).
#include <Eigen/Core>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/fem/traction.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::hf {

template <int Dim>
struct BasicContactProblem {
  static constexpr int dim = Dim;
  mesh::SimplexMesh<Dim> mesh;                            // Omega(mu) = h(mu)(reference mesh)
  std::vector<fem::Material> materials;                   // one per body
  std::vector<Eigen::Matrix<double, Dim, 1>> body_loads;  // one per body, or empty (no load)
  std::vector<fem::SurfaceLoad<Dim>> tractions;           // surface loads on boundary groups
  std::vector<fem::DirichletCondition> dirichlet;         // uz: 3D only
  contact::Discretization discretization = contact::Discretization::Collocation;  // 3D: Collocation
};
using ContactProblem = BasicContactProblem<2>;
using ContactProblem3 = BasicContactProblem<3>;

// Throws contactrb::Error naming the first inconsistency (mesh invalid, one material per
// body, a missing Dirichlet or contact group, non-finite data).
template <int Dim>
void check_problem(const BasicContactProblem<Dim>& problem);

extern template void check_problem(const BasicContactProblem<2>&);
extern template void check_problem(const BasicContactProblem<3>&);

}  // namespace contactrb::hf
