#pragma once
// Whole files as bytes, and counting a tool's message lines: for the tests that damage files
// and read what the command says about them.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace contactrb::test {

inline std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void write_bytes(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// Lines of `text` that begin with `prefix` (e.g. "contactrb: error:").
inline int count_lines_starting(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) n += line.rfind(prefix, 0) == 0 ? 1 : 0;
  return n;
}

}  // namespace contactrb::test
