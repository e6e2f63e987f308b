// The case of a command's --case / --case-file, and a snapshot file, refused when the command
// has no 3D path.
#include <string>

#include "commands.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/io/snapshot_file.hpp"

namespace contactrb::app {

cases::CaseSpec read_case(const std::string& case_name, const std::string& case_file) {
  return case_file.empty() ? cases::builtin_case_spec(case_name) : cases::case_from_toml_file(case_file);
}

cases::CaseSpec read_case_2d(const std::string& case_name, const std::string& case_file, const std::string& command) {
  cases::CaseSpec spec = read_case(case_name, case_file);
  const int dimension = cases::case_dimension(spec);
  if (dimension != 2) {
    throw Error("`contactrb " + command + "` supports 2D cases only in this build: " + spec.context() + " is " +
                std::to_string(dimension) + "D (`contactrb mesh` writes its mesh)");
  }
  return spec;
}

void require_2d_snapshots(const io::SnapshotSet& set, const std::string& path, const std::string& command) {
  if (set.dimension != 2) {
    throw Error("`contactrb " + command + "` supports 2D snapshots only in this build: snapshot file '" + path +
                "' (case '" + set.case_name + "') is " + std::to_string(set.dimension) + "D");
  }
}

}  // namespace contactrb::app
