#pragma once
// The files of a frictional solve (hf/friction.hpp; docs/file-formats.md, "Frictional solve
// files"): multipliers.csv with the tangential traction and the state of each row, VTU files of
// the displacement and of the slave boundary with the normal and tangential tractions, the state
// and the slip, and the same VTU files at the end of each load step with their ParaView
// collections (.pvd). 2D and 3D, collocation rows (one per slave node).
#include <string>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/hf/friction.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::study {

struct FrictionFiles {
  std::string vtu;           // dir/solution.vtu: Omega with "displacement"
  std::string deformed_vtu;  // dir/solution_deformed.vtu: the same on the deformed configuration
  // dir/contact.vtu: the slave boundary (2D: its chain as lines; 3D: its triangles), one point per
  // row, with "displacement", "contact_pressure", "tangential_traction" (2D: the signed traction
  // along tau; 3D: the vector sum_j t_j tau_j), "state" (0 open, 1 stick, 2 slip), "slip" (as
  // the traction)
  std::string contact_vtu;
  // dir/multipliers.csv, 2D: r,abscissa,x,y,gap,pressure,tangential,state,weight;
  // 3D: r,x,y,z,gap,pressure,tangential_1,tangential_2,state,weight
  std::string multipliers;
};

// Into the existing directory `dir`. Throws contactrb::Error for sizes that do not match the mesh
// or the rows, or a file that cannot be written.
template <int Dim>
FrictionFiles write_friction_fields(const mesh::SimplexMesh<Dim>& mesh, const contact::ContactPairOf<Dim>& pair,
                                    const contact::ContactQuadrature& quadrature,
                                    const hf::BasicFrictionalSolution<Dim>& solution, const std::string& dir);

// The fields at the end of each load step: dir/steps/solution_K.vtu and dir/steps/contact_K.vtu
// (K = 1, 2, ... the step's number in the path; the arrays of solution.vtu and contact.vtu), and
// the collections dir/solution_steps.pvd and dir/contact_steps.pvd (timestep K).
struct FrictionStepFiles {
  std::string solution_pvd, contact_pvd;
  std::vector<std::string> vtus;  // every file of dir/steps written, in order
};

// Collects the steps of a path (an hf::LoadStepObserver) and writes them.
template <int Dim>
class FrictionStepSeries {
 public:
  // Borrows the mesh, pair and quadrature: they must outlive the series.
  FrictionStepSeries(const mesh::SimplexMesh<Dim>& mesh, const contact::ContactPairOf<Dim>& pair,
                     const contact::ContactQuadrature& quadrature);
  // The state at the end of step `step` (0-based) of the path.
  void add(std::size_t step, const hf::BasicFrictionalSolution<Dim>& state);
  std::size_t size() const { return steps_.size(); }
  // Into the existing directory `dir` (dir/steps is created). Throws contactrb::Error as
  // write_friction_fields.
  FrictionStepFiles write(const std::string& dir) const;

 private:
  struct Step {
    std::size_t index;
    hf::BasicFrictionalSolution<Dim> state;
  };
  const mesh::SimplexMesh<Dim>* mesh_;
  const contact::ContactPairOf<Dim>* pair_;
  const contact::ContactQuadrature* quadrature_;
  std::vector<Step> steps_;
};

extern template FrictionFiles write_friction_fields(const mesh::SimplexMesh<2>&, const contact::ContactPairOf<2>&,
                                                    const contact::ContactQuadrature&,
                                                    const hf::BasicFrictionalSolution<2>&, const std::string&);
extern template FrictionFiles write_friction_fields(const mesh::SimplexMesh<3>&, const contact::ContactPairOf<3>&,
                                                    const contact::ContactQuadrature&,
                                                    const hf::BasicFrictionalSolution<3>&, const std::string&);
extern template class FrictionStepSeries<2>;
extern template class FrictionStepSeries<3>;

}  // namespace contactrb::study
