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
  // Built-in Gmsh geometry: "hertz" (two half-disks R1 = R2 = 1, gap 0.1, matching) or
  // "ring-block" (docs/meshes.md); refined by the `level` of make_problem.
  std::string generator;
  // .msh file (ASCII 4.1): an absolute path, or relative to the directory of the TOML
  // file it came from (resolved by the loader, so this holds the resolved path).
  std::string msh_file;
  std::array<std::string, 2> body_groups{"body1", "body2"};  // 2D groups: slave, master
  std::string slave_group = "slave";    // 1D group mapped to the mesh group "slave"
  std::string master_group = "master";  // 1D group mapped to the mesh group "master"
};

// Material and constant body force (per unit volume of Omega_i(mu)) of one body.
struct BodySpec {
  double E = 1.0;
  double nu = 0.3;
  Eigen::Vector2d load = Eigen::Vector2d::Zero();
};

// A Dirichlet value affine in the parameter: a + b mu.
struct AffineValue {
  double a = 0.0;
  double b = 0.0;
  double at(double mu) const { return a + b * mu; }
};

// Prescribed displacement on a boundary group of the mesh; an empty component is free.
struct DirichletSpec {
  std::string group;
  std::optional<AffineValue> ux;
  std::optional<AffineValue> uy;
};

struct CaseSpec {
  std::string name;
  std::string description;  // one line
  MeshSpec mesh;
  std::array<BodySpec, 2> bodies;  // 0: slave Omega_1, 1: master Omega_2
  std::vector<DirichletSpec> dirichlet;
  contact::Discretization constraint = contact::Discretization::Collocation;
  ParameterSpec parameter;
  std::string origin;  // "built-in" or the TOML file it was read from (for messages)
};

// Throws contactrb::Error naming the first inconsistency and `spec.origin`: no or two
// mesh sources, unknown generator, a material out of range, a non-finite value, an empty
// Dirichlet group name, a Dirichlet condition with no component, a DirichletScale
// parameter that no Dirichlet value depends on, an inconsistent parameter.
// Does not read the mesh (group names are checked by reference_mesh / make_problem).
void check_case_spec(const CaseSpec& spec);

// The built-in cases (paper Section 6; data in docs/cases.md). Throws contactrb::Error
// naming an unknown case and listing the known ones.
CaseSpec builtin_case_spec(const std::string& name);

// True when some Dirichlet value depends on mu (b != 0).
bool has_affine_dirichlet(const CaseSpec& spec);

}  // namespace contactrb::cases
