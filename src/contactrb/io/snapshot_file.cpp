#include "contactrb/io/snapshot_file.hpp"

#include <hdf5.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <system_error>

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
#include "contactrb/io/snapshot_rows.hpp"

namespace contactrb::io {

int SnapshotSet::num_failed() const {
  int n = 0;
  for (const Snapshot& s : snapshots) n += s.converged ? 0 : 1;
  return n;
}

namespace {

using hdf5::check;
using hdf5::Description;
using hdf5::Handle;
using hdf5::list_entry_name;
using hdf5::Loc;
using H5Failure = hdf5::Failure;
using QuietHdf5 = hdf5::Quiet;

// More parameters than this is taken for a damaged count (a design study has 3 to 10).
constexpr int kMaxParameters = 1000;

// ---------------------------------------------------------------------------- layout
// One layout, written by hdf5::FieldWriter and read by hdf5::FieldReader (Set: const
// SnapshotSet for the writer, SnapshotSet for the reader). Every field but `description`,
// `checksum` and `complete`, which the writer adds; the meaning of every field:
// docs/file-formats.md, "Snapshot file".

// The per-snapshot tables: /parameter/values and the columns of /snapshots. They repeat what
// the snapshot groups hold (h5py reads a column without opening P groups); the reader checks
// that both copies agree (first_inconsistency).
struct SnapshotTables {
  Eigen::MatrixXd mu;  // P x p: row i is the mu of snapshot i
  std::vector<int> converged;
  std::vector<int> iterations;
  Eigen::VectorXd time_s;
  Eigen::VectorXd cpu_time_s;
  // Each snapshot's K as stored (format 8), checked and converted after the checksum
  // (contact_rows_of); the reader's copy of a dense K (formats 5 to 7) is converted on reading.
  std::vector<CsrArrays> K;
};

SnapshotTables tables_of(const SnapshotSet& set) {
  const std::size_t n = set.snapshots.size();
  SnapshotTables t;
  t.mu.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(set.parameters.size()));
  t.converged.resize(n);
  t.iterations.resize(n);
  t.time_s.resize(static_cast<Eigen::Index>(n));
  t.cpu_time_s.resize(static_cast<Eigen::Index>(n));
  t.K.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Snapshot& s = set.snapshots[i];
    const auto row = static_cast<Eigen::Index>(i);
    t.mu.row(row) = s.mu.transpose();
    t.converged[i] = s.converged ? 1 : 0;
    t.iterations[i] = s.iterations;
    t.time_s(row) = s.time_s;
    t.cpu_time_s(row) = s.cpu_time_s;
    t.K[i] = csr_of(s.K);
  }
  return t;
}

// The format attributes; the reader checks them first (check_header) and reads them again
// here for the checksum.
// Returns the version (the reader's: the file's, checked by check_header).
template <typename V>
int visit_format(V& v, const Loc& root) {
  std::string format = kSnapshotFormatName;
  int version = kSnapshotFormatVersion;
  std::string written_by = kVersion;
  v.str(root, "format", format);
  v.integer(root, "format_version", version);
  v.str(root, "contactrb_version", written_by);
  return version;
}

// The space dimension (format 6 and later; a format 5 file is 2D).
template <typename V, typename Set>
void visit_dimension(V& v, const Loc& root, Set& set, int version) {
  if (version < 6) return;
  v.integer(root, "dimension", set.dimension);
  if (set.dimension != 2 && set.dimension != 3) {
    throw H5Failure{"the root attribute dimension is " + std::to_string(set.dimension) + " (expected 2 or 3)"};
  }
}

template <typename V, typename Set>
void visit_case(V& v, const Loc& root, Set& set) {
  Handle g = v.group(root, "case", "the case the snapshots solve: name, kind (builtin | toml), spec (its name or TOML "
                                   "text), mesh refinement level, constraint discretization");
  const Loc c{g.get(), "/case"};
  v.str(c, "name", set.case_name);
  v.str(c, "kind", set.case_kind);
  v.str(c, "spec", set.case_spec);
  v.integer(c, "level", set.level);
  v.str(c, "constraint", set.constraint);
}

template <typename V, typename Set>
void visit_parameters(V& v, const Loc& root, Set& set, Eigen::MatrixXd& mu) {
  Handle g = v.group(root, "parameter", "the parameters (one subgroup each, 000000, ...) and the parameter set");
  const Loc p{g.get(), "/parameter"};
  v.str(p, "set", set.set_name);
  int count = static_cast<int>(set.parameters.size());
  v.integer(p, "count", count);
  if (count < 1 || count > kMaxParameters) {
    throw H5Failure{"/parameter/count is " + std::to_string(count) + " (expected 1 to " +
                    std::to_string(kMaxParameters) + ")"};
  }
  if constexpr (!V::kWriting) set.parameters.resize(static_cast<std::size_t>(count));
  for (std::size_t k = 0; k < set.parameters.size(); ++k) {
    auto& q = set.parameters[k];
    const std::string name = list_entry_name(k);
    Handle pg = v.group(p, name, "parameter mu_k: name, kind, units, domain [min, max]");
    const Loc one{pg.get(), p.field(name)};
    v.str(one, "name", q.name);
    v.str(one, "kind", q.kind);
    v.str(one, "units", q.units);
    v.num(one, "min", q.min);
    v.num(one, "max", q.max);
  }
  v.mat(p, "values", mu, {"P x p: row i is the parameter point mu of snapshot i", "column k: the units of parameter k"});
}

template <typename V, typename Set>
void visit_settings(V& v, const Loc& root, Set& set, int version) {
  Handle g = v.group(root, "settings", "the HF method (solver: kacanov | newton) and the Kacanov settings of the HF solves");
  const Loc s{g.get(), "/settings"};
  if (version >= 7) {
    v.str(s, "solver", set.solver);
  } else if constexpr (!V::kWriting) {
    set.solver = "kacanov";  // the only method of formats 5 and 6
  }
  v.num(s, "kacanov_alpha", set.kacanov_alpha);
  v.num(s, "kacanov_tolerance", set.kacanov_tolerance);
  v.integer(s, "kacanov_max_iterations", set.kacanov_max_iterations);
}

template <typename V, typename Set>
void visit_discretization(V& v, const Loc& root, Set& set) {
  Handle g = v.group(root, "discretization",
                     "the DOF layout shared by every snapshot: DOF 2 i + c is component c of mesh node i");
  const Loc d{g.get(), "/discretization"};
  v.integer(d, "num_dofs", set.num_dofs);
  v.ints(d, "free_dofs", set.free_dofs, {"n_free: the global DOF of each entry of u0", "index (0-based)"});
  v.ints(d, "contact_dofs", set.contact_dofs,
         {"n_c: the global DOF of each column of K (both components of every slave and master node, ascending)",
          "index (0-based)"});
  v.ints(d, "slave", set.slave, {"S: the slave chain, mesh node indices in order", "index (0-based)"});
  v.ints(d, "master", set.master,
         {"the master chain, mesh node indices in order (closed: the first repeated at the end)", "index (0-based)"});
}

// The reference mesh (format 4 and later): no .msh file is needed to use the snapshots.
template <typename V, typename Set>
void visit_reference_mesh(V& v, const Loc& root, Set& set) {
  const bool three = set.dimension == 3;
  int has_mesh = (three ? set.mesh3.nodes.empty() : set.mesh.nodes.empty()) ? 0 : 1;
  v.integer(root, "has_mesh", has_mesh);
  if (has_mesh == 1 && three) {
    hdf5::visit_mesh(v, root, set.mesh3);
  } else if (has_mesh == 1) {
    hdf5::visit_mesh(v, root, set.mesh);
  } else if (has_mesh != 0) {
    throw H5Failure{"the root attribute has_mesh is " + std::to_string(has_mesh) + " (expected 0 or 1)"};
  }
}

// K(w) on the contact DOFs: compressed rows (format 8), read as such; a dense R x n_c dataset
// `K` (formats 5 to 7) is read and converted to its non-zero entries.
template <typename V>
void visit_contact_rows(V& v, const Loc& one, CsrArrays& K, bool converged, int version) {
  if constexpr (!V::kWriting) {
    if (version < 8) {
      Eigen::MatrixXd dense;
      v.optional(one, "K", dense, {"R x n_c: the contact rows K(w) on the contact DOFs", "1"}, converged);
      K = dense.size() > 0 ? csr_of(rows_from_dense(dense)) : CsrArrays{};
      return;
    }
    if (!converged && !V::has(one, "K_indptr")) return;  // a failed solve without rows
  } else if (K.indptr.empty()) {
    return;
  }
  v.ints(one, "K_indptr", K.indptr,
         {"R + 1: row r of K(w) holds the entries K_indptr[r] to K_indptr[r + 1] - 1 of K_indices and K_data",
          "index (0-based)"});
  v.ints(one, "K_indices", K.indices,
         {"nnz: the column of each entry of K(w), a contact DOF (/discretization/contact_dofs), ascending within a row",
          "index (0-based)"});
  v.dvec(one, "K_data", K.data, {"nnz: the value of each entry of K(w)", "1"});
}

// One HF solve. The arrays of a converged solve are required; a failed one stores whatever
// the solver returned (no arrays after an exception).
template <typename V, typename S>
void visit_snapshot(V& v, const Loc& snaps, std::size_t i, S& s, CsrArrays& K, bool converged, int version) {
  const std::string name = list_entry_name(i);
  Handle g = v.group(snaps, name, "one HF solve: mu, status, message; the arrays (a failed solve may lack them)");
  const Loc one{g.get(), snaps.field(name)};
  v.vec(one, "mu", s.mu, {"p: the parameter point", "entry k: the units of parameter k"});
  v.str(one, "status", s.status);
  v.str(one, "message", s.message);
  v.optional(one, "u0", s.u0, {"n_free: the displacement on the free DOFs (/discretization/free_dofs)", "length"},
             converged);
  v.optional(one, "u", s.u, {"num_dofs: the total displacement u_D + u_0 on every DOF", "length"}, converged);
  v.optional(one, "lambda", s.lambda, {"R: the contact pressure of each constraint row", "pressure"}, converged);
  visit_contact_rows(v, one, K, converged, version);
  v.optional(one, "g", s.g, {"R: the gap rows g(w)", "length"}, converged);
  v.optional(one, "weight", s.weight, {"R: |I_r|, the length each row integrates", "length"}, converged);
  v.optional(one, "gap_pointwise", s.gap_pointwise, {"S: the pointwise gap of each slave node", "length"}, converged);
}

// The tables are read before the snapshot groups: a group's `converged` entry says which of
// its arrays must be there.
template <typename V, typename Set>
void visit_snapshots(V& v, const Loc& root, Set& set, SnapshotTables& t, int version) {
  Handle g = v.group(root, "snapshots",
                     "one subgroup per snapshot (000000, ...) in the order of the set, and the per-snapshot tables");
  const Loc snaps{g.get(), "/snapshots"};
  int count = static_cast<int>(set.snapshots.size());
  v.integer(snaps, "count", count);
  v.ints(snaps, "converged", t.converged, {"P: 1 when snapshot i converged, 0 otherwise", "1"});
  v.ints(snaps, "iterations", t.iterations, {"P: Kacanov iterations of snapshot i", "count"});
  v.vec(snaps, "time_s", t.time_s, {"P: wall-clock time of snapshot i (construction, setup, solve)", "s"});
  v.vec(snaps, "cpu_time_s", t.cpu_time_s, {"P: CPU time of the thread that solved snapshot i", "s"});
  const auto n = static_cast<std::size_t>(count);
  if (count < 0 || t.mu.rows() != count || t.mu.cols() != static_cast<Eigen::Index>(set.parameters.size()) ||
      t.converged.size() != n || t.iterations.size() != n || t.time_s.size() != count || t.cpu_time_s.size() != count) {
    throw H5Failure{"the snapshot count " + std::to_string(count) + " disagrees with /parameter/values (" +
                    std::to_string(t.mu.rows()) + " x " + std::to_string(t.mu.cols()) + ") or the per-snapshot tables"};
  }
  if constexpr (!V::kWriting) {
    set.snapshots.resize(n);
    t.K.resize(n);
  }
  for (std::size_t i = 0; i < n; ++i) {
    auto& s = set.snapshots[i];
    visit_snapshot(v, snaps, i, s, t.K[i], t.converged[i] == 1, version);
    if constexpr (!V::kWriting) {
      const auto row = static_cast<Eigen::Index>(i);
      s.converged = t.converged[i] == 1;
      s.iterations = t.iterations[i];
      s.time_s = t.time_s(row);
      s.cpu_time_s = t.cpu_time_s(row);
    }
  }
}

template <typename V, typename Set>
void visit(V& v, const Loc& root, Set& set, SnapshotTables& tables) {
  const int version = visit_format(v, root);
  visit_dimension(v, root, set, version);
  visit_case(v, root, set);
  visit_parameters(v, root, set, tables.mu);
  visit_settings(v, root, set, version);
  visit_discretization(v, root, set);
  visit_reference_mesh(v, root, set);
  visit_snapshots(v, root, set, tables, version);
}

// The first disagreement between the tables and the snapshot groups, or "". Reported after the
// checksum, which explains most of them (an edited or damaged file).
std::string first_inconsistency(const SnapshotSet& set, const SnapshotTables& t) {
  for (std::size_t i = 0; i < set.snapshots.size(); ++i) {
    if (t.converged[i] != 0 && t.converged[i] != 1) {
      return "/snapshots/converged[" + std::to_string(i) + "] is " + std::to_string(t.converged[i]) +
             " (expected 0 or 1)";
    }
    // Two copies of one point: both must agree bitwise.
    const Eigen::VectorXd listed = t.mu.row(static_cast<Eigen::Index>(i)).transpose();
    const Eigen::VectorXd& mu = set.snapshots[i].mu;
    if (listed.size() != mu.size() ||
        std::memcmp(listed.data(), mu.data(), static_cast<std::size_t>(listed.size()) * sizeof(double)) != 0) {
      return "/parameter/values[" + std::to_string(i) + "] differs from the mu of /snapshots/" + list_entry_name(i);
    }
  }
  return {};
}

// Each snapshot's K from its stored arrays, checked first (rows_from_csr): a crafted file with a
// valid checksum must not reach Eigen with an index out of range.
void contact_rows_of(SnapshotSet& set, const SnapshotTables& t) {
  const auto n_c = static_cast<Eigen::Index>(set.contact_dofs.size());
  for (std::size_t i = 0; i < set.snapshots.size(); ++i) {
    if (t.K[i].indptr.empty()) continue;
    try {
      set.snapshots[i].K = rows_from_csr(t.K[i], n_c, "/snapshots/" + list_entry_name(i));
    } catch (const Error& e) {
      throw H5Failure{e.what()};
    }
  }
}

// ---------------------------------------------------------------------------- writing

// A new temporary file next to the target (common/output_file.hpp); temporaries of killed
// writers are removed first.
std::string temporary_name(const std::string& path) {
  check_output_target(path);
  remove_stale_temporaries(path);
  return temporary_path(path).string();
}

void write_file(const std::string& tmp, const SnapshotSet& set) {
  const Handle fcpl = hdf5::sealed_file_properties();
  Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_EXCL, fcpl.get(), H5P_DEFAULT), H5Fclose,
              "cannot create the file (is the directory there and writable?)");
  const hid_t f = file.get();
  hdf5::write_string_attribute(f, "description",
                               "contactrb snapshot set (HF solutions over a parameter set); layout: docs/file-formats.md");
  FieldChecksum sum;
  hdf5::FieldWriter w(sum);
  SnapshotTables tables = tables_of(set);
  visit(w, Loc{f, ""}, set, tables);
  hdf5::write_number_attribute(f, "checksum", sum.value(), H5T_STD_U64LE, H5T_NATIVE_UINT64);
  // Written last: a file without it is an interrupted write.
  hdf5::write_number_attribute(f, "complete", 1, H5T_STD_I32LE, H5T_NATIVE_INT);
  file.close("cannot flush and close the file");
}

// ---------------------------------------------------------------------------- reading

int read_int_attribute(hid_t loc, const std::string& name) {
  return hdf5::read_number_attribute<int>(loc, name, H5T_NATIVE_INT, H5T_INTEGER);
}

// The `format` of a reduced model file before model format 5 is a dataset of bytes, not an
// attribute: recognized here to say what the file is.
bool has_model_format(hid_t file) {
  if (H5Lexists(file, "format", H5P_DEFAULT) <= 0) return false;
  hsize_t dims[1] = {0};
  try {  // open_dataset refuses a group or another shape with a Failure
    Handle set = hdf5::open_dataset(file, "format", 1, H5T_INTEGER, dims, 1);
    const std::string expected = kReducedModelFormatName;
    if (dims[0] != expected.size()) return false;
    std::string value(expected.size(), '\0');
    check(H5Dread(set.get(), H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, value.data()), "format");
    return value == expected;
  } catch (const H5Failure&) {
    return false;
  }
}

[[noreturn]] void refuse_model_file(const std::string& name) {
  throw Error(name + " is a contactrb reduced model file, not a snapshot file (a model is read by `contactrb online` "
                     "and `contactrb evaluate`)");
}

// Checks before HDF5 opens the file; true when its seal is valid (common/file_seal.hpp).
bool check_path(const std::string& path, const std::string& name) {
  check_input_file(path, "snapshot file", InputKind::Hdf5);  // a regular file below the size limit
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  if (is_hdf5 == 0) throw Error(name + " is not an HDF5 file (expected a file written by `contactrb snapshots`)");
  if (is_hdf5 < 0) throw Error(name + " cannot be read (" + hdf5::reason() + ")");
  // Before HDF5 parses anything: a sealed file whose bytes changed.
  const SealState seal = check_seal(path);
  if (seal == SealState::Mismatch) {
    throw Error(name + " is truncated or damaged: checksum mismatch: its bytes changed after it was written");
  }
  return seal == SealState::Valid;
}

Handle open_file(const std::string& path, const std::string& name) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create file access properties");
  check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "cannot set the close degree");
  try {
    return Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose, "HDF5 cannot open it");
  } catch (const H5Failure& f) {
    throw Error(name + " is truncated or damaged: " + f.what);
  }
}

// What a file of another snapshot format version gets: its version and the command that
// writes the current one.
std::string version_message(int version) {
  const std::string current = std::to_string(kSnapshotFormatVersion);
  const std::string again = ": generate the snapshots again with `contactrb snapshots`";
  if (version > kSnapshotFormatVersion) {
    return "snapshot format " + std::to_string(version) + " is newer than this build reads (format " + current + ")" +
           again;
  }
  return "snapshot format " + std::to_string(version) + " is no longer read (this build reads formats " +
         std::to_string(kSnapshotFormatOldestRead) + " to " + current + ")" + again;
}

// A file whose `format` is a variable-length string (snapshot format 4 and model format 5 and
// before), told from the attribute's type alone: its strings are never read (hdf5_fields.hpp,
// fixed_string_type). The integer `format_version` names the version.
[[noreturn]] void refuse_variable_length_file(hid_t file, const std::string& name) {
  if (H5Lexists(file, "meta", H5P_DEFAULT) > 0) refuse_model_file(name);
  if (H5Lexists(file, "snapshots", H5P_DEFAULT) <= 0) {
    throw Error(name + " is an HDF5 file but not a contactrb snapshot file of a format this build reads");
  }
  int version = -1;
  try {
    version = read_int_attribute(file, "format_version");
  } catch (const H5Failure& f) {
    throw Error(name + " is a snapshot file of an older format without a valid format version: " + f.what);
  }
  if (version >= kSnapshotFormatOldestRead && version <= kSnapshotFormatVersion) {
    throw Error(name + " is damaged: its 'format' is a variable-length string, which format " +
                std::to_string(version) + " never stores (not read)");
  }
  throw Error(name + ": " + version_message(version));
}

// The format, its version, the seal and the `complete` mark of an open file.
void check_header(hid_t file, const std::string& name, bool sealed) {
  if (H5Aexists(file, "format") <= 0) {
    if (has_model_format(file)) refuse_model_file(name);
    throw Error(name + " is an HDF5 file but not a contactrb snapshot file (no 'format' attribute)");
  }
  if (hdf5::is_vlen_string_attribute(file, "format")) refuse_variable_length_file(file, name);
  std::string format;
  try {
    format = hdf5::read_string_attribute(file, "format");
  } catch (const H5Failure& f) {
    if (!sealed) throw Error(name + " is damaged or not written by contactrb (" + f.what + ")");
    format = "(unreadable)";
  }
  if (format == kReducedModelFormatName) refuse_model_file(name);
  if (format != kSnapshotFormatName) {
    throw Error(name + " is an HDF5 file of another format ('" + format + "', expected '" + kSnapshotFormatName + "')");
  }
  int version = -1;
  try {
    version = read_int_attribute(file, "format_version");
  } catch (const H5Failure& f) {
    throw Error(name + " has no valid format version: " + f.what);
  }
  if (version < kSnapshotFormatOldestRead || version > kSnapshotFormatVersion) {
    throw Error(name + ": " + version_message(version));
  }
  // Every file of this version is sealed by its writer: no seal, its first bytes were damaged.
  if (!sealed) throw Error(name + " is damaged: its seal (the first bytes of the file) is missing");
  // `complete` = 1 is written last; any other value (0, a damaged one) is not a finished write.
  if (H5Aexists(file, "complete") <= 0 || read_int_attribute(file, "complete") != 1) {
    throw Error(name + " is incomplete (the run that wrote it was interrupted): generate it again");
  }
}

// Every field, the checksum over them and the agreement of the two copies; throws H5Failure.
SnapshotSet read_contents(hid_t file) {
  const auto stored = hdf5::read_number_attribute<std::uint64_t>(file, "checksum", H5T_NATIVE_UINT64, H5T_INTEGER);
  FieldChecksum sum;
  hdf5::FieldReader r(sum);
  SnapshotSet set;
  SnapshotTables tables;
  visit(r, Loc{file, ""}, set, tables);
  if (stored != sum.value()) throw H5Failure{"checksum mismatch: the file was modified or damaged after it was written"};
  const std::string inconsistency = first_inconsistency(set, tables);
  if (!inconsistency.empty()) throw H5Failure{inconsistency};
  contact_rows_of(set, tables);
  return set;
}

}  // namespace

bool is_snapshot_file(const std::string& path) {
  const QuietHdf5 quiet;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || H5Fis_hdf5(path.c_str()) <= 0) return false;
  try {
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "cannot open");
    if (H5Aexists(file.get(), "format") <= 0) return false;
    // An older snapshot file (a variable-length `format`, never read): told by its groups.
    if (hdf5::is_vlen_string_attribute(file.get(), "format")) {
      return H5Lexists(file.get(), "snapshots", H5P_DEFAULT) > 0 && H5Lexists(file.get(), "meta", H5P_DEFAULT) <= 0;
    }
    return hdf5::read_string_attribute(file.get(), "format") == kSnapshotFormatName;
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
    write_file(tmp, set);
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
  const QuietHdf5 quiet;
  const bool sealed = check_path(path, name);
  try {
    Handle file = open_file(path, name);
    check_header(file.get(), name, sealed);
    SnapshotSet set;
    try {
      set = read_contents(file.get());
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
