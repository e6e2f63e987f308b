#pragma once
// Snapshot files (HDF5): the high-fidelity solutions of one case over one parameter set,
// with everything the offline stage needs (POD of u_0, the dual cone of lambda, the EIM of
// the gap and of the contact map on the contact-surface DOFs). Layout: docs/file-formats.md.
//
// Writing goes to a temporary file next to the target that is renamed over it at the end;
// the root attribute `complete` is written last. A reader therefore never takes an
// interrupted run for a finished one.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::io {

inline constexpr const char* kSnapshotFormatName = "contactrb-snapshots";
// Version 2: a checksum over every field and every index and value checked on reading.
// Version 3: p parameters (a point mu in R^p per snapshot; each parameter's name, kind, units
// and domain). Version 4: the self-describing layout (strings as variable-length UTF-8
// attributes, `shape_meaning` and `units` on every dataset) and the reference mesh in /mesh
// (docs/file-formats.md). Version 5: every string a fixed-length UTF-8 attribute (no
// variable-length data, which HDF5 1.10 cannot read safely from a damaged file). Version 6: the
// root attribute `dimension` (2 or 3) and a 3D mesh in /mesh; a version 5 file is read as 2D.
// Version 7: /settings `solver` (the HF method of the solves); a version 5 or 6 file is read as
// Kacanov, the only method those versions were written with.
// Version 8: each snapshot's K in compressed sparse rows (K_indptr, K_indices, K_data); the dense
// K of versions 5 to 7 is converted on reading.
// Older versions are refused with their version named: generate them again.
inline constexpr int kSnapshotFormatVersion = 8;
// The oldest version this build reads (kSnapshotFormatVersion and this one).
inline constexpr int kSnapshotFormatOldestRead = 5;

// What a snapshot file records of each parameter (cases::ParameterSpec, without the case).
struct SnapshotParameter {
  std::string name;
  std::string kind;   // cases::to_string(ParameterKind)
  std::string units;
  double min = 0.0;
  double max = 0.0;
};

// A snapshot's contact rows: a few non-zeros per row (the DOFs of one slave node and of the
// master facet it projects on), compressed, column indices ascending in each row.
using SnapshotRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// The outcome of one HF solve at one parameter value. A failed solve keeps whatever the
// solver returned (a non-converged solve: its last iterate; an exception: no arrays).
struct Snapshot {
  Eigen::VectorXd mu;  // one value per parameter
  bool converged = false;
  std::string status;   // solve::to_string(KacanovStatus) ("converged", "max_iterations",
                        // "step_failed") or "exception" (building or solving threw)
  std::string message;  // why it failed (empty when converged)
  int iterations = 0;   // Kacanov iterations
  double time_s = 0.0;      // problem construction + HF setup + solve, wall clock
  double cpu_time_s = 0.0;  // the same, CPU time of the thread that did it (load independent)

  Eigen::VectorXd u0;      // free part of the displacement (num_free, order of free_dofs)
  Eigen::VectorXd u;       // total displacement u_D + u_0 (num_dofs)
  Eigen::VectorXd lambda;  // contact pressures, one per constraint row (R)
  SnapshotRows K;          // contact rows K(w) on the contact DOF columns (R x n_c)
  Eigen::VectorXd g;       // gap rows g(w) (R)
  Eigen::VectorXd weight;  // |I_r| (R): depends on mu when the slave body is mapped
  Eigen::VectorXd gap_pointwise;  // pointwise gap g(w)_s of the slave nodes (S)
};

// A snapshot set: the case, the parameter set and one Snapshot per parameter value,
// in the order of the set.
struct SnapshotSet {
  // Case specification: for a built-in case, case_spec is its name (kind "builtin");
  // for any other case, its TOML text (kind "toml", cases::to_toml: self-contained, read
  // back by cases::case_from_toml_string).
  std::string case_name;
  std::string case_kind;  // "builtin" | "toml"
  std::string case_spec;
  int level = 0;           // mesh refinement level (0: the paper's mesh)
  std::string constraint;  // "collocation" | "lac" | "lac-simpson"

  std::vector<SnapshotParameter> parameters;  // p >= 1, in the order of each snapshot's mu
  std::string set_name;  // "training", "verification" or "custom"

  // The HF method of the solves: "kacanov" | "newton" (hf::to_string(hf::HFMethod)).
  std::string solver = "kacanov";
  // Kacanov settings the solves used (recorded whatever the method).
  double kacanov_alpha = 0.0;
  double kacanov_tolerance = 0.0;
  int kacanov_max_iterations = 0;

  // The space dimension of the mesh and of every displacement: 2 (triangles, 2 components per
  // node) or 3 (tetrahedra, 3 components per node).
  int dimension = 2;

  // Discretization, identical for every mu (one reference mesh, mapped).
  int num_dofs = 0;
  std::vector<int> free_dofs;     // global index of each entry of u0
  std::vector<int> contact_dofs;  // global index of each column of K (every component of
                                  // every slave and master node, ascending)
  std::vector<int> slave;         // 2D: slave chain; 3D: slave nodes, sorted (mesh node indices)
  std::vector<int> master;        // 2D: master chain (closed: first node repeated at the end);
                                  // 3D: master nodes, sorted
  // The reference mesh of these DOFs (level `level`), stored in /mesh so that no .msh file is
  // needed later; empty when unknown (a set built by hand, or no solve got a discretization).
  // `mesh` in 2D, `mesh3` in 3D; the other one stays empty.
  mesh::Mesh mesh;
  mesh::Mesh3 mesh3;

  std::vector<Snapshot> snapshots;

  int num_failed() const;
};

// Writes `set` to `path` atomically (temporary file + rename). Throws contactrb::Error
// naming `path` when the file cannot be written or the set is inconsistent (array sizes
// against num_dofs, free_dofs, contact_dofs).
void write_snapshot_file(const SnapshotSet& set, const std::string& path);

// Reads a file written by write_snapshot_file. Throws contactrb::Error naming `path` for a
// missing file, a file that is not HDF5, an HDF5 file of another format (a reduced model
// file is named as such), another format version, an incomplete one (an interrupted write:
// `complete` missing or not 1), a truncated or damaged file (a group, dataset or attribute
// missing or of the wrong shape, a checksum mismatch), compressed rows of K that describe no
// matrix (io/snapshot_rows.hpp, rows_from_csr), or contents that fail check_snapshot_set.
SnapshotSet read_snapshot_file(const std::string& path);

// Throws contactrb::Error naming the first field (by its path in the file) that is
// inconsistent: an index of free_dofs, slave or master outside its range, negative or
// repeated; contact_dofs other than both components of the contact nodes, ascending; an
// array size against num_dofs, free_dofs, contact_dofs or the slave chain; a non-finite value
// in an array of a converged snapshot; no parameter, a mu of the wrong size or outside the
// stored domains, a domain that is not an interval; a status that disagrees with `converged`; invalid Kacanov
// settings; a solver other than kacanov or newton. Run by the writer, the reader and offline::build_reduced_model.
void check_snapshot_set(const SnapshotSet& set);

// True when `path` is an HDF5 file whose root attribute `format` is kSnapshotFormatName
// (whatever its version or state); false otherwise, never throws. Lets other readers say
// what a file is when it is given in the wrong place.
bool is_snapshot_file(const std::string& path);

}  // namespace contactrb::io
