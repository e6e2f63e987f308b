#pragma once
// The built-in cases (paper Section 6) by name; their full specifications (parameter domains,
// training sets, affine decompositions) are in case_spec.hpp.
#include <string>
#include <vector>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::cases {

struct CaseInfo {
  std::string name;
  std::string summary;  // one line for `contactrb cases`
  int dimension = 2;    // 2: triangles (plane strain), 3: tetrahedra
};

// The parametrized (frictionless) cases: every command and the reduced models take them.
const std::vector<CaseInfo>& builtin_cases();
// The frictional built-in cases (frictional_cases.hpp; docs/cases.md, "Frictional cases"):
// only `contactrb solve` takes them.
const std::vector<CaseInfo>& frictional_builtin_cases();
bool is_frictional_case(const std::string& name);
// Throws contactrb::Error for a name that is not a frictional built-in case.
const CaseInfo& frictional_case_info(const std::string& name);
// Throws contactrb::Error naming the unknown case and listing the known ones, or saying that a
// frictional case is for `contactrb solve` only.
const CaseInfo& find_case(const std::string& name);

// Reference mesh of a built-in case (mu = reference value) at refinement level `level`
// (0: the paper's mesh). Throws contactrb::Error for an unknown case, level < 0 or a 3D case.
mesh::Mesh reference_mesh(const std::string& name, int level = 0);
// The same for a three-dimensional built-in case (throws contactrb::Error for a 2D case).
mesh::Mesh3 reference_mesh3(const std::string& name, int level = 0);

}  // namespace contactrb::cases
