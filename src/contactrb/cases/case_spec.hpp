#pragma once
// The specification of a parametrized two-body contact case: everything needed to build
// the high-fidelity problem at any mu (case_problem.hpp), its affine decomposition
// (theta.hpp online, affine_assembly.hpp offline) and its parameter sets. The built-in
// cases of the paper (Section 6) and the user's TOML cases (case_toml.hpp) fill the same
// type: one code path (docs/cases.md).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/cases/parameter.hpp"
#include "contactrb/contact/contact_pair.hpp"

namespace contactrb::cases {

// Where the reference mesh (Omega = Omega(reference)) comes from: exactly one of a
// built-in generator or a Gmsh .msh file.
struct MeshSpec {
  // Built-in geometry: "hertz" (two half-disks R1 = R2 = 1, gap 0.1, matching) or
  // "ring-block" (docs/meshes.md) in 2D; "hertz-3d" (mesh::generate_hertz_3d) or
  // "stacked-blocks" (mesh::stacked_blocks) in 3D; refined by the `level` of make_problem.
  std::string generator;
  // .msh file (ASCII 4.1): an absolute path, or relative to the directory of the TOML
  // file it came from (resolved by the loader, so this holds the resolved path).
  std::string msh_file;
  // Groups of the mesh's dimension (2D: surfaces, 3D: volumes): slave, master.
  std::array<std::string, 2> body_groups{"body1", "body2"};
  std::string slave_group = "slave";    // boundary group (one dimension less) mapped to "slave"
  std::string master_group = "master";  // boundary group mapped to "master"
};

// Material and constant body force (per unit volume of Omega_i(mu)) of one body.
struct BodySpec {
  double E = 1.0;
  double nu = 0.3;
  Eigen::Vector2d load = Eigen::Vector2d::Zero();
};

// A Dirichlet value affine in one parameter: a + b mu_parameter (usually a dirichlet-scale
// parameter, whose only role this is; any kind may be named).
struct AffineValue {
  double a = 0.0;
  double b = 0.0;
  int parameter = 0;  // index in CaseSpec::parameters (used when b != 0)
  double at(const Mu& mu) const { return b == 0.0 ? a : a + b * mu(parameter); }
};

// Prescribed displacement on a boundary group of the mesh; an empty component is free.
struct DirichletSpec {
  std::string group;
  std::optional<AffineValue> ux;
  std::optional<AffineValue> uy;
  std::optional<AffineValue> uz = std::nullopt;  // 3D cases only (an initializer: 2D call sites omit it)
};

// A surface load (Neumann) on a boundary group, per unit length of Omega(mu): a fixed vector
// t, or a normal pressure p (t = -p n, n the outward normal: p > 0 pushes into the body),
// optionally times a traction parameter mu_k.
struct TractionSpec {
  std::string group;
  bool is_pressure = false;
  Eigen::Vector2d vector = Eigen::Vector2d::Zero();  // !is_pressure
  double pressure = 0.0;                              // is_pressure
  int parameter = -1;  // index of a traction parameter scaling it, -1: fixed
  // The body whose boundary holds the group (0 slave, 1 master); -1: found from the mesh.
  // Needed (and checked against the mesh) when that body has a body-scaling parameter.
  int body = -1;
};

struct CaseSpec {
  std::string name;
  std::string description;  // one line
  MeshSpec mesh;
  std::array<BodySpec, 2> bodies;  // 0: slave Omega_1, 1: master Omega_2
  std::vector<DirichletSpec> dirichlet;
  std::vector<TractionSpec> tractions;
  contact::Discretization constraint = contact::Discretization::Collocation;
  std::vector<ParameterSpec> parameters;  // mu = (mu_1, ..., mu_p), p >= 1
  std::vector<ParameterSet> sets;         // named point sets: "training", "verification", ...
  std::string origin;  // "built-in" or the TOML file it was read from (for messages)

  int num_parameters() const { return static_cast<int>(parameters.size()); }
  bool has_set(const std::string& set_name) const;
  // Throws contactrb::Error naming the set and listing the sets present.
  const std::vector<Mu>& set(const std::string& set_name) const;
  // "case 'name'" or "case 'name' from origin" (messages).
  std::string context() const;
  // Throws contactrb::Error for mu of the wrong size or outside the domain, naming the case.
  void check_mu(const Mu& mu) const;
  // The index of the body-scaling parameter of `body`, -1 if none (same for the other kinds).
  int parameter_of_body(ParameterKind kind, int body) const;
};

// Throws contactrb::Error naming the first inconsistency and `spec.origin`: no or two
// mesh sources, unknown generator, a material out of range, a non-finite value, an empty
// Dirichlet group name, a Dirichlet condition with no component, a Dirichlet value that
// names no parameter of the case, a DirichletScale parameter that no
// Dirichlet value depends on, a traction parameter that no traction names, a body-force
// parameter of a body without load, an inconsistent parameter list or set.
// Does not read the mesh (group names are checked by reference_mesh / make_problem).
void check_case_spec(const CaseSpec& spec);

// The dimension of the case's mesh: 2 or 3, from its generator or from the elements of its
// .msh file (mesh::msh_dimension). Throws contactrb::Error for a .msh file that cannot be read.
int case_dimension(const CaseSpec& spec);

// The built-in cases (paper Section 6; data in docs/cases.md). Throws contactrb::Error
// naming an unknown case and listing the known ones, or a frictional case (catalog.hpp, find_case).
CaseSpec builtin_case_spec(const std::string& name);

// True when some Dirichlet value depends on mu (b != 0).
bool has_affine_dirichlet(const CaseSpec& spec);
// The dirichlet-scale parameters some Dirichlet value depends on, increasing (lift terms 2..).
std::vector<int> dirichlet_parameters(const CaseSpec& spec);

}  // namespace contactrb::cases
