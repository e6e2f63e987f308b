#pragma once
// Elementary compression (Remark 7): constraints never active on the training set are dropped
// from K(mu, u) and g(mu, u) (their rows) and from the multiplier snapshots.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace contactrb::offline {

struct CompressionSettings {
  bool enabled = true;     // off: every constraint is kept (the report still counts the active ones)
  double threshold = 0.0;  // constraint r is active for mu when lambda_r(mu) > threshold (absolute)
};

struct Compression {
  std::vector<int> kept;  // constraint indices kept, increasing (all of them when disabled)
  int total = 0;          // number of constraints before compression
  int active = 0;         // constraints active for at least one snapshot
};

// multipliers: R x P (one snapshot per column), finite. Throws contactrb::Error otherwise or for
// a negative / non-finite threshold.
Compression compress_constraints(const Eigen::MatrixXd& multipliers, const CompressionSettings& settings = {});
// Indices r with lambda_r(mu) > threshold for at least one column.
std::vector<int> active_constraints(const Eigen::MatrixXd& multipliers, double threshold = 0.0);
// The given rows, in the given order. Throws for an index outside [0, rows).
Eigen::MatrixXd restrict_rows(const Eigen::MatrixXd& A, const std::vector<int>& rows);
Eigen::VectorXd restrict_rows(const Eigen::VectorXd& v, const std::vector<int>& rows);
// The same rows of a sparse matrix, dense (a snapshot's K on the kept rows).
Eigen::MatrixXd restrict_rows(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A, const std::vector<int>& rows);

}  // namespace contactrb::offline
