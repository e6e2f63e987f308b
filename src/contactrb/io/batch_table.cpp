#include "contactrb/io/batch_table.hpp"

#include <bit>
#include <charconv>
#include <cstdint>
#include <limits>

#include "contactrb/common/error.hpp"

namespace contactrb::io {

namespace {

void append_double(std::string& s, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);  // shortest round trip
  s.append(buf, r.ptr);
}

void append_int(std::string& s, long long x) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  s.append(buf, r.ptr);
}

// A CSV field: quoted when it holds a separator, a quote or a line break (RFC 4180).
void append_field(std::string& s, const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) {
    s += text;
    return;
  }
  s += '"';
  for (char c : text) {
    if (c == '"') s += '"';
    s += c;
  }
  s += '"';
}

}  // namespace

CsvBatchWriter::CsvBatchWriter(std::ostream& out, const std::vector<std::string>& names)
    : out_(out), p_(names.size()) {
  std::string h = "line";
  for (const std::string& n : names) {
    h += ',';
    append_field(h, n);
  }
  h += ",status,iterations,energy,contact_force,estimate\n";
  out_ << h;
}

void append_csv_batch_row(std::string& s, const BatchRow& row, std::size_t p) {
  append_int(s, row.line);
  if (!row.answered) {
    s.append(p, ',');
    s += ",error,,,,\n";
    return;
  }
  require(static_cast<std::size_t>(row.mu.size()) == p, "CsvBatchWriter: mu has the wrong size");
  for (Eigen::Index k = 0; k < row.mu.size(); ++k) {
    s += ',';
    append_double(s, row.mu(k));
  }
  s += ',';
  s += row.status_name;
  s += ',';
  append_int(s, row.iterations);
  s += ',';
  append_double(s, row.energy);
  s += ',';
  append_double(s, row.contact_force);
  s += ',';
  if (row.has_estimate) append_double(s, row.estimate);
  s += '\n';
}

void CsvBatchWriter::write(const BatchRow& row) {
  buffer_.clear();
  append_csv_batch_row(buffer_, row, p_);
  out_ << buffer_;
}

void append_npy_batch_row(std::string& s, const BatchRow& row, std::size_t p) {
  static_assert(std::endian::native == std::endian::little, "npy output: '<f8' written from memory");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto put = [&s](double x) { s.append(reinterpret_cast<const char*>(&x), sizeof x); };
  put(row.line);
  if (!row.answered) {
    for (std::size_t k = 0; k < p; ++k) put(nan);
    for (double x : {kBatchErrorStatus, nan, nan, nan, nan}) put(x);
    return;
  }
  require(static_cast<std::size_t>(row.mu.size()) == p, "NpyBatchWriter: mu has the wrong size");
  for (Eigen::Index k = 0; k < row.mu.size(); ++k) put(row.mu(k));
  for (double x : {static_cast<double>(row.status), static_cast<double>(row.iterations), row.energy, row.contact_force,
                   row.has_estimate ? row.estimate : nan}) {
    put(x);
  }
}

void write_npy_batch(std::ostream& out, std::size_t columns, const std::string& data) {
  const std::size_t row_bytes = columns * sizeof(double);
  require(columns > 0 && data.size() % row_bytes == 0, "npy output: the data are not whole rows");
  const std::size_t rows = data.size() / row_bytes;
  std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " +
                     std::to_string(columns) + "), }";
  // Format 1.0: magic (6), version (2), header length (2, little-endian), then the header
  // padded with blanks and ended by '\n' so that the data start at a multiple of 64 bytes.
  const std::size_t unpadded = 10 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict += '\n';
  require(dict.size() <= 65535, "NpyBatchWriter: header too long");
  const auto len = static_cast<std::uint16_t>(dict.size());
  out.write("\x93NUMPY\x01\x00", 8);
  const char len_bytes[2] = {static_cast<char>(len & 0xff), static_cast<char>(len >> 8)};
  out.write(len_bytes, 2);
  out << dict;
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
}

}  // namespace contactrb::io
