#include "contactrb/cases/catalog.hpp"

#include <sstream>

#include "contactrb/common/error.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"

namespace contactrb::cases {

const std::vector<CaseInfo>& builtin_cases() {
  static const std::vector<CaseInfo> cases{
      {"hertz-a", "two half-disks R1 = R2 = 1, gap 0.1, imposed displacement mu in [0.15, 0.45], collocation"},
      {"hertz-b", "two half-disks, lower radius R2 = mu in [0.9, 1.12], non-matching meshes, collocation"},
      {"ring-block", "half-ring of radius mu in [0.95, 1.15] pressed on a softer block, LAC"},
      {"hertz-3p", "two half-disks: imposed displacement delta x lower radius R2 x lower modulus E2, collocation"},
      {"hertz-3d", "quarter of a hemisphere R = 1 pressed on a block, imposed displacement mu in [0.01, 0.03]", 3},
      {"patch-3d", "two stacked blocks, non-matching meshes, uniform compression mu in [0.01, 0.03], LAC", 3},
  };
  return cases;
}

const std::vector<CaseInfo>& frictional_builtin_cases() {
  static const std::vector<CaseInfo> cases{
      {"cattaneo", "frictional (Coulomb, f = mu in [0, 1]): the hertz-a half-disks pressed together, then the upper "
                   "edge moved sideways; `solve` only"},
      {"cattaneo-3d", "frictional (Coulomb, f = mu in [0, 1]): the hertz-3d hemisphere (full model) pressed on its "
                      "block, then its flat top moved sideways; `solve` only", 3},
  };
  return cases;
}

bool is_frictional_case(const std::string& name) {
  for (const CaseInfo& c : frictional_builtin_cases()) {
    if (c.name == name) return true;
  }
  return false;
}

const CaseInfo& frictional_case_info(const std::string& name) {
  for (const CaseInfo& c : frictional_builtin_cases()) {
    if (c.name == name) return c;
  }
  throw Error("'" + name + "' is not a frictional built-in case");
}

const CaseInfo& find_case(const std::string& name) {
  // A frictional case has no CaseSpec (no reduced model, no parameter box of this kind): every
  // path that asks for one (snapshots, offline, report, mesh, Python) refuses it here.
  require(!is_frictional_case(name), "case '" + name +
                                         "' is frictional: only `contactrb solve` handles friction (docs/cases.md, "
                                         "\"Frictional cases\")");
  for (const CaseInfo& c : builtin_cases()) {
    if (c.name == name) return c;
  }
  std::ostringstream os;
  os << "unknown case '" << name << "' (built-in cases:";
  for (const CaseInfo& c : builtin_cases()) os << " " << c.name;
  os << "; frictional:";
  for (const CaseInfo& c : frictional_builtin_cases()) os << " " << c.name;
  os << ")";
  throw Error(os.str());
}

mesh::Mesh reference_mesh(const std::string& name, int level) {
  return reference_mesh(builtin_case_spec(name), level);
}

mesh::Mesh3 reference_mesh3(const std::string& name, int level) {
  return reference_mesh3(builtin_case_spec(name), level);
}

}  // namespace contactrb::cases
