#include "contactrb/hf/contact_problem.hpp"

#include <cmath>
#include <string>

#include "contactrb/common/error.hpp"

namespace contactrb::hf {

template <int Dim>
void check_problem(const BasicContactProblem<Dim>& p) {
  mesh::validate(p.mesh);
  const int bodies = 2;
  require(p.mesh.num_bodies() == bodies,
          "a contact problem needs two bodies; the mesh has " + std::to_string(p.mesh.num_bodies()));
  require(static_cast<int>(p.materials.size()) == bodies,
          "one material per body expected (" + std::to_string(bodies) + "), got " +
              std::to_string(p.materials.size()));
  for (const fem::Material& m : p.materials) fem::check_material(m);
  require(p.body_loads.empty() || static_cast<int>(p.body_loads.size()) == bodies,
          "body loads: one per body or none, got " + std::to_string(p.body_loads.size()));
  for (const auto& l : p.body_loads) require(l.allFinite(), "body load is not finite");
  for (const fem::SurfaceLoad<Dim>& t : p.tractions) {
    require(p.mesh.has_boundary(t.group), "traction group '" + t.group + "' is not a boundary group of the mesh");
    require(t.vector.allFinite() && std::isfinite(t.pressure), "traction load on '" + t.group + "' is not finite");
  }
  for (const fem::DirichletCondition& c : p.dirichlet) {
    p.mesh.boundary(c.group);  // throws naming the group
    require((!c.ux || std::isfinite(*c.ux)) && (!c.uy || std::isfinite(*c.uy)) && (!c.uz || std::isfinite(*c.uz)),
            "Dirichlet data on group '" + c.group + "' is not finite");
  }
  p.mesh.boundary(mesh::kSlaveBoundary);
  p.mesh.boundary(mesh::kMasterBoundary);
}

template void check_problem(const BasicContactProblem<2>&);
template void check_problem(const BasicContactProblem<3>&);

}  // namespace contactrb::hf
