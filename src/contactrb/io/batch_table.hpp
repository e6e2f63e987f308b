#pragma once
// The compact outputs of `contactrb online --batch --format csv|npy` (docs/file-formats.md,
// "Batch input and output"): one row per batch line, the numbers of the JSON line and nothing else.
//   columns: line, mu_1 .. mu_p, status, iterations, energy, contact_force, estimate
// CSV: a header line (the parameter names as mu columns), then one line per row; every double
// with the shortest text that reads back as the same double (std::to_chars), so the numbers
// equal the JSON's bit for bit; status as its name ("converged", ..., "error" for a line that
// could not be answered), empty fields where the JSON has none (error, no estimate).
// npy (NumPy format 1.0, little-endian float64, C order, shape (rows, p + 6)): status as its
// code (batch_status_code), NaN where the JSON has none. The row count is in the header, so
// the rows are kept in memory and written by finish().
#include <Eigen/Core>
#include <ostream>
#include <string>
#include <vector>

namespace contactrb::io {

// One answered (or refused) batch line.
struct BatchRow {
  int line = 0;
  bool answered = false;       // false: a bad line (mu and the numbers are not written)
  Eigen::VectorXd mu;          // p values (answered)
  int status = 0;              // the solver's status code (answered): 0 converged
  const char* status_name = "";
  int iterations = 0;
  double energy = 0.0;
  double contact_force = 0.0;
  bool has_estimate = false;
  double estimate = 0.0;       // the energy-norm error estimate (has_estimate)
};

// The status column of npy: the solver's code, or this for a line that could not be answered.
inline constexpr double kBatchErrorStatus = -1.0;

// Appends the CSV line of `row` (with its '\n') for p parameters (CsvBatchWriter::write's text).
void append_csv_batch_row(std::string& s, const BatchRow& row, std::size_t p);

class CsvBatchWriter {
 public:
  // Writes the header line to `out` (kept by reference).
  CsvBatchWriter(std::ostream& out, const std::vector<std::string>& parameter_names);
  void write(const BatchRow& row);

 private:
  std::ostream& out_;
  std::size_t p_;
  std::string buffer_;
};

// The npy columns for p parameters: line, mu_1 .. mu_p, status, iterations, energy,
// contact_force, estimate.
constexpr std::size_t npy_batch_columns(std::size_t p) { return p + 6; }

// Appends the npy row of `row` for p parameters: p + 6 float64 values, their bytes as in memory
// (NpyBatchWriter::write's data; rows formatted apart, e.g. on threads, then joined in order).
void append_npy_batch_row(std::string& s, const BatchRow& row, std::size_t p);

// The .npy file of rows made by append_npy_batch_row (`rows`: their bytes, in order), `columns`
// values each, to `out`. Throws contactrb::Error when the bytes are not whole rows.
void write_npy_batch(std::ostream& out, std::size_t columns, const std::string& rows);

class NpyBatchWriter {
 public:
  explicit NpyBatchWriter(std::size_t num_parameters) : p_(num_parameters) {}
  void write(const BatchRow& row) { append_npy_batch_row(data_, row, p_); }
  // The whole .npy file (header and rows) to `out`.
  void finish(std::ostream& out) const { write_npy_batch(out, columns(), data_); }
  std::size_t columns() const { return npy_batch_columns(p_); }

 private:
  std::size_t p_;
  std::string data_;  // the rows' bytes
};

}  // namespace contactrb::io
