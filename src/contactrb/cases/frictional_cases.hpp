#pragma once
// Frictional cases: a contact problem, its load path and its friction law (hf/friction.hpp;
// docs/cases.md, "Frictional cases"): the built-in cattaneo (catalog.hpp,
// frictional_builtin_cases) and case files with friction keys. Reduced models are frictionless.
#include <vector>

#include "contactrb/cases/case_toml.hpp"
#include "contactrb/cases/parameter.hpp"
#include "contactrb/hf/contact_problem.hpp"
#include "contactrb/hf/friction.hpp"

namespace contactrb::cases {

struct FrictionalCase {
  hf::ContactProblem problem;      // the mesh, materials and constraint rows
  std::vector<hf::LoadStep> path;  // in order
  hf::FrictionSettings friction;
};

// cattaneo: hertz-a's half-disks (R = 1, gap 0.1, E = 15, nu = 0.35 for both: the normal and
// tangential problems decouple), the flat edges brought together by `approach` (top
// (0, -approach/2), bottom (0, approach/2)), then the upper edge moved by `tangential` along x in
// `tangential_steps` equal steps; Coulomb friction with `coefficient`.
struct CattaneoData {
  double approach = 0.13;    // > gap 0.1: a/R about 0.1 at 0.13
  double tangential = 0.01;  // Q / (f P) about 0.6 at f = 0.3
  double coefficient = 0.3;
  int tangential_steps = 1;
};
// level: the hertz-a mesh level (slave arc nodes mesh::hertz_arc_nodes_for_level). Throws
// contactrb::Error for an approach that does not close the gap or exceeds hertz-a's domain (0.45),
// a negative or non-finite coefficient or displacement, tangential_steps < 1, level < 0.
FrictionalCase cattaneo_case(int level, const CattaneoData& data = {});

// A frictional case file (case_toml.hpp, frictional_case_from_toml_file) at mu on `reference`
// (reference_mesh): the problem of make_problem, one load step per [[load_steps]] with its
// Dirichlet values and tractions at mu (a step without tractions: the case's [[traction]]), the
// friction law of [friction]. Throws contactrb::Error
// for mu outside the case's domain.
FrictionalCase frictional_case(const FrictionalCaseFile& file, const mesh::Mesh& reference, const Mu& mu);

}  // namespace contactrb::cases
