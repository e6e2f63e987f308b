#include "contactrb/common/input_file.hpp"

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <system_error>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/printable.hpp"

namespace contactrb {

namespace fs = std::filesystem;

const char* to_string(InputKind kind) { return kind == InputKind::Text ? "text" : "hdf5"; }

InputKind input_kind_from_string(const std::string& name) {
  return enum_from_string(name, "input kind", std::array{InputKind::Text, InputKind::Hdf5});
}

namespace {

constexpr std::uintmax_t kMiB = 1024 * 1024;

std::string mib_text(std::uintmax_t bytes) {
  // One decimal: "0.3 MiB" says more than "0 MiB" for a small limit.
  const std::uintmax_t tenths = (bytes * 10 + kMiB / 2) / kMiB;
  return std::to_string(tenths / 10) + "." + std::to_string(tenths % 10) + " MiB";
}

}  // namespace

std::uintmax_t input_size_limit(InputKind kind) {
  const char* variable = kind == InputKind::Text ? kTextInputLimitVariable : kHdf5InputLimitVariable;
  const std::uintmax_t fallback = kind == InputKind::Text ? kDefaultTextInputLimitMiB : kDefaultHdf5InputLimitMiB;
  const char* value = std::getenv(variable);
  if (value == nullptr || *value == '\0') return fallback * kMiB;
  const std::string text(value);
  // Digits only: strtoull would accept "-1" (as a huge value) and " 5".
  bool digits = text.size() <= 12;
  for (char c : text) digits = digits && c >= '0' && c <= '9';
  const std::uintmax_t mib = digits ? std::stoull(text) : 0;
  require(mib >= 1, std::string(variable) + " must be a positive whole number of MiB, got '" + printable(text) + "'");
  return mib * kMiB;
}

std::uintmax_t check_input_file(const std::string& path, const std::string& what, InputKind kind) {
  const std::string name = what + " '" + printable(path) + "'";
  require(!path.empty(), what + ": the file name is empty");
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows symbolic links
  if (st.type() == fs::file_type::not_found) throw Error(name + " does not exist");
  if (ec) throw Error(name + " cannot be examined: " + ec.message());
  if (st.type() == fs::file_type::directory) throw Error(name + " is a directory, not a file");
  if (st.type() != fs::file_type::regular) {
    throw Error(name + " is not a regular file (a device, FIFO or socket cannot be read as input)");
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw Error(name + " cannot be examined: " + ec.message());
  const std::uintmax_t limit = input_size_limit(kind);
  if (size > limit) {
    throw Error(name + " is " + mib_text(size) + ", above the input limit of " + mib_text(limit) + " (set " +
                (kind == InputKind::Text ? kTextInputLimitVariable : kHdf5InputLimitVariable) +
                " to a larger number of MiB to read it)");
  }
  return size;
}

std::string read_text_input(const std::string& path, const std::string& what) {
  const std::uintmax_t size = check_input_file(path, what, InputKind::Text);
  const std::uintmax_t limit = input_size_limit(InputKind::Text);
  std::ifstream in(path, std::ios::binary);
  require(static_cast<bool>(in), what + " '" + printable(path) + "' cannot be opened for reading");
  std::string text;
  text.reserve(static_cast<std::size_t>(size));
  std::array<char, 65536> buffer{};
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    // The file may have grown since the check: the limit holds for what is read.
    require(text.size() + got <= limit, what + " '" + printable(path) + "' grew above the input limit while read");
    text.append(buffer.data(), got);
  }
  require(!in.bad(), what + " '" + printable(path) + "': read error");
  return text;
}

}  // namespace contactrb
