// The names of cases::MeshFile (case_toml.hpp).
#include <array>
#include <string>

#include "contactrb/cases/case_toml.hpp"
#include "contactrb/common/enum_names.hpp"

namespace contactrb::cases {

const char* to_string(MeshFile value) { return value == MeshFile::Required ? "required" : "optional"; }

MeshFile mesh_file_from_string(const std::string& name) {
  return enum_from_string(name, "mesh file requirement", std::array{MeshFile::Required, MeshFile::Optional});
}

}  // namespace contactrb::cases
