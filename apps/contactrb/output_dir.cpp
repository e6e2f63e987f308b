#include <filesystem>
#include <system_error>

#include "commands.hpp"
#include "contactrb/common/error.hpp"

namespace contactrb::app {

void ensure_output_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  require(!dir.empty(), "output directory must not be empty");
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    require(fs::is_directory(dir, ec), "output path '" + dir + "' exists and is not a directory");
    return;
  }
  fs::create_directories(dir, ec);
  if (ec) throw Error("cannot create output directory '" + dir + "': " + ec.message());
}

}  // namespace contactrb::app
