#include "contactrb/io/snapshot_file.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <system_error>
#include <utility>

#include "contactrb/common/error.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/common/version.hpp"
#include "contactrb/io/hdf5_handle.hpp"

namespace contactrb::io {

int SnapshotSet::num_failed() const {
  int n = 0;
  for (const Snapshot& s : snapshots) n += s.converged ? 0 : 1;
  return n;
}

namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

using hdf5::check;
using hdf5::Handle;
using H5Failure = hdf5::Failure;
using QuietHdf5 = hdf5::Quiet;

bool exists(hid_t loc, const std::string& name) {
  // H5Lexists on a path checks one link; our names are single components.
  return H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0;
}

// ---------------------------------------------------------------------------- writing

Handle create_group(hid_t loc, const std::string& name) {
  return {H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
          "cannot create group '" + name + "'"};
}

Handle string_type(std::size_t length) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create a string type");
  check(H5Tset_size(type.get(), length == 0 ? 1 : length), "cannot size a string type");
  check(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "cannot set string padding");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "cannot set string encoding");
  return type;
}

void write_attribute(hid_t loc, const std::string& name, const std::string& value) {
  Handle type = string_type(value.size());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a dataspace");
  Handle attr(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "cannot create attribute '" + name + "'");
  const std::string buffer = value.empty() ? std::string(1, '\0') : value;
  check(H5Awrite(attr.get(), type.get(), buffer.data()), "cannot write attribute '" + name + "'");
}

template <typename T>
void write_attribute_number(hid_t loc, const std::string& name, T value, hid_t file_type, hid_t mem_type) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a dataspace");
  Handle attr(H5Acreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "cannot create attribute '" + name + "'");
  check(H5Awrite(attr.get(), mem_type, &value), "cannot write attribute '" + name + "'");
}
void write_attribute(hid_t loc, const std::string& name, double value) {
  write_attribute_number(loc, name, value, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}
void write_attribute(hid_t loc, const std::string& name, int value) {
  write_attribute_number(loc, name, value, H5T_STD_I32LE, H5T_NATIVE_INT);
}

void write_dataset(hid_t loc, const std::string& name, const void* data, int rank, const hsize_t* dims,
                   hid_t file_type, hid_t mem_type) {
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose, "cannot create the dataspace of '" + name + "'");
  Handle set(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose, "cannot create dataset '" + name + "'");
  check(H5Dwrite(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "cannot write dataset '" + name + "'");
}
void write_vector(hid_t loc, const std::string& name, const Eigen::VectorXd& v) {
  const hsize_t dims[1] = {static_cast<hsize_t>(v.size())};
  write_dataset(loc, name, v.data(), 1, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}
void write_vector(hid_t loc, const std::string& name, const std::vector<int>& v) {
  const hsize_t dims[1] = {static_cast<hsize_t>(v.size())};
  write_dataset(loc, name, v.data(), 1, dims, H5T_STD_I32LE, H5T_NATIVE_INT);
}
void write_matrix(hid_t loc, const std::string& name, const Eigen::MatrixXd& m) {
  const RowMajorMatrix row_major = m;  // HDF5 stores C order
  const hsize_t dims[2] = {static_cast<hsize_t>(m.rows()), static_cast<hsize_t>(m.cols())};
  write_dataset(loc, name, row_major.data(), 2, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}
// Arrays a failed solve may lack are written only when present.
void write_optional(hid_t loc, const std::string& name, const Eigen::VectorXd& v) {
  if (v.size() > 0) write_vector(loc, name, v);
}

std::string snapshot_group_name(std::size_t i) {
  char buffer[24];
  std::snprintf(buffer, sizeof buffer, "%06zu", i);
  return buffer;
}

void check_sizes(const SnapshotSet& set) {
  const auto num_free = static_cast<Eigen::Index>(set.free_dofs.size());
  const auto nc = static_cast<Eigen::Index>(set.contact_dofs.size());
  for (int d : set.free_dofs) require(d >= 0 && d < set.num_dofs, "free DOF index out of range");
  for (int d : set.contact_dofs) require(d >= 0 && d < set.num_dofs, "contact DOF index out of range");
  for (const Snapshot& s : set.snapshots) {
    std::ostringstream where;
    where << "snapshot mu = " << s.mu << ": ";
    const auto R = s.lambda.size();
    require(s.u0.size() == 0 || s.u0.size() == num_free,
            where.str() + "u0 has " + std::to_string(s.u0.size()) + " entries, expected " + std::to_string(num_free));
    require(s.u.size() == 0 || s.u.size() == set.num_dofs,
            where.str() + "u has " + std::to_string(s.u.size()) + " entries, expected " + std::to_string(set.num_dofs));
    require(s.K.size() == 0 || (s.K.rows() == R && s.K.cols() == nc),
            where.str() + "K is " + std::to_string(s.K.rows()) + " x " + std::to_string(s.K.cols()) + ", expected " +
                std::to_string(R) + " x " + std::to_string(nc));
    require(s.g.size() == 0 || s.g.size() == R, where.str() + "g and lambda differ in size");
    require(s.weight.size() == 0 || s.weight.size() == R, where.str() + "weight and lambda differ in size");
    require(s.gap_pointwise.size() == 0 || s.gap_pointwise.size() == static_cast<Eigen::Index>(set.slave.size()),
            where.str() + "gap_pointwise and the slave chain differ in size");
    require(!s.converged || (s.u0.size() > 0 && s.u.size() > 0 && s.g.size() == R && s.weight.size() == R),
            where.str() + "a converged snapshot needs u0, u, lambda, K, g and weight");
  }
}

void write_contents(hid_t file, const SnapshotSet& set) {
  write_attribute(file, "format", std::string(kSnapshotFormatName));
  write_attribute(file, "format_version", kSnapshotFormatVersion);
  write_attribute(file, "contactrb_version", std::string(kVersion));
  {
    Handle g = create_group(file, "case");
    write_attribute(g.get(), "name", set.case_name);
    write_attribute(g.get(), "kind", set.case_kind);
    write_attribute(g.get(), "spec", set.case_spec);
    write_attribute(g.get(), "level", set.level);
    write_attribute(g.get(), "constraint", set.constraint);
  }
  {
    Handle g = create_group(file, "parameter");
    write_attribute(g.get(), "name", set.parameter_name);
    write_attribute(g.get(), "min", set.parameter_min);
    write_attribute(g.get(), "max", set.parameter_max);
    write_attribute(g.get(), "set", set.set_name);
    Eigen::VectorXd mu(static_cast<Eigen::Index>(set.snapshots.size()));
    for (std::size_t i = 0; i < set.snapshots.size(); ++i) mu(static_cast<Eigen::Index>(i)) = set.snapshots[i].mu;
    write_vector(g.get(), "values", mu);
  }
  {
    Handle g = create_group(file, "settings");
    write_attribute(g.get(), "kacanov_alpha", set.kacanov_alpha);
    write_attribute(g.get(), "kacanov_tolerance", set.kacanov_tolerance);
    write_attribute(g.get(), "kacanov_max_iterations", set.kacanov_max_iterations);
  }
  {
    Handle g = create_group(file, "discretization");
    write_attribute(g.get(), "num_dofs", set.num_dofs);
    write_vector(g.get(), "free_dofs", set.free_dofs);
    write_vector(g.get(), "contact_dofs", set.contact_dofs);
    write_vector(g.get(), "slave", set.slave);
    write_vector(g.get(), "master", set.master);
  }
  Handle snaps = create_group(file, "snapshots");
  const std::size_t n = set.snapshots.size();
  write_attribute(snaps.get(), "count", static_cast<int>(n));
  std::vector<int> converged(n), iterations(n);
  Eigen::VectorXd time(static_cast<Eigen::Index>(n)), cpu_time(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const Snapshot& s = set.snapshots[i];
    converged[i] = s.converged ? 1 : 0;
    iterations[i] = s.iterations;
    time(static_cast<Eigen::Index>(i)) = s.time_s;
    cpu_time(static_cast<Eigen::Index>(i)) = s.cpu_time_s;
    Handle g = create_group(snaps.get(), snapshot_group_name(i));
    write_attribute(g.get(), "mu", s.mu);
    write_attribute(g.get(), "status", s.status);
    write_attribute(g.get(), "message", s.message);
    write_optional(g.get(), "u0", s.u0);
    write_optional(g.get(), "u", s.u);
    write_optional(g.get(), "lambda", s.lambda);
    if (s.K.size() > 0) write_matrix(g.get(), "K", s.K);
    write_optional(g.get(), "g", s.g);
    write_optional(g.get(), "weight", s.weight);
    write_optional(g.get(), "gap_pointwise", s.gap_pointwise);
  }
  write_vector(snaps.get(), "converged", converged);
  write_vector(snaps.get(), "iterations", iterations);
  write_vector(snaps.get(), "time_s", time);
  write_vector(snaps.get(), "cpu_time_s", cpu_time);
}

// ---------------------------------------------------------------------------- reading

Handle open_group(hid_t loc, const std::string& name) {
  if (!exists(loc, name)) throw H5Failure{"missing group '" + name + "'"};
  return {H5Gopen2(loc, name.c_str(), H5P_DEFAULT), H5Gclose, "cannot open group '" + name + "'"};
}

Handle open_attribute(hid_t loc, const std::string& name) {
  if (H5Aexists(loc, name.c_str()) <= 0) throw H5Failure{"missing attribute '" + name + "'"};
  return {H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose, "cannot open attribute '" + name + "'"};
}

std::string read_string_attribute(hid_t loc, const std::string& name) {
  Handle attr = open_attribute(loc, name);
  Handle type(H5Aget_type(attr.get()), H5Tclose, "cannot read the type of attribute '" + name + "'");
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) {
    throw H5Failure{"attribute '" + name + "' is not a fixed-length string"};
  }
  // Read with the stored type itself: any padding and character set, no conversion.
  const std::size_t size = H5Tget_size(type.get());
  std::string value(size, '\0');
  check(H5Aread(attr.get(), type.get(), value.data()), "cannot read attribute '" + name + "'");
  value.resize(value.find_last_not_of('\0') == std::string::npos ? 0 : value.find_last_not_of('\0') + 1);
  return value;
}

template <typename T>
T read_number_attribute(hid_t loc, const std::string& name, hid_t mem_type, H5T_class_t expected) {
  Handle attr = open_attribute(loc, name);
  Handle type(H5Aget_type(attr.get()), H5Tclose, "cannot read the type of attribute '" + name + "'");
  if (H5Tget_class(type.get()) != expected) throw H5Failure{"attribute '" + name + "' has the wrong type"};
  T value{};
  check(H5Aread(attr.get(), mem_type, &value), "cannot read attribute '" + name + "'");
  return value;
}
double read_double_attribute(hid_t loc, const std::string& name) {
  return read_number_attribute<double>(loc, name, H5T_NATIVE_DOUBLE, H5T_FLOAT);
}
int read_int_attribute(hid_t loc, const std::string& name) {
  return read_number_attribute<int>(loc, name, H5T_NATIVE_INT, H5T_INTEGER);
}

// Opens dataset `name`, checks its rank and type class, returns its dimensions.
Handle open_dataset(hid_t loc, const std::string& name, int rank, H5T_class_t expected, hsize_t* dims) {
  if (!exists(loc, name)) throw H5Failure{"missing dataset '" + name + "'"};
  Handle set(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose, "cannot open dataset '" + name + "'");
  Handle space(H5Dget_space(set.get()), H5Sclose, "cannot read the shape of dataset '" + name + "'");
  if (H5Sget_simple_extent_ndims(space.get()) != rank) {
    throw H5Failure{"dataset '" + name + "' has rank " + std::to_string(H5Sget_simple_extent_ndims(space.get())) +
                    ", expected " + std::to_string(rank)};
  }
  check(H5Sget_simple_extent_dims(space.get(), dims, nullptr), "cannot read the shape of dataset '" + name + "'");
  Handle type(H5Dget_type(set.get()), H5Tclose, "cannot read the type of dataset '" + name + "'");
  if (H5Tget_class(type.get()) != expected) throw H5Failure{"dataset '" + name + "' has the wrong type"};
  // Before the caller allocates dims' worth of memory (4 bytes: the smallest element we read).
  hdf5::checked_element_count(set.get(), dims, rank, 4, name);
  return set;
}

Eigen::VectorXd read_vector(hid_t loc, const std::string& name) {
  hsize_t dims[1] = {0};
  Handle set = open_dataset(loc, name, 1, H5T_FLOAT, dims);
  Eigen::VectorXd v(static_cast<Eigen::Index>(dims[0]));
  if (v.size() > 0) {
    check(H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
          "cannot read dataset '" + name + "'");
  }
  return v;
}
std::vector<int> read_int_vector(hid_t loc, const std::string& name) {
  hsize_t dims[1] = {0};
  Handle set = open_dataset(loc, name, 1, H5T_INTEGER, dims);
  std::vector<int> v(static_cast<std::size_t>(dims[0]));
  if (!v.empty()) {
    check(H5Dread(set.get(), H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
          "cannot read dataset '" + name + "'");
  }
  return v;
}
Eigen::MatrixXd read_matrix(hid_t loc, const std::string& name) {
  hsize_t dims[2] = {0, 0};
  Handle set = open_dataset(loc, name, 2, H5T_FLOAT, dims);
  RowMajorMatrix m(static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]));
  if (m.size() > 0) {
    check(H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.data()),
          "cannot read dataset '" + name + "'");
  }
  return m;
}
Eigen::VectorXd read_optional(hid_t loc, const std::string& name) {
  return exists(loc, name) ? read_vector(loc, name) : Eigen::VectorXd();
}

// Checked on reading: array sizes against the discretization. A failed snapshot may lack
// arrays; a converged one has them all.
void check_snapshot(const SnapshotSet& set, const Snapshot& s, const std::string& group) {
  const auto R = s.lambda.size();
  const auto expect = [&](bool ok, const std::string& what) {
    if (!ok) throw H5Failure{"snapshot '" + group + "': " + what};
  };
  if (s.converged) {
    expect(s.u0.size() == static_cast<Eigen::Index>(set.free_dofs.size()) && s.u.size() == set.num_dofs &&
               s.g.size() == R && s.weight.size() == R,
           "a converged snapshot lacks u0, u, g or weight");
  }
  expect(s.u0.size() == 0 || s.u0.size() == static_cast<Eigen::Index>(set.free_dofs.size()), "u0 has the wrong size");
  expect(s.u.size() == 0 || s.u.size() == set.num_dofs, "u has the wrong size");
  expect(s.K.size() == 0 || (s.K.rows() == R && s.K.cols() == static_cast<Eigen::Index>(set.contact_dofs.size())),
         "K has the wrong shape");
  expect(s.g.size() == 0 || s.g.size() == R, "g has the wrong size");
  expect(s.weight.size() == 0 || s.weight.size() == R, "weight has the wrong size");
  expect(s.gap_pointwise.size() == 0 || s.gap_pointwise.size() == static_cast<Eigen::Index>(set.slave.size()),
         "gap_pointwise has the wrong size");
}

SnapshotSet read_contents(hid_t file) {
  SnapshotSet set;
  {
    Handle g = open_group(file, "case");
    set.case_name = read_string_attribute(g.get(), "name");
    set.case_kind = read_string_attribute(g.get(), "kind");
    set.case_spec = read_string_attribute(g.get(), "spec");
    set.level = read_int_attribute(g.get(), "level");
    set.constraint = read_string_attribute(g.get(), "constraint");
  }
  Eigen::VectorXd mu;
  {
    Handle g = open_group(file, "parameter");
    set.parameter_name = read_string_attribute(g.get(), "name");
    set.parameter_min = read_double_attribute(g.get(), "min");
    set.parameter_max = read_double_attribute(g.get(), "max");
    set.set_name = read_string_attribute(g.get(), "set");
    mu = read_vector(g.get(), "values");
  }
  {
    Handle g = open_group(file, "settings");
    set.kacanov_alpha = read_double_attribute(g.get(), "kacanov_alpha");
    set.kacanov_tolerance = read_double_attribute(g.get(), "kacanov_tolerance");
    set.kacanov_max_iterations = read_int_attribute(g.get(), "kacanov_max_iterations");
  }
  {
    Handle g = open_group(file, "discretization");
    set.num_dofs = read_int_attribute(g.get(), "num_dofs");
    set.free_dofs = read_int_vector(g.get(), "free_dofs");
    set.contact_dofs = read_int_vector(g.get(), "contact_dofs");
    set.slave = read_int_vector(g.get(), "slave");
    set.master = read_int_vector(g.get(), "master");
  }
  Handle snaps = open_group(file, "snapshots");
  const int count = read_int_attribute(snaps.get(), "count");
  const std::vector<int> converged = read_int_vector(snaps.get(), "converged");
  const std::vector<int> iterations = read_int_vector(snaps.get(), "iterations");
  const Eigen::VectorXd time = read_vector(snaps.get(), "time_s");
  const Eigen::VectorXd cpu_time = read_vector(snaps.get(), "cpu_time_s");
  const auto n = static_cast<std::size_t>(count);
  if (count < 0 || mu.size() != count || converged.size() != n || iterations.size() != n ||
      time.size() != count || cpu_time.size() != count) {
    throw H5Failure{"the snapshot count " + std::to_string(count) + " disagrees with /parameter/values (" +
                    std::to_string(mu.size()) + ") or the per-snapshot tables"};
  }
  set.snapshots.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Snapshot& s = set.snapshots[i];
    const std::string name = snapshot_group_name(i);
    Handle g = open_group(snaps.get(), name);
    s.mu = read_double_attribute(g.get(), "mu");
    s.status = read_string_attribute(g.get(), "status");
    s.message = read_string_attribute(g.get(), "message");
    s.converged = converged[i] != 0;
    s.iterations = iterations[i];
    s.time_s = time(static_cast<Eigen::Index>(i));
    s.cpu_time_s = cpu_time(static_cast<Eigen::Index>(i));
    if (s.converged) {
      s.u0 = read_vector(g.get(), "u0");
      s.u = read_vector(g.get(), "u");
      s.lambda = read_vector(g.get(), "lambda");
      s.K = read_matrix(g.get(), "K");
      s.g = read_vector(g.get(), "g");
      s.weight = read_vector(g.get(), "weight");
      s.gap_pointwise = read_vector(g.get(), "gap_pointwise");
    } else {
      s.u0 = read_optional(g.get(), "u0");
      s.u = read_optional(g.get(), "u");
      s.lambda = read_optional(g.get(), "lambda");
      if (exists(g.get(), "K")) s.K = read_matrix(g.get(), "K");
      s.g = read_optional(g.get(), "g");
      s.weight = read_optional(g.get(), "weight");
      s.gap_pointwise = read_optional(g.get(), "gap_pointwise");
    }
    check_snapshot(set, s, "/snapshots/" + name);
  }
  return set;
}

// A new temporary file next to the target (common/output_file.hpp); temporaries of killed
// writers are removed first.
std::string temporary_name(const std::string& path) {
  check_output_target(path);
  remove_stale_temporaries(path);
  return temporary_path(path).string();
}

}  // namespace

void write_snapshot_file(const SnapshotSet& set, const std::string& path) {
  try {
    check_sizes(set);
  } catch (const Error& e) {
    throw Error("cannot write snapshot file '" + path + "': " + e.what());
  }
  const QuietHdf5 quiet;
  const std::string tmp = temporary_name(path);
  try {
    Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                "cannot create the file (is the directory there and writable?)");
    write_contents(file.get(), set);
    // Written last: a file without it is an interrupted write.
    write_attribute(file.get(), "complete", 1);
    file.close("cannot flush and close the file");
  } catch (const H5Failure& f) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw Error("cannot write snapshot file '" + path + "': " + f.what);
  }
  try {
    commit_temporary(tmp, path);
  } catch (const Error& e) {
    throw Error("cannot write snapshot file '" + path + "': " + e.what());
  }
}

SnapshotSet read_snapshot_file(const std::string& path) {
  const std::string name = "snapshot file '" + path + "'";
  check_input_file(path, "snapshot file", InputKind::Hdf5);  // a regular file below the size limit
  const QuietHdf5 quiet;
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  if (is_hdf5 == 0) throw Error(name + " is not an HDF5 file (expected a file written by `contactrb snapshots`)");
  if (is_hdf5 < 0) throw Error(name + " cannot be read (" + hdf5::reason() + ")");
  try {
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create file access properties");
    check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "cannot set the close degree");
    Handle file;
    try {
      file = Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose, "HDF5 cannot open it");
    } catch (const H5Failure& f) {
      throw Error(name + " is truncated or damaged: " + f.what);
    }
    if (H5Aexists(file.get(), "format") <= 0) {
      throw Error(name + " is an HDF5 file but not a contactrb snapshot file (no 'format' attribute)");
    }
    std::string format;
    try {
      format = read_string_attribute(file.get(), "format");
    } catch (const H5Failure&) {
      format = "(unreadable)";
    }
    if (format != kSnapshotFormatName) {
      throw Error(name + " is an HDF5 file of another format ('" + format + "', expected '" + kSnapshotFormatName + "')");
    }
    int version = -1;
    try {
      version = read_int_attribute(file.get(), "format_version");
    } catch (const H5Failure& f) {
      throw Error(name + " has no valid format version: " + f.what);
    }
    if (version != kSnapshotFormatVersion) {
      throw Error(name + " has snapshot format version " + std::to_string(version) + "; this contactrb reads version " +
                  std::to_string(kSnapshotFormatVersion));
    }
    if (H5Aexists(file.get(), "complete") <= 0 || read_int_attribute(file.get(), "complete") != 1) {
      throw Error(name + " is incomplete (the run that wrote it was interrupted): generate it again");
    }
    try {
      return read_contents(file.get());
    } catch (const H5Failure& f) {
      throw Error(name + " is truncated or damaged: " + f.what);
    }
  } catch (const H5Failure& f) {
    throw Error(name + ": " + f.what);
  }
}

}  // namespace contactrb::io
