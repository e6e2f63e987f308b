#pragma once
// A snapshot's contact rows K (io::SnapshotRows) as compressed-row arrays, the layout of the
// snapshot file (docs/file-formats.md, "Snapshot file") and of the MPI messages: scipy's
// csr_matrix((data, indices, indptr), shape=(R, n_c)) reads them as they are.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "contactrb/io/snapshot_file.hpp"

namespace contactrb::io {

struct CsrArrays {
  std::vector<int> indptr;   // R + 1: row r holds entries indptr[r] .. indptr[r + 1] - 1
  std::vector<int> indices;  // nnz: the column of each entry, ascending within a row
  std::vector<double> data;  // nnz: the value of each entry
};

// The arrays of K (every stored entry, as stored; an empty K gives empty arrays).
CsrArrays csr_of(const SnapshotRows& K);

// K from its arrays, with `cols` columns. Throws contactrb::Error naming `where` + "/K_indptr",
// "/K_indices" or "/K_data" when the arrays do not describe a matrix: indptr empty, not starting
// at 0, decreasing, or not ending at the length of indices and data; a column outside [0, cols)
// or not above the previous one of its row. Values are not checked (check_snapshot_set does,
// for a converged snapshot).
SnapshotRows rows_from_csr(const CsrArrays& a, Eigen::Index cols, const std::string& where);

// The non-zero entries of a dense K (the layout of snapshot formats 5 to 7).
SnapshotRows rows_from_dense(const Eigen::MatrixXd& K);

}  // namespace contactrb::io
