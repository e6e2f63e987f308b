#pragma once
// Reading the text and CSV files the commands write, for the CLI tests.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace contactrb::test {

inline std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The cells of one CSV line (no quoting); a trailing comma ends with an empty cell.
inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// A column of number cells as numbers.
inline std::vector<double> numbers(const std::vector<std::string>& cells) {
  std::vector<double> v;
  for (const std::string& c : cells) v.push_back(std::stod(c));
  return v;
}

// A CSV with a header: column name -> cells (a line with another number of cells fails the test).
inline std::map<std::string, std::vector<std::string>> read_csv(const std::string& path) {
  const std::vector<std::string> lines = lines_of(file_text(path));
  std::map<std::string, std::vector<std::string>> out;
  if (lines.empty()) return out;
  const std::vector<std::string> header = split_csv_line(lines[0]);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> cells = split_csv_line(lines[i]);
    EXPECT_EQ(cells.size(), header.size()) << lines[i];
    for (std::size_t c = 0; c < header.size() && c < cells.size(); ++c) out[header[c]].push_back(cells[c]);
  }
  return out;
}

}  // namespace contactrb::test
