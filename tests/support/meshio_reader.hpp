#pragma once
// The independent VTU reader of the tests: Debian's python3-meshio, run with /usr/bin/python3
// (the system Python that has it), through tests/io/read_vtu.py, which prints the file as JSON
// (points, cells, point_data, cell_data, field_data).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <sys/wait.h>

namespace contactrb::test {

inline constexpr const char* kSystemPython = "/usr/bin/python3";

inline bool meshio_available() {
  if (!std::filesystem::exists(kSystemPython)) return false;
  const std::string cmd = std::string(kSystemPython) + " -c 'import meshio' >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

// Runs read_vtu.py on `path`; returns the parsed JSON. Fails the test (and returns null) on a
// reader error.
inline nlohmann::json read_vtu_with_meshio(const std::filesystem::path& path) {
  const std::string cmd = std::string(kSystemPython) + " " + CONTACTRB_SOURCE_DIR + "/tests/io/read_vtu.py '" +
                          path.string() + "' 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("popen failed");
  std::string output;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) output.append(buf.data(), n);
  const int status = ::pclose(pipe);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    ADD_FAILURE() << "read_vtu.py failed (status " << status << "): " << output;
    return {};
  }
  return nlohmann::json::parse(output);
}

}  // namespace contactrb::test

#define SKIP_WITHOUT_MESHIO()                \
  if (!contactrb::test::meshio_available()) \
  GTEST_SKIP() << "/usr/bin/python3 with meshio (python3-meshio) missing"
