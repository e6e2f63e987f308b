#pragma once
// From a case specification to the high-fidelity problem at mu: the reference mesh, the
// geometric maps applied to it (same connectivity for every mu, so snapshots at different
// mu live in one R^N), the materials and the Dirichlet data at mu.
#include <optional>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/hf/contact_problem.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::cases {

// The reference mesh Omega = Omega(reference) of a case at refinement level `level`
// (0: the generator's default, the paper's mesh). A .msh case has level 0 only; its
// slave and master groups are renamed "slave" and "master". Throws contactrb::Error naming
// the file and the problem (missing file, missing group, level > 0 for a .msh).
mesh::Mesh reference_mesh(const CaseSpec& spec, int level = 0);

// The reference mesh of a three-dimensional case (generator "hertz-3d" or "stacked-blocks", or a
// .msh file of tetrahedra), with the same checks. "hertz-3d" at level k has the contact-zone size
// mesh::hertz_3d_fine_size_for_level(k); "stacked-blocks" is mesh::stacked_blocks(k) with the
// groups "symmetry_x" and "symmetry_y" (the block faces on x = 0 and y = 0) added. Throws
// contactrb::Error for a 2D case, a level outside the generator's range, or as reference_mesh.
mesh::Mesh3 reference_mesh3(const CaseSpec& spec, int level = 0);

// Throws contactrb::Error naming the case for a traction group missing from `reference`, or
// on another body than the case says (reference_mesh runs it; for built-in generators too).
void check_tractions(const CaseSpec& spec, const mesh::Mesh& reference);

// Omega(mu) = h(mu)(reference): the geometric maps applied to a copy of `reference`.
mesh::Mesh mapped_mesh(const CaseSpec& spec, const mesh::Mesh& reference, const Mu& mu);
mesh::Mesh mapped_mesh(const CaseSpec& spec, const mesh::Mesh& reference, double mu);  // p = 1

// The HF problem at mu. `constraint` overrides the case's discretization. Throws
// contactrb::Error for an invalid spec or mu outside the parameter domain.
hf::ContactProblem make_problem(const CaseSpec& spec, const Mu& mu, int level = 0,
                                std::optional<contact::Discretization> constraint = std::nullopt);
// Same, from a reference mesh built once by reference_mesh(spec, level) (parameter sweeps).
hf::ContactProblem make_problem(const CaseSpec& spec, const mesh::Mesh& reference, const Mu& mu,
                                std::optional<contact::Discretization> constraint = std::nullopt);
// One-parameter cases: mu as a number (throws contactrb::Error for p != 1).
hf::ContactProblem make_problem(const CaseSpec& spec, double mu, int level = 0,
                                std::optional<contact::Discretization> constraint = std::nullopt);
hf::ContactProblem make_problem(const CaseSpec& spec, const mesh::Mesh& reference, double mu,
                                std::optional<contact::Discretization> constraint = std::nullopt);

// The 3D HF problem at mu on `reference` (reference_mesh3): 3D cases have no geometric
// parameter, body load or traction (case_spec.hpp), so Omega(mu) is the reference mesh.
hf::ContactProblem3 make_problem(const CaseSpec& spec, const mesh::Mesh3& reference, const Mu& mu,
                                 std::optional<contact::Discretization> constraint = std::nullopt);

// Dirichlet conditions at mu (values a + b mu_k).
std::vector<fem::DirichletCondition> dirichlet_at(const CaseSpec& spec, const Mu& mu);
// The materials at mu (E of a body with a young-modulus parameter is mu_k).
std::vector<fem::Material> materials(const CaseSpec& spec, const Mu& mu);
// The body loads (times their body-force parameters) and the tractions (times their traction
// parameters) at mu.
std::vector<Eigen::Vector2d> body_loads_at(const CaseSpec& spec, const Mu& mu);
std::vector<fem::TractionLoad> tractions_at(const CaseSpec& spec, const Mu& mu);

}  // namespace contactrb::cases
