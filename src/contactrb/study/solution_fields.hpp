#pragma once
// Solutions as files for ParaView (docs/file-formats.md, "VTU files (ParaView)"): the fields of a displacement u
// and multipliers lambda on Omega(mu), written by `contactrb solve` (the HF solution) and
// `contactrb online --out` (the reconstructed reduced solution). For the online case the
// reference mesh is the one stored in the model file (or, for a reconstruction without one, is
// regenerated from the case the model records), mapped by h(mu), and checked against the
// reconstruction's DOF count.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/mesh/mesh.hpp"
#include "contactrb/model/reconstruction.hpp"
#include "contactrb/model/reduced_model.hpp"

namespace contactrb::study {

// reconstruction.mesh, or cases::reference_mesh(spec, model.level) when it is empty, checked against
// the case at the model's level by cases::recorded_reference_mesh (`origin`: the model file).
// Throws contactrb::Error when they disagree (a damaged or crafted file, or the case changed
// since the model was built, e.g. an edited .msh file).
mesh::Mesh model_reference_mesh(const cases::CaseSpec& spec, const contactrb::model::ReducedModel& model,
                                const contactrb::model::ReducedReconstruction& reconstruction,
                                const std::string& origin);

// The stress of a P1 displacement, constant per triangle: xx, yy, xy from fem::element_stress;
// plane strain adds zz = nu (xx + yy) (nu of the triangle's body); von Mises
// sqrt(((xx - yy)^2 + (yy - zz)^2 + (zz - xx)^2) / 2 + 3 xy^2). One value per triangle each.
struct CellStress {
  Eigen::VectorXd xx, yy, xy, zz, von_mises;
};
CellStress cell_stress(const mesh::Mesh& mesh, const std::vector<fem::Material>& materials, const Eigen::VectorXd& u);

// Contact pressure per node: at each slave node the W-weighted mean of the rows integrating it
// (collocation: lambda_r at the node of row r; LAC spreads each macro-segment's value), 0
// elsewhere. Throws contactrb::Error when lambda is not one value per row of `quadrature`.
Eigen::VectorXd nodal_pressure(const mesh::Mesh& mesh, const contact::ContactPair& pair,
                               const contact::ContactQuadrature& quadrature, const Eigen::VectorXd& lambda);

struct VtuFiles {
  std::string vtu;           // dir/solution.vtu: Omega(mu)
  std::string deformed_vtu;  // dir/solution_deformed.vtu: the same on Omega(mu) + u
  std::string contact_vtu;   // dir/contact.vtu: the slave boundary of Omega(mu) as line cells
};
// The three ParaView files of (u, lambda) on Omega(mu) = `mesh`, into the existing directory
// `dir`, each with the field data "one array per parameter name, its value at mu":
//   solution.vtu, solution_deformed.vtu: point data displacement, contact_pressure
//     (nodal_pressure); cell data body, stress_xx, stress_yy, stress_xy, stress_zz, von_mises
//     (cell_stress with `materials`, the materials at mu);
//   contact.vtu: the slave chain's nodes (in chain order) and edges; point data displacement,
//     contact_pressure, gap (the deformed normal gap at the node, g(u)_s - k(u; u)_s of
//     contact/projection.hpp: > 0 open, 0 in contact, < 0 penetration; a node beyond the master's
//     end: its distance to the master).
// Throws contactrb::Error for sizes that do not match the mesh, the parameters or the rows,
// or a file that cannot be written.
VtuFiles write_solution_vtus(const mesh::Mesh& mesh, const std::vector<fem::Material>& materials,
                             const contact::ContactPair& pair, const contact::ContactQuadrature& quadrature,
                             const std::vector<cases::ParameterSpec>& parameters, const cases::Mu& mu,
                             const Eigen::VectorXd& u, const Eigen::VectorXd& lambda, const std::string& dir);

struct SolutionFiles {
  std::string vtu;           // dir/solution.vtu (write_solution_vtus)
  std::string deformed_vtu;  // dir/solution_deformed.vtu
  std::string contact_vtu;   // dir/contact.vtu
  std::string multipliers;   // dir/multipliers.csv: r,x,y,lambda (x, y: the row's slave node in Omega)
};

// The names of the files write_solution_fields writes into `dir`, in SolutionFiles' order.
SolutionFiles solution_file_names(const std::string& dir);

// Writes the four files of a total displacement u (num_dofs) and multipliers lambda (one per
// constraint row of `discretization` on Omega(mu)) into the existing directory `dir`: the
// VTU files of write_solution_vtus (materials and parameter names of `spec`) and
// multipliers.csv. Throws contactrb::Error for sizes that do not match the mesh or the
// constraint rows, or a file that cannot be written.
SolutionFiles write_solution_fields(const cases::CaseSpec& spec, const mesh::Mesh& reference, const cases::Mu& mu,
                                    contact::Discretization discretization, const Eigen::VectorXd& u,
                                    const Eigen::VectorXd& lambda, const std::string& dir);

}  // namespace contactrb::study
