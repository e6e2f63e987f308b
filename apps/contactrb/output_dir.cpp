#include <filesystem>
#include <unistd.h>
#include <system_error>

#include "commands.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"

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

void check_output_file(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  require(!p.filename().empty(), "--out '" + path + "' names a directory, not a file");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  std::error_code ec;
  if (!fs::exists(dir, ec)) {  // created as `mkdir -p` would (every missing parent)
    fs::create_directories(dir, ec);
    if (ec) throw Error("cannot create the directory of --out '" + path + "': " + ec.message());
  }
  require(fs::is_directory(dir, ec), "the directory of --out '" + path + "' is not a directory");
  require(::access(dir.c_str(), W_OK) == 0, "the directory of --out '" + path + "' is not writable");
  require(!fs::is_directory(p, ec), "--out '" + path + "' is a directory");
  check_output_target(p);
}

void check_file_roles(const std::vector<FileRole>& inputs, const std::vector<FileRole>& outputs) {
  const auto named = [](const FileRole& f) { return f.role + " '" + f.path + "'"; };
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const FileRole& out = outputs[i];
    check_output_target(out.path);
    for (const FileRole& in : inputs) {
      if (!in.path.empty() && same_file(out.path, in.path)) {
        throw Error("the output " + named(out) + " is the input " + named(in) +
                    ": writing it would destroy the input; choose another output path");
      }
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (same_file(out.path, outputs[k].path)) {
        throw Error("the outputs " + named(outputs[k]) + " and " + named(out) +
                    " are the same file: one would overwrite the other; choose another output path");
      }
    }
  }
}

}  // namespace contactrb::app
