#include "contactrb/io/csv_writer.hpp"

#include <array>
#include <charconv>
#include <ostream>

#include "contactrb/common/error.hpp"
#include "contactrb/io/atomic_file.hpp"

namespace contactrb::io {

namespace {

void put_text(std::ostream& out, const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) {
    out << s;
    return;
  }
  out << '"';
  for (char c : s) {
    if (c == '"') out << '"';
    out << c;
  }
  out << '"';
}

void put_cell(std::ostream& out, const CsvCell& cell) {
  if (const auto* d = std::get_if<double>(&cell)) {
    std::array<char, 32> buf{};
    const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), *d);
    out.write(buf.data(), result.ptr - buf.data());
  } else if (const auto* i = std::get_if<long long>(&cell)) {
    out << *i;
  } else {
    put_text(out, std::get<std::string>(cell));
  }
}

}  // namespace

CsvWriter::CsvWriter(std::vector<std::string> columns) : columns_(std::move(columns)) {
  require(!columns_.empty(), "a CSV table needs at least one column");
}

CsvWriter& CsvWriter::add_row(std::vector<CsvCell> row) {
  require(row.size() == columns_.size(), "CSV row " + std::to_string(rows_.size()) + " has " +
                                             std::to_string(row.size()) + " cells, expected " +
                                             std::to_string(columns_.size()) + " (one per column)");
  rows_.push_back(std::move(row));
  return *this;
}

void CsvWriter::write(const std::string& path) const {
  write_file_atomically(path, [&](std::ostream& out) {
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (c > 0) out << ',';
      put_text(out, columns_[c]);
    }
    out << '\n';
    for (const auto& row : rows_) {
      for (std::size_t c = 0; c < row.size(); ++c) {
        if (c > 0) out << ',';
        put_cell(out, row[c]);
      }
      out << '\n';
    }
  });
}

}  // namespace contactrb::io
