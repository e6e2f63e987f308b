#pragma once
// A JSON file written by a command (solution.json, greedy.json, ...), parsed.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace contactrb::test {

inline nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

}  // namespace contactrb::test
