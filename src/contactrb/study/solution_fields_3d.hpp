#pragma once
// Three-dimensional solutions as files for ParaView and spreadsheets (docs/file-formats.md,
// "VTU files (ParaView)" and "multipliers.csv"): a displacement u on a tetrahedron mesh and the
// contact data on its slave surface, given as plain vectors (one entry per contact row), so that
// any solver's result can be written.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "contactrb/cases/parameter.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/mesh/mesh.hpp"
#include "contactrb/study/solution_fields.hpp"

namespace contactrb::study {

// The contact rows of a 3D solution, one per slave node (collocation: the row of node
// nodes[r]): its pressure lambda_r (>= 0), its deformed normal gap (> 0 open, 0 in contact,
// < 0 penetration) and its weight (the nodal area of the slave node).
struct SlaveSurfaceFields {
  std::vector<int> nodes;
  Eigen::VectorXd pressure;
  Eigen::VectorXd gap;
  Eigen::VectorXd weight;
};

// The triangles of the mesh group "slave" in the numbering of `nodes` (triangle k joins
// nodes[t[k][0..2]]: the points of contact.vtu, one per contact row). Throws contactrb::Error for
// a slave triangle on a node that is not in `nodes`.
std::vector<std::array<int, 3>> slave_triangles(const mesh::Mesh3& mesh, const std::vector<int>& nodes);

// The full stress tensor per tetrahedron (9 components, row by row: xx, xy, xz, yx, ..., zz)
// from fem::element_stress, and its von Mises value
// sqrt(((xx - yy)^2 + (yy - zz)^2 + (zz - xx)^2) / 2 + 3 (xy^2 + yz^2 + xz^2)).
struct CellStress3 {
  Eigen::VectorXd tensor;  // 9 per cell
  Eigen::VectorXd von_mises;
};
CellStress3 cell_stress(const mesh::Mesh3& mesh, const std::vector<fem::Material>& materials, const Eigen::VectorXd& u);

// The three ParaView files of a 3D solution on Omega(mu) = `mesh`, into the existing directory
// `dir`, each with the field data "one array per parameter name, its value at mu":
//   solution.vtu, solution_deformed.vtu: tetrahedra; point data displacement (3 components),
//     contact_pressure (the row's pressure at its slave node, 0 elsewhere); cell data body,
//     stress (9 components), von_mises;
//   contact.vtu: the triangles of the mesh group "slave" on the rows' nodes (in row order);
//     point data displacement, contact_pressure, gap.
// Throws contactrb::Error for sizes that do not match the mesh, the parameters or the rows, a
// slave triangle on a node without a row, or a file that cannot be written.
VtuFiles write_solution_vtus(const mesh::Mesh3& mesh, const std::vector<fem::Material>& materials,
                             const std::vector<cases::ParameterSpec>& parameters, const cases::Mu& mu,
                             const Eigen::VectorXd& u, const SlaveSurfaceFields& contact, const std::string& dir);

// multipliers.csv of a 3D solution, the columns of the 2D `solve` file without the abscissa:
// r, x, y, z (the row's slave node in Omega(mu) = `mesh`), gap, pressure, weight; one line per
// row. Throws contactrb::Error for inconsistent sizes or a file that cannot be written.
void write_multipliers_csv(const mesh::Mesh3& mesh, const SlaveSurfaceFields& contact, const std::string& path);

}  // namespace contactrb::study
