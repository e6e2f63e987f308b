#pragma once
// Two visitors with one interface, so that a file's layout is written once (a template
// `visit(V&, ...)`) and read back by the same code: FieldWriter writes each field (from a const
// reference too, so a layout templated on the record's constness writes without a copy),
// FieldReader reads it into the same reference. Both add every field to a FieldChecksum under its path
// ("/meta/case_name", "/primal/A_hat"), kind and shape; the descriptive attributes
// (description, shape_meaning, units) are not fields. Layout rules: hdf5_fields.hpp.
// Internal to io/: include only from io/*.cpp.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "contactrb/io/field_checksum.hpp"
#include "contactrb/io/hdf5_fields.hpp"

namespace contactrb::io::hdf5 {

// A group (or the root) and its path, the prefix of its fields' checksum names.
struct Loc {
  hid_t id;
  std::string path;  // "" for the root, "/meta", "/eim/kappa", ...
  std::string field(const std::string& name) const { return path + "/" + name; }
};

// Lists longer than this are taken for a damaged count.
inline constexpr hsize_t kMaxListLength = 1000000;

namespace field_kind {
inline constexpr char kString = 's';
inline constexpr char kDouble = 'd';
inline constexpr char kInt = 'i';
}  // namespace field_kind

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class FieldWriter {
 public:
  static constexpr bool kWriting = true;
  explicit FieldWriter(FieldChecksum& sum) : sum_(sum) {}

  Handle group(const Loc& parent, const std::string& name, const std::string& description) {
    return create_group(parent.id, name, description);
  }
  void str(const Loc& loc, const std::string& name, const std::string& s) {
    write_string_attribute(loc.id, name, s);
    sum_.add(loc.field(name), field_kind::kString, {s.size()}, s.data(), s.size());
  }
  void num(const Loc& loc, const std::string& name, const double& v) {
    write_number_attribute(loc.id, name, v, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
    sum_.add(loc.field(name), field_kind::kDouble, {1}, &v, sizeof v);
  }
  void integer(const Loc& loc, const std::string& name, const int& v) {
    write_number_attribute(loc.id, name, v, H5T_STD_I32LE, H5T_NATIVE_INT);
    sum_.add(loc.field(name), field_kind::kInt, {1}, &v, sizeof v);
  }
  void flag(const Loc& loc, const std::string& name, const bool& b) {
    int i = b ? 1 : 0;
    integer(loc, name, i);
  }
  // rank 1 (cols == 0) or rows x cols (cols > 0, data.size() a multiple of cols), C order.
  void ints(const Loc& loc, const std::string& name, const std::vector<int>& v, const Description& d, hsize_t cols = 0) {
    if (cols > 0 && v.size() % cols != 0) throw Failure{"'" + loc.field(name) + "' is not a table of " + std::to_string(cols) + " columns"};
    const hsize_t dims[2] = {cols > 0 ? v.size() / cols : v.size(), cols};
    write_dataset(loc.id, name, v.data(), cols > 0 ? 2 : 1, dims, H5T_STD_I32LE, H5T_NATIVE_INT, d);
    add_ints(loc.field(name), dims, cols > 0 ? 2 : 1, v);
  }
  void vec(const Loc& loc, const std::string& name, const Eigen::VectorXd& v, const Description& d) {
    const hsize_t dims[1] = {static_cast<hsize_t>(v.size())};
    write_dataset(loc.id, name, v.data(), 1, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, d);
    sum_.add(loc.field(name), field_kind::kDouble, {dims[0]}, v.data(), bytes(v.size()));
  }
  void dvec(const Loc& loc, const std::string& name, const std::vector<double>& v, const Description& d) {
    const hsize_t dims[1] = {v.size()};
    write_dataset(loc.id, name, v.data(), 1, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, d);
    sum_.add(loc.field(name), field_kind::kDouble, {dims[0]}, v.data(), bytes(static_cast<Eigen::Index>(v.size())));
  }
  // rows x cols, as documented (C order: the HDF5 shape is the matrix's shape).
  void mat(const Loc& loc, const std::string& name, const Eigen::MatrixXd& m, const Description& d) {
    const RowMajor r = m;
    const hsize_t dims[2] = {static_cast<hsize_t>(m.rows()), static_cast<hsize_t>(m.cols())};
    write_dataset(loc.id, name, r.data(), 2, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, d);
    sum_.add(loc.field(name), field_kind::kDouble, {dims[0], dims[1]}, r.data(), bytes(r.size()));
  }
  // K matrices of one size as a K x rows x cols array (an empty list: 0 x 0 x 0).
  void stack(const Loc& loc, const std::string& name, const std::vector<Eigen::MatrixXd>& list, const Description& d) {
    const Eigen::Index rows = list.empty() ? 0 : list.front().rows(), cols = list.empty() ? 0 : list.front().cols();
    std::vector<double> data;
    data.reserve(list.size() * static_cast<std::size_t>(rows * cols));
    for (const Eigen::MatrixXd& m : list) {
      if (m.rows() != rows || m.cols() != cols) throw Failure{"the matrices of '" + loc.field(name) + "' differ in size"};
      const RowMajor r = m;
      data.insert(data.end(), r.data(), r.data() + r.size());
    }
    const hsize_t dims[3] = {list.size(), static_cast<hsize_t>(rows), static_cast<hsize_t>(cols)};
    write_dataset(loc.id, name, data.data(), 3, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, d);
    sum_.add(loc.field(name), field_kind::kDouble, {dims[0], dims[1], dims[2]}, data.data(),
             data.size() * sizeof(double));
  }
  // K vectors of one size as a K x n array (row k is vector k).
  void rows(const Loc& loc, const std::string& name, const std::vector<Eigen::VectorXd>& list, const Description& d) {
    const Eigen::Index n = list.empty() ? 0 : list.front().size();
    std::vector<double> data;
    data.reserve(list.size() * static_cast<std::size_t>(n));
    for (const Eigen::VectorXd& v : list) {
      if (v.size() != n) throw Failure{"the vectors of '" + loc.field(name) + "' differ in size"};
      data.insert(data.end(), v.data(), v.data() + v.size());
    }
    const hsize_t dims[2] = {list.size(), static_cast<hsize_t>(n)};
    write_dataset(loc.id, name, data.data(), 2, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, d);
    sum_.add(loc.field(name), field_kind::kDouble, {dims[0], dims[1]}, data.data(), data.size() * sizeof(double));
  }

  // A dataset a record may lack (an array a failed solve did not produce): written when not
  // empty. `required` is the reader's (FieldReader::optional).
  void optional(const Loc& loc, const std::string& name, const Eigen::VectorXd& v, const Description& d, bool) {
    if (v.size() > 0) vec(loc, name, v, d);
  }
  void optional(const Loc& loc, const std::string& name, const Eigen::MatrixXd& m, const Description& d, bool) {
    if (m.size() > 0) mat(loc, name, m, d);
  }

 private:
  static std::size_t bytes(Eigen::Index n) { return static_cast<std::size_t>(n) * sizeof(double); }
  void add_ints(const std::string& field, const hsize_t* dims, int rank, const std::vector<int>& v) {
    if (rank == 1) {
      sum_.add(field, field_kind::kInt, {dims[0]}, v.data(), v.size() * sizeof(int));
    } else {
      sum_.add(field, field_kind::kInt, {dims[0], dims[1]}, v.data(), v.size() * sizeof(int));
    }
  }
  FieldChecksum& sum_;
};

class FieldReader {
 public:
  static constexpr bool kWriting = false;
  explicit FieldReader(FieldChecksum& sum) : sum_(sum) {}

  Handle group(const Loc& parent, const std::string& name, const std::string&) { return open_group(parent.id, name); }
  void str(const Loc& loc, const std::string& name, std::string& s) {
    s = read_string_attribute(loc.id, name);
    sum_.add(loc.field(name), field_kind::kString, {s.size()}, s.data(), s.size());
  }
  void num(const Loc& loc, const std::string& name, double& v) {
    v = read_number_attribute<double>(loc.id, name, H5T_NATIVE_DOUBLE, H5T_FLOAT);
    sum_.add(loc.field(name), field_kind::kDouble, {1}, &v, sizeof v);
  }
  void integer(const Loc& loc, const std::string& name, int& v) {
    v = read_number_attribute<int>(loc.id, name, H5T_NATIVE_INT, H5T_INTEGER);
    sum_.add(loc.field(name), field_kind::kInt, {1}, &v, sizeof v);
  }
  void flag(const Loc& loc, const std::string& name, bool& b) {
    int i = 0;
    integer(loc, name, i);
    if (i != 0 && i != 1) throw Failure{"'" + loc.field(name) + "' is " + std::to_string(i) + " (expected 0 or 1)"};
    b = i == 1;
  }
  void ints(const Loc& loc, const std::string& name, std::vector<int>& v, const Description&, hsize_t cols = 0) {
    const int rank = cols > 0 ? 2 : 1;
    hsize_t dims[2] = {0, 0};
    Handle set = open_dataset(loc.id, name, rank, H5T_INTEGER, dims, sizeof(int));
    if (cols > 0 && dims[1] != cols) {
      throw Failure{"dataset '" + loc.field(name) + "' has " + std::to_string(dims[1]) + " columns, expected " +
                    std::to_string(cols)};
    }
    v.assign(static_cast<std::size_t>(dims[0] * (cols > 0 ? cols : 1)), 0);
    read(set.get(), H5T_NATIVE_INT, v.data(), v.size(), loc.field(name));
    if (rank == 1) {
      sum_.add(loc.field(name), field_kind::kInt, {dims[0]}, v.data(), v.size() * sizeof(int));
    } else {
      sum_.add(loc.field(name), field_kind::kInt, {dims[0], dims[1]}, v.data(), v.size() * sizeof(int));
    }
  }
  void vec(const Loc& loc, const std::string& name, Eigen::VectorXd& v, const Description&) {
    hsize_t dims[1] = {0};
    Handle set = open_dataset(loc.id, name, 1, H5T_FLOAT, dims, sizeof(double));
    v.resize(static_cast<Eigen::Index>(dims[0]));
    read(set.get(), H5T_NATIVE_DOUBLE, v.data(), static_cast<std::size_t>(v.size()), loc.field(name));
    sum_.add(loc.field(name), field_kind::kDouble, {dims[0]}, v.data(), static_cast<std::size_t>(v.size()) * sizeof(double));
  }
  void dvec(const Loc& loc, const std::string& name, std::vector<double>& v, const Description& d) {
    Eigen::VectorXd x;
    vec(loc, name, x, d);
    v.assign(x.data(), x.data() + x.size());
  }
  void mat(const Loc& loc, const std::string& name, Eigen::MatrixXd& m, const Description&) {
    hsize_t dims[2] = {0, 0};
    Handle set = open_dataset(loc.id, name, 2, H5T_FLOAT, dims, sizeof(double));
    RowMajor r(static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]));
    read(set.get(), H5T_NATIVE_DOUBLE, r.data(), static_cast<std::size_t>(r.size()), loc.field(name));
    sum_.add(loc.field(name), field_kind::kDouble, {dims[0], dims[1]}, r.data(), static_cast<std::size_t>(r.size()) * sizeof(double));
    m = r;
  }
  void stack(const Loc& loc, const std::string& name, std::vector<Eigen::MatrixXd>& list, const Description&) {
    hsize_t dims[3] = {0, 0, 0};
    Handle set = open_dataset(loc.id, name, 3, H5T_FLOAT, dims, sizeof(double));
    if (dims[0] > kMaxListLength) throw Failure{"dataset '" + loc.field(name) + "' declares too many matrices"};
    std::vector<double> data(static_cast<std::size_t>(dims[0] * dims[1] * dims[2]));
    read(set.get(), H5T_NATIVE_DOUBLE, data.data(), data.size(), loc.field(name));
    sum_.add(loc.field(name), field_kind::kDouble, {dims[0], dims[1], dims[2]}, data.data(), data.size() * sizeof(double));
    const auto r = static_cast<Eigen::Index>(dims[1]), c = static_cast<Eigen::Index>(dims[2]);
    list.assign(static_cast<std::size_t>(dims[0]), Eigen::MatrixXd());
    for (std::size_t k = 0; k < list.size(); ++k) {
      list[k] = Eigen::Map<const RowMajor>(data.data() + k * static_cast<std::size_t>(r * c), r, c);
    }
  }
  void rows(const Loc& loc, const std::string& name, std::vector<Eigen::VectorXd>& list, const Description&) {
    hsize_t dims[2] = {0, 0};
    Handle set = open_dataset(loc.id, name, 2, H5T_FLOAT, dims, sizeof(double));
    if (dims[0] > kMaxListLength) throw Failure{"dataset '" + loc.field(name) + "' declares too many vectors"};
    std::vector<double> data(static_cast<std::size_t>(dims[0] * dims[1]));
    read(set.get(), H5T_NATIVE_DOUBLE, data.data(), data.size(), loc.field(name));
    sum_.add(loc.field(name), field_kind::kDouble, {dims[0], dims[1]}, data.data(), data.size() * sizeof(double));
    const auto n = static_cast<Eigen::Index>(dims[1]);
    list.assign(static_cast<std::size_t>(dims[0]), Eigen::VectorXd());
    for (std::size_t k = 0; k < list.size(); ++k) {
      list[k] = Eigen::Map<const Eigen::VectorXd>(data.data() + k * static_cast<std::size_t>(n), n);
    }
  }

  // Read when `required` or present; an absent one is left empty.
  void optional(const Loc& loc, const std::string& name, Eigen::VectorXd& v, const Description& d, bool required) {
    if (required || exists(loc, name)) {
      vec(loc, name, v, d);
    } else {
      v.resize(0);
    }
  }
  void optional(const Loc& loc, const std::string& name, Eigen::MatrixXd& m, const Description& d, bool required) {
    if (required || exists(loc, name)) {
      mat(loc, name, m, d);
    } else {
      m.resize(0, 0);
    }
  }
  // True when `loc` has a link `name` (a dataset a record may lack).
  static bool has(const Loc& loc, const std::string& name) { return exists(loc, name); }

 private:
  static bool exists(const Loc& loc, const std::string& name) {
    return H5Lexists(loc.id, name.c_str(), H5P_DEFAULT) > 0;  // one link: our names are single components
  }
  static void read(hid_t set, hid_t mem_type, void* data, std::size_t count, const std::string& name) {
    if (count > 0) {
      check(H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
            "cannot read dataset '" + name + "' (truncated or damaged)");
    }
  }
  FieldChecksum& sum_;
};

}  // namespace contactrb::io::hdf5
