#include "contactrb/cases/case_record.hpp"

#include "contactrb/cases/case_toml.hpp"
#include "contactrb/common/error.hpp"

namespace contactrb::cases {

CaseSpec case_from_record(const std::string& kind, const std::string& text, const std::string& origin,
                          MeshFile mesh_file) {
  if (kind == "builtin") return builtin_case_spec(text);
  require(kind == "toml", "file '" + origin + "' records a case of unknown kind '" + kind + "'");
  return case_from_toml_string(text, origin, mesh_file);
}

}  // namespace contactrb::cases
