#include "contactrb/offline/compression.hpp"

#include <cmath>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::offline {

namespace {
void check_rows(const char* who, Eigen::Index n, const std::vector<int>& rows) {
  for (int r : rows)
    require(r >= 0 && r < n, std::string(who) + ": row index " + std::to_string(r) + " outside [0, " +
                                 std::to_string(n) + ")");
}
}  // namespace

std::vector<int> active_constraints(const Eigen::MatrixXd& multipliers, double threshold) {
  require(multipliers.allFinite(), "active_constraints: the multipliers have non-finite entries");
  require(std::isfinite(threshold) && threshold >= 0.0,
          "active_constraints: threshold must be finite and >= 0, got " + number_text(threshold));
  std::vector<int> active;
  for (Eigen::Index r = 0; r < multipliers.rows(); ++r)
    if (multipliers.cols() > 0 && multipliers.row(r).maxCoeff() > threshold) active.push_back(static_cast<int>(r));
  return active;
}

Compression compress_constraints(const Eigen::MatrixXd& multipliers, const CompressionSettings& settings) {
  Compression c;
  c.total = static_cast<int>(multipliers.rows());
  const std::vector<int> active = active_constraints(multipliers, settings.threshold);
  c.active = static_cast<int>(active.size());
  if (settings.enabled) {
    c.kept = active;
  } else {
    c.kept.resize(static_cast<std::size_t>(c.total));
    for (int r = 0; r < c.total; ++r) c.kept[static_cast<std::size_t>(r)] = r;
  }
  return c;
}

Eigen::MatrixXd restrict_rows(const Eigen::MatrixXd& A, const std::vector<int>& rows) {
  check_rows("restrict_rows", A.rows(), rows);
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), A.cols());
  for (std::size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = A.row(rows[i]);
  return out;
}

Eigen::MatrixXd restrict_rows(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A, const std::vector<int>& rows) {
  check_rows("restrict_rows", A.rows(), rows);
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()), A.cols());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, rows[i]); it; ++it) {
      out(static_cast<Eigen::Index>(i), it.col()) = it.value();
    }
  }
  return out;
}

Eigen::VectorXd restrict_rows(const Eigen::VectorXd& v, const std::vector<int>& rows) {
  check_rows("restrict_rows", v.size(), rows);
  Eigen::VectorXd out(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) out(static_cast<Eigen::Index>(i)) = v(rows[i]);
  return out;
}

}  // namespace contactrb::offline
