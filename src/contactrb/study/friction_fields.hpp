#pragma once
// The files of a frictional solve (hf/friction.hpp; docs/file-formats.md, "Frictional solve
// files"): multipliers.csv with the tangential traction and the state of each row, and VTU files
// of the displacement and of the slave boundary with the normal and tangential tractions, the
// state and the slip. 2D, collocation rows (one per slave node).
#include <string>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/hf/friction.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::study {

struct FrictionFiles {
  std::string vtu;           // dir/solution.vtu: Omega with "displacement"
  std::string deformed_vtu;  // dir/solution_deformed.vtu: the same on the deformed configuration
  std::string contact_vtu;   // dir/contact.vtu: the slave chain with "displacement", "contact_pressure",
                             // "tangential_traction", "state" (0 open, 1 stick, 2 slip), "slip"
  // dir/multipliers.csv: r,abscissa,x,y,gap,pressure,tangential,state,weight
  std::string multipliers;
};

// Into the existing directory `dir`. Throws contactrb::Error for sizes that do not match the mesh
// or the rows, or a file that cannot be written.
FrictionFiles write_friction_fields(const mesh::Mesh& mesh, const contact::ContactPair& pair,
                                    const contact::ContactQuadrature& quadrature,
                                    const hf::FrictionalSolution& solution, const std::string& dir);

}  // namespace contactrb::study
