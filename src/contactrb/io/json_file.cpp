#include "contactrb/io/json_file.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "contactrb/common/error.hpp"
#include "contactrb/io/atomic_file.hpp"

namespace contactrb::io {

void write_json(const nlohmann::json& value, const std::string& path, int indent) {
  write_file_atomically(path, [&](std::ostream& out) { out << value.dump(indent) << '\n'; });
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  require(static_cast<bool>(in), "cannot read JSON file '" + path + "': no such file or not readable");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error("cannot read JSON file '" + path + "': " + e.what());
  }
}

}  // namespace contactrb::io
