#include "contactrb/io/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <unistd.h>

#include "contactrb/common/error.hpp"

namespace contactrb::io {

namespace fs = std::filesystem;

namespace {

// Unique within the process (counter) and across processes (pid): two writers of the same
// target never share a temporary file.
fs::path temporary_path_for(const fs::path& target) {
  static std::atomic<unsigned long> counter{0};
  fs::path tmp = target;
  tmp += ".tmp." + std::to_string(static_cast<long>(::getpid())) + "." + std::to_string(counter++);
  return tmp;
}

void remove_quietly(const fs::path& p) {
  std::error_code ignored;
  fs::remove(p, ignored);
}

}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  require(!path.empty(), "cannot write a file with an empty path");
  const fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw Error("cannot write '" + path + "': it is a directory");
  const fs::path tmp = temporary_path_for(target);
  {
    std::ofstream out(tmp, std::ios::out | std::ios::trunc | std::ios::binary);
    if (!out) {
      const std::string reason = std::strerror(errno);
      throw Error("cannot write '" + path + "': " + reason);
    }
    try {
      write(out);
    } catch (...) {
      out.close();
      remove_quietly(tmp);
      throw;
    }
    out.flush();
    if (!out) {
      out.close();
      remove_quietly(tmp);
      throw Error("cannot write '" + path + "': write failed (disk full?)");
    }
    out.close();
    if (out.fail()) {
      remove_quietly(tmp);
      throw Error("cannot write '" + path + "': closing the file failed");
    }
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    remove_quietly(tmp);
    throw Error("cannot write '" + path + "': rename failed: " + ec.message());
  }
}

}  // namespace contactrb::io
