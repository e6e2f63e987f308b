#pragma once
// Reconstructed reduced solutions as files on the HF mesh Omega(mu) (`contactrb online --out`):
// the reference mesh is regenerated from the case the model records (it is not stored in the
// model file), mapped by h(mu), and checked against the reconstruction's DOF count.
#include <Eigen/Core>
#include <string>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/mesh/mesh.hpp"
#include "contactrb/rb/reconstruction.hpp"
#include "contactrb/rb/reduced_model.hpp"

namespace contactrb::rb {

// cases::reference_mesh(spec, model.level). Throws contactrb::Error when its DOF count is not
// the reconstruction's (the case changed since the model was built, e.g. another Gmsh version
// or an edited .msh file).
mesh::Mesh model_reference_mesh(const cases::CaseSpec& spec, const ReducedModel& model,
                                const ReducedReconstruction& reconstruction);

struct SolutionFiles {
  std::string vtu;           // dir/solution.vtu: Omega(mu), point fields displacement, contact_pressure
  std::string deformed_vtu;  // dir/solution_deformed.vtu: the same on Omega(mu) + u
  std::string multipliers;   // dir/multipliers.csv: r,x,y,lambda (x, y: the row's slave node in Omega)
};

// Writes the three files of a total displacement u (num_dofs) and multipliers lambda (one per
// constraint row of `discretization` on Omega(mu)) into the existing directory `dir`.
// contact_pressure is, at each slave node, the W-weighted mean of the rows integrating it
// (collocation: lambda_r at the node of row r), 0 elsewhere. Throws contactrb::Error for sizes
// that do not match the mesh or the constraint rows, or a file that cannot be written.
SolutionFiles write_solution_fields(const cases::CaseSpec& spec, const mesh::Mesh& reference, const cases::Mu& mu,
                                    contact::Discretization discretization, const Eigen::VectorXd& u,
                                    const Eigen::VectorXd& lambda, const std::string& dir);

}  // namespace contactrb::rb
