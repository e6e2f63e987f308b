#pragma once
// CSV tables (error histories, timing tables, figure data): a header line with the column
// names, then one line per row. Numbers are written round-trip exact; text cells are
// quoted when they hold a comma, a quote or a line break (RFC 4180).
#include <string>
#include <variant>
#include <vector>

namespace contactrb::io {

using CsvCell = std::variant<double, long long, std::string>;

class CsvWriter {
 public:
  // Throws contactrb::Error when `columns` is empty.
  explicit CsvWriter(std::vector<std::string> columns);

  // Throws contactrb::Error when the row does not have one cell per column.
  CsvWriter& add_row(std::vector<CsvCell> row);

  int num_rows() const { return static_cast<int>(rows_.size()); }

  // Writes through a temporary file renamed at the end; throws contactrb::Error naming
  // the path when it cannot be written.
  void write(const std::string& path) const;

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<CsvCell>> rows_;
};

}  // namespace contactrb::io
