#include "contactrb/io/snapshot_rows.hpp"

#include <cstddef>

#include "contactrb/common/error.hpp"

namespace contactrb::io {

namespace {

[[noreturn]] void invalid(const std::string& what) { throw Error(what); }

// indptr: 0 first, non-decreasing, nnz last (the length of indices and of data).
void check_row_pointers(const CsrArrays& a, const std::string& where) {
  if (a.indptr.empty()) invalid(where + "/K_indptr is empty (expected R + 1 entries)");
  if (a.indptr.front() != 0) {
    invalid(where + "/K_indptr[0] = " + std::to_string(a.indptr.front()) + " (expected 0)");
  }
  for (std::size_t r = 1; r < a.indptr.size(); ++r) {
    if (a.indptr[r] < a.indptr[r - 1]) {
      invalid(where + "/K_indptr[" + std::to_string(r) + "] = " + std::to_string(a.indptr[r]) +
              " is below the entry before it (row pointers never decrease)");
    }
  }
  const auto nnz = static_cast<std::size_t>(a.indptr.back());
  if (nnz != a.indices.size() || nnz != a.data.size()) {
    invalid(where + "/K_indptr ends at " + std::to_string(nnz) + " entries, K_indices holds " +
            std::to_string(a.indices.size()) + " and K_data " + std::to_string(a.data.size()));
  }
}

// Every column in [0, cols), ascending within its row (no entry twice).
void check_columns(const CsrArrays& a, Eigen::Index cols, const std::string& where) {
  for (std::size_t r = 0; r + 1 < a.indptr.size(); ++r) {
    const auto begin = static_cast<std::size_t>(a.indptr[r]), end = static_cast<std::size_t>(a.indptr[r + 1]);
    for (std::size_t k = begin; k < end; ++k) {
      const int c = a.indices[k];
      if (c < 0 || c >= cols) {
        invalid(where + "/K_indices[" + std::to_string(k) + "] = " + std::to_string(c) + " is outside [0, n_c = " +
                std::to_string(cols) + ")");
      }
      if (k > begin && c <= a.indices[k - 1]) {
        invalid(where + "/K_indices[" + std::to_string(k) + "] = " + std::to_string(c) +
                " is not above the column before it in row " + std::to_string(r) +
                " (columns ascend within a row, none twice)");
      }
    }
  }
}

}  // namespace

CsrArrays csr_of(const SnapshotRows& K) {
  CsrArrays a;
  if (K.rows() == 0 && K.cols() == 0) return a;
  a.indptr.reserve(static_cast<std::size_t>(K.rows()) + 1);
  a.indices.reserve(static_cast<std::size_t>(K.nonZeros()));
  a.data.reserve(static_cast<std::size_t>(K.nonZeros()));
  a.indptr.push_back(0);
  for (Eigen::Index r = 0; r < K.outerSize(); ++r) {
    for (SnapshotRows::InnerIterator it(K, r); it; ++it) {
      a.indices.push_back(static_cast<int>(it.col()));
      a.data.push_back(it.value());
    }
    a.indptr.push_back(static_cast<int>(a.indices.size()));
  }
  return a;
}

SnapshotRows rows_from_csr(const CsrArrays& a, Eigen::Index cols, const std::string& where) {
  check_row_pointers(a, where);
  check_columns(a, cols, where);
  const auto rows = static_cast<Eigen::Index>(a.indptr.size() - 1);
  const auto nnz = static_cast<Eigen::Index>(a.data.size());
  return Eigen::Map<const SnapshotRows>(rows, cols, nnz, a.indptr.data(), a.indices.data(), a.data.data());
}

SnapshotRows rows_from_dense(const Eigen::MatrixXd& K) {
  SnapshotRows S(K.rows(), K.cols());
  Eigen::VectorXi per_row(K.rows());
  for (Eigen::Index r = 0; r < K.rows(); ++r) per_row(r) = static_cast<int>((K.row(r).array() != 0.0).count());
  S.reserve(per_row);
  for (Eigen::Index r = 0; r < K.rows(); ++r) {
    for (Eigen::Index c = 0; c < K.cols(); ++c) {
      if (K(r, c) != 0.0) S.insert(r, c) = K(r, c);
    }
  }
  S.makeCompressed();
  return S;
}

}  // namespace contactrb::io
