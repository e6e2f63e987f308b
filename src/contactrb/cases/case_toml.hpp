#pragma once
// User cases from TOML files (toml++), and the inverse, so that a CaseSpec can be stored
// inside other files (e.g. snapshot stores). The format is in docs/cases.md; examples in
// examples/*/case.toml.
#include <string>

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

// The TOML text of a spec, read back by case_from_toml_string to an equal spec (doubles
// are written in their shortest round-trip form; parameter sets as explicit lists; a .msh
// path as given in the spec, i.e. resolved: absolute when it came from a case file or text).
std::string to_toml(const CaseSpec& spec);

// Field-by-field equality, exact on doubles, of every field but `origin` (provenance):
// for round-trip tests and consistency checks.
bool same_case(const CaseSpec& a, const CaseSpec& b);

}  // namespace contactrb::cases
