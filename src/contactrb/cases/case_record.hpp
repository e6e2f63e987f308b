#pragma once
// The case a snapshot file or a reduced model was made from, as they record it: a kind
// ("builtin": the built-in case of that name; "toml": the whole TOML text of the case,
// cases::to_toml) and its text. One reader for every file that records a case.
#include <string>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"

namespace contactrb::cases {

// Throws contactrb::Error naming `origin` (the file holding the record) for an unknown kind,
// an unknown built-in name or an invalid TOML text. MeshFile::Optional: the recorded .msh file
// may be gone (the file holding the record stores the mesh itself).
CaseSpec case_from_record(const std::string& kind, const std::string& text, const std::string& origin,
                          MeshFile mesh_file = MeshFile::Required);

}  // namespace contactrb::cases
