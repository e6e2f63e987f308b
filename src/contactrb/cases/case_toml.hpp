#pragma once
// User cases from TOML files (toml++), and the inverse, so that a CaseSpec can be stored
// inside other files (e.g. snapshot stores). The format is in docs/cases.md; examples in
// examples/*/case.toml.
#include <optional>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"

namespace contactrb::cases {

// Reads and checks a case file. A relative mesh.file is resolved against the directory of
// `path` and made absolute (so the spec, and the files recording it, work from any
// working directory). Throws contactrb::Error with one message naming the file, the line when known and
// the key: a TOML syntax error, an unknown key, a missing key, a wrong type, an invalid
// value (check_case_spec). The .msh file is not read here (see reference_mesh), but its
// existence is checked.
CaseSpec case_from_toml_file(const std::string& path);

// Same from the text of a case file; `origin` names it in messages and a relative
// mesh.file is resolved against the directory of `origin` (the working directory if it
// has none) and made absolute.
// MeshFile::Optional: a mesh.file that does not exist (any more) is accepted; for a case
// recorded in a snapshot or model file that stores its mesh (docs/file-formats.md, /mesh).
enum class MeshFile { Required, Optional };
const char* to_string(MeshFile value);  // "required" | "optional"
MeshFile mesh_file_from_string(const std::string& name);  // throws contactrb::Error
CaseSpec case_from_toml_string(const std::string& text, const std::string& origin,
                               MeshFile mesh_file = MeshFile::Required);

// The friction keys of a case file ([friction], [[load_steps]]; docs/cases.md, "Frictional case
// files"). case_from_toml_file and case_from_toml_string refuse a file that has them (only
// `contactrb solve` handles friction).
struct FrictionFileSpec {
  bool has_friction = false;
  std::string law = "coulomb";  // "coulomb" | "tresca" (hf::friction_law_from_string)
  double coefficient = 0.0;     // coulomb: f >= 0
  int coefficient_parameter = -1;  // coulomb: the friction-coefficient parameter giving f, -1: `coefficient`
  double threshold = 0.0;       // tresca: s >= 0
  struct Step {
    std::vector<DirichletSpec> dirichlet;  // the groups and components of CaseSpec::dirichlet, in order
    std::vector<TractionSpec> tractions;
  };
  std::vector<Step> steps;  // at least one
};
struct FrictionalCaseFile {
  CaseSpec spec;  // the frictionless keys, checked as case_from_toml_file does
  FrictionFileSpec friction;
};
// nullopt for a file without friction keys; otherwise the case and its friction, each key
// checked (throws contactrb::Error naming the file, the line and the key: an unknown law, a
// negative or non-finite coefficient or threshold, the key of the other law, [friction] without
// [[load_steps]] or the reverse, no step, a step that prescribes other groups or components than
// [[dirichlet]], a constraint other than collocation).
std::optional<FrictionalCaseFile> frictional_case_from_toml_file(const std::string& path);

// The TOML text of a spec, read back by case_from_toml_string to an equal spec (doubles
// are written in their shortest round-trip form; parameter sets as explicit lists; a .msh
// path as given in the spec, i.e. resolved: absolute when it came from a case file or text).
std::string to_toml(const CaseSpec& spec);

// Field-by-field equality, exact on doubles, of every field but `origin` (provenance):
// for round-trip tests and consistency checks.
bool same_case(const CaseSpec& a, const CaseSpec& b);

}  // namespace contactrb::cases
