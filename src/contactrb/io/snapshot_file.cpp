#include "contactrb/io/snapshot_file.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <system_error>
#include <utility>

#include "contactrb/common/error.hpp"
#include "contactrb/common/file_seal.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/common/version.hpp"
#include "contactrb/io/field_checksum.hpp"
#include "contactrb/io/hdf5_handle.hpp"
#include "contactrb/io/hdf5_visitor.hpp"
#include "contactrb/io/mesh_group.hpp"
#include "contactrb/io/reduced_model_file.hpp"

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

// Field kinds of the checksum (FieldChecksum::add).
constexpr char kString = 's';
// More parameters than this is taken for a damaged count (a design study has 3 to 10).
constexpr int kMaxParameters = 1000;
constexpr char kDouble = 'd';
constexpr char kInt = 'i';

// A group (or the root) and its path ("" for the root, "/case", "/snapshots/000003", ...), the
// prefix of the checksum names of its fields.
using hdf5::Loc;
using hdf5::Description;

// ---------------------------------------------------------------------------- writing

class FileWriter {
 public:
  Handle create_group(const Loc& loc, const std::string& name, const std::string& description) {
    return hdf5::create_group(loc.id, name, description);
  }

  // Strings: variable-length UTF-8 (h5py reads them as str).
  void attribute(const Loc& loc, const std::string& name, const std::string& value) {
    hdf5::write_string_attribute(loc.id, name, value);
    sum_.add(loc.field(name), kString, {value.size()}, value.data(), value.size());
  }
  void attribute(const Loc& loc, const std::string& name, double value) {
    number_attribute(loc, name, value, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
    sum_.add(loc.field(name), kDouble, {1}, &value, sizeof value);
  }
  void attribute(const Loc& loc, const std::string& name, int value) {
    number_attribute(loc, name, value, H5T_STD_I32LE, H5T_NATIVE_INT);
    sum_.add(loc.field(name), kInt, {1}, &value, sizeof value);
  }

  void vector(const Loc& loc, const std::string& name, const Eigen::VectorXd& v, const Description& d) {
    const hsize_t dims[1] = {static_cast<hsize_t>(v.size())};
    hdf5::write_dataset(loc.id, name, v.data(), 1, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, d);
    sum_.add(loc.field(name), kDouble, {dims[0]}, v.data(), static_cast<std::size_t>(v.size()) * sizeof(double));
  }
  void vector(const Loc& loc, const std::string& name, const std::vector<int>& v, const Description& d) {
    const hsize_t dims[1] = {static_cast<hsize_t>(v.size())};
    hdf5::write_dataset(loc.id, name, v.data(), 1, dims, H5T_STD_I32LE, H5T_NATIVE_INT, d);
    sum_.add(loc.field(name), kInt, {dims[0]}, v.data(), v.size() * sizeof(int));
  }
  void matrix(const Loc& loc, const std::string& name, const Eigen::MatrixXd& m, const Description& d) {
    const RowMajorMatrix row_major = m;  // HDF5 stores C order
    const hsize_t dims[2] = {static_cast<hsize_t>(m.rows()), static_cast<hsize_t>(m.cols())};
    hdf5::write_dataset(loc.id, name, row_major.data(), 2, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, d);
    sum_.add(loc.field(name), kDouble, {dims[0], dims[1]}, row_major.data(),
             static_cast<std::size_t>(m.size()) * sizeof(double));
  }
  // Arrays a failed solve may lack are written only when present.
  void optional(const Loc& loc, const std::string& name, const Eigen::VectorXd& v, const Description& d) {
    if (v.size() > 0) vector(loc, name, v, d);
  }

  std::uint64_t checksum() const { return sum_.value(); }
  FieldChecksum& sum() { return sum_; }  // for the shared groups (/mesh)

 private:
  template <typename T>
  static void number_attribute(const Loc& loc, const std::string& name, T value, hid_t file_type, hid_t mem_type) {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a dataspace");
    Handle attr(H5Acreate2(loc.id, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                "cannot create attribute '" + name + "'");
    check(H5Awrite(attr.get(), mem_type, &value), "cannot write attribute '" + name + "'");
  }
  FieldChecksum sum_;
};

std::string snapshot_group_name(std::size_t i) {
  char buffer[24];
  std::snprintf(buffer, sizeof buffer, "%06zu", i);
  return buffer;
}

// Every field but `complete` and `checksum` (written by the caller, last). Layout and the
// meaning of every field: docs/file-formats.md.
void write_contents(hid_t file, const SnapshotSet& set, FileWriter& w) {
  const Loc root{file, ""};
  w.attribute(root, "format", std::string(kSnapshotFormatName));
  w.attribute(root, "format_version", kSnapshotFormatVersion);
  w.attribute(root, "contactrb_version", std::string(kVersion));
  hdf5::write_string_attribute(file, "description",
                               "contactrb snapshot set (HF solutions over a parameter set); layout: docs/file-formats.md");
  {
    Handle g = w.create_group(root, "case", "the case the snapshots solve: name, kind (builtin | toml), spec (its name or "
                                            "TOML text), mesh refinement level, constraint discretization");
    const Loc c{g.get(), "/case"};
    w.attribute(c, "name", set.case_name);
    w.attribute(c, "kind", set.case_kind);
    w.attribute(c, "spec", set.case_spec);
    w.attribute(c, "level", set.level);
    w.attribute(c, "constraint", set.constraint);
  }
  {
    Handle g = w.create_group(root, "parameter", "the parameters (one subgroup each, 000000, ...) and the parameter set");
    const Loc p{g.get(), "/parameter"};
    w.attribute(p, "set", set.set_name);
    w.attribute(p, "count", static_cast<int>(set.parameters.size()));
    for (std::size_t k = 0; k < set.parameters.size(); ++k) {
      const SnapshotParameter& q = set.parameters[k];
      const std::string name = snapshot_group_name(k);
      Handle pg = w.create_group(p, name, "parameter mu_k: name, kind, units, domain [min, max]");
      const Loc one{pg.get(), p.field(name)};
      w.attribute(one, "name", q.name);
      w.attribute(one, "kind", q.kind);
      w.attribute(one, "units", q.units);
      w.attribute(one, "min", q.min);
      w.attribute(one, "max", q.max);
    }
    // P x p, one row per snapshot (the snapshot groups hold the same points).
    Eigen::MatrixXd mu(static_cast<Eigen::Index>(set.snapshots.size()), static_cast<Eigen::Index>(set.parameters.size()));
    for (std::size_t i = 0; i < set.snapshots.size(); ++i) mu.row(static_cast<Eigen::Index>(i)) = set.snapshots[i].mu.transpose();
    w.matrix(p, "values", mu, {"P x p: row i is the parameter point mu of snapshot i", "column k: the units of parameter k"});
  }
  {
    Handle g = w.create_group(root, "settings", "the Kacanov settings of the HF solves");
    const Loc s{g.get(), "/settings"};
    w.attribute(s, "kacanov_alpha", set.kacanov_alpha);
    w.attribute(s, "kacanov_tolerance", set.kacanov_tolerance);
    w.attribute(s, "kacanov_max_iterations", set.kacanov_max_iterations);
  }
  {
    Handle g = w.create_group(root, "discretization",
                              "the DOF layout shared by every snapshot: DOF 2 i + c is component c of mesh node i");
    const Loc d{g.get(), "/discretization"};
    w.attribute(d, "num_dofs", set.num_dofs);
    w.vector(d, "free_dofs", set.free_dofs, {"n_free: the global DOF of each entry of u0", "index (0-based)"});
    w.vector(d, "contact_dofs", set.contact_dofs,
             {"n_c: the global DOF of each column of K (both components of every slave and master node, ascending)",
              "index (0-based)"});
    w.vector(d, "slave", set.slave, {"S: the slave chain, mesh node indices in order", "index (0-based)"});
    w.vector(d, "master", set.master,
             {"the master chain, mesh node indices in order (closed: the first repeated at the end)", "index (0-based)"});
  }
  // The reference mesh (format 4): no .msh file is needed to use the snapshots.
  w.attribute(root, "has_mesh", set.mesh.nodes.empty() ? 0 : 1);
  if (!set.mesh.nodes.empty()) {
    hdf5::FieldWriter mesh_writer(w.sum());
    mesh::Mesh copy = set.mesh;  // the visitor takes references
    hdf5::visit_mesh(mesh_writer, root, copy);
  }
  Handle snaps_group = w.create_group(root, "snapshots",
                                      "one subgroup per snapshot (000000, ...) in the order of the set, and the "
                                      "per-snapshot tables");
  const Loc snaps{snaps_group.get(), "/snapshots"};
  const std::size_t n = set.snapshots.size();
  w.attribute(snaps, "count", static_cast<int>(n));
  std::vector<int> converged(n), iterations(n);
  Eigen::VectorXd time(static_cast<Eigen::Index>(n)), cpu_time(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const Snapshot& s = set.snapshots[i];
    converged[i] = s.converged ? 1 : 0;
    iterations[i] = s.iterations;
    time(static_cast<Eigen::Index>(i)) = s.time_s;
    cpu_time(static_cast<Eigen::Index>(i)) = s.cpu_time_s;
    const std::string name = snapshot_group_name(i);
    Handle g = w.create_group(snaps, name,
                              "one HF solve: mu, status, message; the arrays (a failed solve may lack them)");
    const Loc one{g.get(), snaps.field(name)};
    w.vector(one, "mu", s.mu, {"p: the parameter point", "entry k: the units of parameter k"});
    w.attribute(one, "status", s.status);
    w.attribute(one, "message", s.message);
    w.optional(one, "u0", s.u0, {"n_free: the displacement on the free DOFs (/discretization/free_dofs)", "length"});
    w.optional(one, "u", s.u, {"num_dofs: the total displacement u_D + u_0 on every DOF", "length"});
    w.optional(one, "lambda", s.lambda, {"R: the contact pressure of each constraint row", "pressure"});
    if (s.K.size() > 0) {
      w.matrix(one, "K", s.K, {"R x n_c: the contact rows K(w) on the contact DOFs (/discretization/contact_dofs)", "1"});
    }
    w.optional(one, "g", s.g, {"R: the gap rows g(w)", "length"});
    w.optional(one, "weight", s.weight, {"R: |I_r|, the length each row integrates", "length"});
    w.optional(one, "gap_pointwise", s.gap_pointwise, {"S: the pointwise gap of each slave node", "length"});
  }
  w.vector(snaps, "converged", converged, {"P: 1 when snapshot i converged, 0 otherwise", "1"});
  w.vector(snaps, "iterations", iterations, {"P: Kacanov iterations of snapshot i", "count"});
  w.vector(snaps, "time_s", time, {"P: wall-clock time of snapshot i (construction, setup, solve)", "s"});
  w.vector(snaps, "cpu_time_s", cpu_time, {"P: CPU time of the thread that solved snapshot i", "s"});
}

void write_checksum(hid_t file, std::uint64_t value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a dataspace");
  Handle attr(H5Acreate2(file, "checksum", H5T_STD_U64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "cannot create attribute 'checksum'");
  check(H5Awrite(attr.get(), H5T_NATIVE_UINT64, &value), "cannot write attribute 'checksum'");
}

// ---------------------------------------------------------------------------- reading

using hdf5::read_number_attribute;
using hdf5::read_string_attribute;  // variable-length (format 4) or fixed-length (older `format`)

int read_int_attribute(hid_t loc, const std::string& name) {
  return read_number_attribute<int>(loc, name, H5T_NATIVE_INT, H5T_INTEGER);
}

// Opens dataset `name`, checks its rank and type class, returns its dimensions (bounded by
// the file's size: 4 bytes, the smallest element we read).
Handle open_dataset(hid_t loc, const std::string& name, int rank, H5T_class_t expected, hsize_t* dims) {
  return hdf5::open_dataset(loc, name, rank, expected, dims, 4);
}

// The mirror of FileWriter: every value read is added to the checksum under the same name.
class FileReader {
 public:
  Handle open_group(const Loc& loc, const std::string& name) const {
    if (!exists(loc.id, name)) throw H5Failure{"missing group '" + name + "'"};
    return {H5Gopen2(loc.id, name.c_str(), H5P_DEFAULT), H5Gclose, "cannot open group '" + name + "'"};
  }

  std::string string(const Loc& loc, const std::string& name) {
    const std::string v = read_string_attribute(loc.id, name);
    sum_.add(loc.field(name), kString, {v.size()}, v.data(), v.size());
    return v;
  }
  double number(const Loc& loc, const std::string& name) {
    const double v = read_number_attribute<double>(loc.id, name, H5T_NATIVE_DOUBLE, H5T_FLOAT);
    sum_.add(loc.field(name), kDouble, {1}, &v, sizeof v);
    return v;
  }
  int integer(const Loc& loc, const std::string& name) {
    const int v = read_int_attribute(loc.id, name);
    sum_.add(loc.field(name), kInt, {1}, &v, sizeof v);
    return v;
  }

  Eigen::VectorXd vector(const Loc& loc, const std::string& name) {
    hsize_t dims[1] = {0};
    Handle set = open_dataset(loc.id, name, 1, H5T_FLOAT, dims);
    Eigen::VectorXd v(static_cast<Eigen::Index>(dims[0]));
    if (v.size() > 0) {
      check(H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
            "cannot read dataset '" + name + "'");
    }
    sum_.add(loc.field(name), kDouble, {dims[0]}, v.data(), static_cast<std::size_t>(v.size()) * sizeof(double));
    return v;
  }
  std::vector<int> int_vector(const Loc& loc, const std::string& name) {
    hsize_t dims[1] = {0};
    Handle set = open_dataset(loc.id, name, 1, H5T_INTEGER, dims);
    std::vector<int> v(static_cast<std::size_t>(dims[0]));
    if (!v.empty()) {
      check(H5Dread(set.get(), H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
            "cannot read dataset '" + name + "'");
    }
    sum_.add(loc.field(name), kInt, {dims[0]}, v.data(), v.size() * sizeof(int));
    return v;
  }
  Eigen::MatrixXd matrix(const Loc& loc, const std::string& name) {
    hsize_t dims[2] = {0, 0};
    Handle set = open_dataset(loc.id, name, 2, H5T_FLOAT, dims);
    RowMajorMatrix m(static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]));
    if (m.size() > 0) {
      check(H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.data()),
            "cannot read dataset '" + name + "'");
    }
    sum_.add(loc.field(name), kDouble, {dims[0], dims[1]}, m.data(),
             static_cast<std::size_t>(m.size()) * sizeof(double));
    return m;
  }
  Eigen::VectorXd optional(const Loc& loc, const std::string& name) {
    return exists(loc.id, name) ? vector(loc, name) : Eigen::VectorXd();
  }

  std::uint64_t checksum() const { return sum_.value(); }
  FieldChecksum& sum() { return sum_; }  // for the shared groups (/mesh)

 private:
  FieldChecksum sum_;
};

// `inconsistency`: the first disagreement between two stored copies of one fact, reported by
// the caller after the checksum (which explains most of them: an edited or damaged file).
SnapshotSet read_contents(hid_t file, FileReader& r, std::string& inconsistency) {
  const auto note = [&](const std::string& what) {
    if (inconsistency.empty()) inconsistency = what;
  };
  const Loc root{file, ""};
  SnapshotSet set;
  // The root attributes were checked before; read again for the checksum.
  (void)r.string(root, "format");
  (void)r.integer(root, "format_version");
  (void)r.string(root, "contactrb_version");
  {
    Handle g = r.open_group(root, "case");
    const Loc c{g.get(), "/case"};
    set.case_name = r.string(c, "name");
    set.case_kind = r.string(c, "kind");
    set.case_spec = r.string(c, "spec");
    set.level = r.integer(c, "level");
    set.constraint = r.string(c, "constraint");
  }
  Eigen::MatrixXd mu;
  {
    Handle g = r.open_group(root, "parameter");
    const Loc p{g.get(), "/parameter"};
    set.set_name = r.string(p, "set");
    const int count = r.integer(p, "count");
    if (count < 1 || count > kMaxParameters) {
      throw H5Failure{"/parameter/count is " + std::to_string(count) + " (expected 1 to " +
                      std::to_string(kMaxParameters) + ")"};
    }
    for (int k = 0; k < count; ++k) {
      const std::string name = snapshot_group_name(static_cast<std::size_t>(k));
      Handle pg = r.open_group(p, name);
      const Loc one{pg.get(), p.field(name)};
      SnapshotParameter& q = set.parameters.emplace_back();
      q.name = r.string(one, "name");
      q.kind = r.string(one, "kind");
      q.units = r.string(one, "units");
      q.min = r.number(one, "min");
      q.max = r.number(one, "max");
    }
    mu = r.matrix(p, "values");
  }
  {
    Handle g = r.open_group(root, "settings");
    const Loc s{g.get(), "/settings"};
    set.kacanov_alpha = r.number(s, "kacanov_alpha");
    set.kacanov_tolerance = r.number(s, "kacanov_tolerance");
    set.kacanov_max_iterations = r.integer(s, "kacanov_max_iterations");
  }
  {
    Handle g = r.open_group(root, "discretization");
    const Loc d{g.get(), "/discretization"};
    set.num_dofs = r.integer(d, "num_dofs");
    set.free_dofs = r.int_vector(d, "free_dofs");
    set.contact_dofs = r.int_vector(d, "contact_dofs");
    set.slave = r.int_vector(d, "slave");
    set.master = r.int_vector(d, "master");
  }
  const int has_mesh = r.integer(root, "has_mesh");
  if (has_mesh == 1) {
    hdf5::FieldReader mesh_reader(r.sum());
    hdf5::visit_mesh(mesh_reader, root, set.mesh);
  } else if (has_mesh != 0) {
    throw H5Failure{"the root attribute has_mesh is " + std::to_string(has_mesh) + " (expected 0 or 1)"};
  }
  Handle snaps_group = r.open_group(root, "snapshots");
  const Loc snaps{snaps_group.get(), "/snapshots"};
  const int count = r.integer(snaps, "count");
  const std::vector<int> converged = r.int_vector(snaps, "converged");
  const std::vector<int> iterations = r.int_vector(snaps, "iterations");
  const Eigen::VectorXd time = r.vector(snaps, "time_s");
  const Eigen::VectorXd cpu_time = r.vector(snaps, "cpu_time_s");
  const auto n = static_cast<std::size_t>(count);
  if (count < 0 || mu.rows() != count || mu.cols() != static_cast<Eigen::Index>(set.parameters.size()) ||
      converged.size() != n || iterations.size() != n ||
      time.size() != count || cpu_time.size() != count) {
    throw H5Failure{"the snapshot count " + std::to_string(count) + " disagrees with /parameter/values (" +
                    std::to_string(mu.rows()) + " x " + std::to_string(mu.cols()) + ") or the per-snapshot tables"};
  }
  set.snapshots.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Snapshot& s = set.snapshots[i];
    const std::string name = snapshot_group_name(i);
    Handle g = r.open_group(snaps, name);
    const Loc one{g.get(), snaps.field(name)};
    s.mu = r.vector(one, "mu");
    s.status = r.string(one, "status");
    s.message = r.string(one, "message");
    if (converged[i] != 0 && converged[i] != 1) {
      note("/snapshots/converged[" + std::to_string(i) + "] is " + std::to_string(converged[i]) + " (expected 0 or 1)");
    }
    s.converged = converged[i] == 1;
    s.iterations = iterations[i];
    s.time_s = time(static_cast<Eigen::Index>(i));
    s.cpu_time_s = cpu_time(static_cast<Eigen::Index>(i));
    // /parameter/values and the group's mu are two copies: both must agree (bitwise).
    const Eigen::VectorXd listed = mu.row(static_cast<Eigen::Index>(i)).transpose();
    if (listed.size() != s.mu.size() ||
        std::memcmp(listed.data(), s.mu.data(), static_cast<std::size_t>(listed.size()) * sizeof(double)) != 0) {
      note("/parameter/values[" + std::to_string(i) + "] differs from the mu of " + one.path);
    }
    if (s.converged) {
      s.u0 = r.vector(one, "u0");
      s.u = r.vector(one, "u");
      s.lambda = r.vector(one, "lambda");
      s.K = r.matrix(one, "K");
      s.g = r.vector(one, "g");
      s.weight = r.vector(one, "weight");
      s.gap_pointwise = r.vector(one, "gap_pointwise");
    } else {
      s.u0 = r.optional(one, "u0");
      s.u = r.optional(one, "u");
      s.lambda = r.optional(one, "lambda");
      if (exists(one.id, "K")) s.K = r.matrix(one, "K");
      s.g = r.optional(one, "g");
      s.weight = r.optional(one, "weight");
      s.gap_pointwise = r.optional(one, "gap_pointwise");
    }
  }
  return set;
}

std::uint64_t read_checksum(hid_t file) {
  return read_number_attribute<std::uint64_t>(file, "checksum", H5T_NATIVE_UINT64, H5T_INTEGER);
}

// The `format` of a reduced model file before model format 5 is a dataset of bytes, not an
// attribute: recognized here to say what the file is.
bool has_model_format(hid_t file) {
  if (!exists(file, "format")) return false;
  hsize_t dims[1] = {0};
  try {  // open_dataset refuses a group or another shape with a Failure
    Handle set = open_dataset(file, "format", 1, H5T_INTEGER, dims);
    const std::string expected = kReducedModelFormatName;
    if (dims[0] != expected.size()) return false;
    std::string value(expected.size(), '\0');
    check(H5Dread(set.get(), H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, value.data()), "format");
    return value == expected;
  } catch (const H5Failure&) {
    return false;
  }
}

// A new temporary file next to the target (common/output_file.hpp); temporaries of killed
// writers are removed first.
std::string temporary_name(const std::string& path) {
  check_output_target(path);
  remove_stale_temporaries(path);
  return temporary_path(path).string();
}

}  // namespace

// ---------------------------------------------------------------------------- checking

namespace {

[[noreturn]] void invalid(const std::string& what) { throw Error(what); }

// Shortest text that reads back as the same double: a value just outside the domain must not
// print as its bound.
std::string exact(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

// Index list `name`: every entry in [0, bound), no entry twice (except that a closed chain
// may repeat its first node once, at the end). Duplicates are found by sorting a copy: the
// memory is that of the list, not of `bound` (a damaged num_dofs may be huge).
void check_indices(const std::vector<int>& v, int bound, const std::string& name, const std::string& bound_name,
                   bool closed_chain_allowed = false) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] < 0 || v[i] >= bound) {
      invalid(name + "[" + std::to_string(i) + "] = " + std::to_string(v[i]) + " is outside [0, " + bound_name +
              " = " + std::to_string(bound) + ")");
    }
  }
  const bool closed = closed_chain_allowed && v.size() >= 3 && v.back() == v.front();
  std::vector<std::pair<int, std::size_t>> sorted;  // (index, position)
  for (std::size_t i = 0; i + (closed ? 1 : 0) < v.size(); ++i) sorted.emplace_back(v[i], i);
  std::sort(sorted.begin(), sorted.end());
  std::size_t first = v.size();  // earliest position that repeats an earlier entry
  for (std::size_t k = 1; k < sorted.size(); ++k) {
    if (sorted[k].first == sorted[k - 1].first) first = std::min(first, sorted[k].second);
  }
  if (first < v.size()) {
    invalid(name + "[" + std::to_string(first) + "] = " + std::to_string(v[first]) + " appears twice");
  }
}

// The first non-finite entry of a converged snapshot's array, named (a NaN in u0 would
// become a NaN POD basis, in K a NaN EIM, silently).
template <typename Derived>
void check_finite(const Eigen::DenseBase<Derived>& a, const std::string& name) {
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      if (!std::isfinite(a(i, j))) {
        std::ostringstream os;
        os << name << " holds a non-finite value (" << a(i, j) << ") at ";
        if (a.cols() == 1) {
          os << "entry " << i;
        } else {
          os << "(" << i << ", " << j << ")";
        }
        invalid(os.str());
      }
    }
  }
}

bool known_constraint(const std::string& c) { return c == "collocation" || c == "lac" || c == "lac-simpson"; }

}  // namespace

void check_snapshot_set(const SnapshotSet& set) {
  // Header.
  if (set.case_kind != "builtin" && set.case_kind != "toml") {
    invalid("/case/kind is '" + set.case_kind + "' (expected builtin or toml)");
  }
  if (set.level < 0) invalid("/case/level is " + std::to_string(set.level) + " (expected >= 0)");
  if (set.parameters.empty()) invalid("/parameter holds no parameter");
  for (std::size_t k = 0; k < set.parameters.size(); ++k) {
    const SnapshotParameter& q = set.parameters[k];
    if (!std::isfinite(q.min) || !std::isfinite(q.max) || q.min > q.max) {
      invalid("the domain [" + exact(q.min) + ", " + exact(q.max) + "] of parameter '" + q.name + "' (/parameter/" +
              snapshot_group_name(k) + " min, max) is not an interval");
    }
  }
  if (!(std::isfinite(set.kacanov_alpha) && set.kacanov_alpha > 0.0 && set.kacanov_alpha <= 1.0) ||
      !(std::isfinite(set.kacanov_tolerance) && set.kacanov_tolerance > 0.0) || set.kacanov_max_iterations < 1) {
    invalid("the Kacanov settings (/settings) are invalid (alpha in (0, 1], tolerance > 0, max_iterations >= 1)");
  }

  // Discretization: every index is checked before anyone uses it.
  const bool has_layout = set.num_dofs != 0;
  if (set.num_dofs < 0 || set.num_dofs % 2 != 0) {
    invalid("/discretization num_dofs = " + std::to_string(set.num_dofs) + " (expected 2 x nodes, >= 0)");
  }
  if (!has_layout) {
    // Every solve threw before its discretization existed: nothing but failures to record.
    if (!set.free_dofs.empty() || !set.contact_dofs.empty() || !set.slave.empty() || !set.master.empty()) {
      invalid("/discretization has index lists but num_dofs = 0");
    }
  } else if (!known_constraint(set.constraint)) {
    invalid("/case/constraint is '" + set.constraint + "' (expected collocation, lac or lac-simpson)");
  }
  const int num_nodes = set.num_dofs / 2;
  check_indices(set.free_dofs, set.num_dofs, "/discretization/free_dofs", "num_dofs");
  check_indices(set.slave, num_nodes, "/discretization/slave", "nodes");
  check_indices(set.master, num_nodes, "/discretization/master", "nodes", /*closed_chain_allowed=*/true);
  if (has_layout && (set.slave.empty() || set.master.size() < 2)) {
    invalid("/discretization: the slave chain has " + std::to_string(set.slave.size()) + " node(s), the master " +
            std::to_string(set.master.size()) + " (at least 1 and 2 are needed)");
  }
  // contact_dofs is derived from the chains (both components of each contact node, ascending):
  // anything else would make K's columns mean other DOFs.
  std::vector<int> nodes = set.slave;
  nodes.insert(nodes.end(), set.master.begin(), set.master.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  bool contact_ok = set.contact_dofs.size() == 2 * nodes.size();
  for (std::size_t i = 0; contact_ok && i < nodes.size(); ++i) {
    contact_ok = set.contact_dofs[2 * i] == 2 * nodes[i] && set.contact_dofs[2 * i + 1] == 2 * nodes[i] + 1;
  }
  if (!contact_ok) {
    invalid("/discretization/contact_dofs (" + std::to_string(set.contact_dofs.size()) +
            " entries) are not the two components of the " + std::to_string(nodes.size()) +
            " slave and master nodes in ascending order");
  }

  // The stored reference mesh (format 4): valid, and the mesh of these DOFs.
  if (!set.mesh.nodes.empty()) {
    try {
      mesh::validate(set.mesh);
    } catch (const Error& e) {
      invalid(std::string("/mesh: ") + e.what());
    }
    if (set.mesh.num_dofs() != set.num_dofs) {
      invalid("/mesh has " + std::to_string(set.mesh.num_nodes()) + " nodes (" + std::to_string(set.mesh.num_dofs()) +
              " DOFs), /discretization num_dofs = " + std::to_string(set.num_dofs));
    }
  }

  // Snapshots.
  const auto num_free = static_cast<Eigen::Index>(set.free_dofs.size());
  const auto nc = static_cast<Eigen::Index>(set.contact_dofs.size());
  const auto S = static_cast<Eigen::Index>(set.slave.size());
  for (std::size_t i = 0; i < set.snapshots.size(); ++i) {
    const Snapshot& s = set.snapshots[i];
    const std::string where = "/snapshots/" + snapshot_group_name(i);
    if (s.mu.size() != static_cast<Eigen::Index>(set.parameters.size())) {
      invalid(where + ": mu has " + std::to_string(s.mu.size()) + " values for " + std::to_string(set.parameters.size()) +
              " parameters");
    }
    for (std::size_t k = 0; k < set.parameters.size(); ++k) {
      const double v = s.mu(static_cast<Eigen::Index>(k));
      const SnapshotParameter& q = set.parameters[k];
      if (!std::isfinite(v) || v < q.min || v > q.max) {
        invalid(where + ": mu = " + exact(v) + " (" + q.name + ") is outside the stored domain [" + exact(q.min) + ", " +
                exact(q.max) + "]");
      }
    }
    if (!std::isfinite(s.time_s) || s.time_s < 0.0 || !std::isfinite(s.cpu_time_s) || s.cpu_time_s < 0.0) {
      invalid(where + ": its time_s or cpu_time_s is negative or not finite");
    }
    if (s.iterations < 0) invalid(where + ": iterations = " + std::to_string(s.iterations) + " (expected >= 0)");
    if (s.converged != (s.status == "converged")) {
      invalid(where + ": status '" + s.status + "' disagrees with /snapshots/converged = " + (s.converged ? "1" : "0"));
    }
    const auto R = s.lambda.size();
    const auto expect = [&](bool ok, const std::string& what) {
      if (!ok) invalid(where + ": " + what);
    };
    expect(s.u0.size() == 0 || s.u0.size() == num_free,
           "u0 has " + std::to_string(s.u0.size()) + " entries, expected " + std::to_string(num_free));
    expect(s.u.size() == 0 || s.u.size() == set.num_dofs,
           "u has " + std::to_string(s.u.size()) + " entries, expected " + std::to_string(set.num_dofs));
    expect(s.K.size() == 0 || (s.K.rows() == R && s.K.cols() == nc),
           "K is " + std::to_string(s.K.rows()) + " x " + std::to_string(s.K.cols()) + ", expected " +
               std::to_string(R) + " x " + std::to_string(nc));
    expect(s.g.size() == 0 || s.g.size() == R, "g and lambda differ in size");
    expect(s.weight.size() == 0 || s.weight.size() == R, "weight and lambda differ in size");
    expect(s.gap_pointwise.size() == 0 || s.gap_pointwise.size() == S, "gap_pointwise and the slave chain differ in size");
    if (!s.converged) continue;  // a failed solve is a record: its last iterate may be anything
    expect(has_layout && s.u0.size() > 0 && s.u.size() > 0 && R > 0 && s.K.size() > 0 && s.g.size() == R &&
               s.weight.size() == R && s.gap_pointwise.size() == S,
           "a converged snapshot needs u0, u, lambda, K, g, weight and gap_pointwise");
    check_finite(s.u0, where + "/u0");
    check_finite(s.u, where + "/u");
    check_finite(s.lambda, where + "/lambda");
    check_finite(s.K, where + "/K");
    check_finite(s.g, where + "/g");
    check_finite(s.weight, where + "/weight");
    check_finite(s.gap_pointwise, where + "/gap_pointwise");
  }
}

bool is_snapshot_file(const std::string& path) {
  const QuietHdf5 quiet;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || H5Fis_hdf5(path.c_str()) <= 0) return false;
  try {
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "cannot open");
    return H5Aexists(file.get(), "format") > 0 &&
           read_string_attribute(file.get(), "format", check_seal(path) == SealState::Valid) == kSnapshotFormatName;
  } catch (const H5Failure&) {
    return false;
  }
}


void write_snapshot_file(const SnapshotSet& set, const std::string& path) {
  try {
    check_snapshot_set(set);
  } catch (const Error& e) {
    throw Error("cannot write snapshot file '" + path + "': " + e.what());
  }
  const QuietHdf5 quiet;
  const std::string tmp = temporary_name(path);
  try {
    const Handle fcpl = hdf5::sealed_file_properties();
    Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_EXCL, fcpl.get(), H5P_DEFAULT), H5Fclose,
                "cannot create the file (is the directory there and writable?)");
    FileWriter w;
    write_contents(file.get(), set, w);
    write_checksum(file.get(), w.checksum());
    // Written last: a file without it is an interrupted write.
    Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a dataspace");
    Handle attr(H5Acreate2(file.get(), "complete", H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                "cannot create attribute 'complete'");
    const int complete = 1;
    check(H5Awrite(attr.get(), H5T_NATIVE_INT, &complete), "cannot write attribute 'complete'");
    file.close("cannot flush and close the file");
  } catch (const H5Failure& f) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw Error("cannot write snapshot file '" + path + "': " + f.what);
  }
  try {
    seal_file(tmp);  // the hash of every byte, checked before HDF5 parses the file
    commit_temporary(tmp, path);
  } catch (const Error& e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
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
  // Before HDF5 parses anything: a sealed file whose bytes changed (common/file_seal.hpp).
  const SealState seal = check_seal(path);
  if (seal == SealState::Mismatch) {
    throw Error(name + " is truncated or damaged: checksum mismatch: its bytes changed after it was written");
  }
  const bool sealed = seal == SealState::Valid;
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
      if (has_model_format(file.get())) {
        throw Error(name + " is a contactrb reduced model file, not a snapshot file (a model is read by `contactrb "
                    "online` and `contactrb evaluate`)");
      }
      throw Error(name + " is an HDF5 file but not a contactrb snapshot file (no 'format' attribute)");
    }
    std::string format;
    try {
      format = read_string_attribute(file.get(), "format", sealed);
    } catch (const H5Failure& f) {
      if (!sealed) throw Error(name + " is damaged or not written by contactrb (" + f.what + ")");
      format = "(unreadable)";
    }
    if (format == kReducedModelFormatName) {
      throw Error(name + " is a contactrb reduced model file, not a snapshot file (a model is read by `contactrb "
                  "online` and `contactrb evaluate`)");
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
                  std::to_string(kSnapshotFormatVersion) + " (generate the snapshots again with `contactrb snapshots`)");
    }
    // Every file of this version is sealed by its writer: no seal, its first bytes were damaged.
    if (!sealed) throw Error(name + " is damaged: its seal (the first bytes of the file) is missing");
    // `complete` = 1 is written last; any other value (0, a damaged one) is not a finished write.
    if (H5Aexists(file.get(), "complete") <= 0 || read_int_attribute(file.get(), "complete") != 1) {
      throw Error(name + " is incomplete (the run that wrote it was interrupted): generate it again");
    }
    SnapshotSet set;
    try {
      const std::uint64_t stored = read_checksum(file.get());
      FileReader r;
      std::string inconsistency;
      set = read_contents(file.get(), r, inconsistency);
      if (stored != r.checksum()) {
        throw H5Failure{"checksum mismatch: the file was modified or damaged after it was written"};
      }
      if (!inconsistency.empty()) throw H5Failure{inconsistency};
    } catch (const H5Failure& f) {
      throw Error(name + " is truncated or damaged: " + f.what);
    }
    // A file with a valid checksum may still come from a faulty writer or be crafted: no index,
    // size or value is used before it is checked.
    try {
      check_snapshot_set(set);
    } catch (const Error& e) {
      throw Error(name + " is damaged: " + e.what());
    }
    return set;
  } catch (const H5Failure& f) {
    throw Error(name + ": " + f.what);
  }
}

}  // namespace contactrb::io
