#include "contactrb/offline/eim_flatten.hpp"

#include <string>

#include "contactrb/common/error.hpp"

namespace contactrb::offline {

Eigen::MatrixXd flatten_columns(const std::vector<Eigen::MatrixXd>& matrices) {
  if (matrices.empty()) return Eigen::MatrixXd(0, 0);
  const Eigen::Index R = matrices.front().rows(), n_c = matrices.front().cols();
  Eigen::MatrixXd F(R * n_c, static_cast<Eigen::Index>(matrices.size()));
  for (std::size_t p = 0; p < matrices.size(); ++p) {
    const Eigen::MatrixXd& K = matrices[p];
    require(K.rows() == R && K.cols() == n_c,
            "flatten_columns: matrix " + std::to_string(p) + " is " + std::to_string(K.rows()) + "x" +
                std::to_string(K.cols()) + " but matrix 0 is " + std::to_string(R) + "x" + std::to_string(n_c));
    for (Eigen::Index r = 0; r < R; ++r)
      for (Eigen::Index n = 0; n < n_c; ++n) F(r * n_c + n, static_cast<Eigen::Index>(p)) = K(r, n);
  }
  return F;
}

Eigen::MatrixXd unflatten_column(const Eigen::VectorXd& column, Eigen::Index R, Eigen::Index n_c) {
  require(R >= 0 && n_c >= 0 && column.size() == R * n_c,
          "unflatten_column: a column of size " + std::to_string(column.size()) + " cannot be " +
              std::to_string(R) + "x" + std::to_string(n_c));
  Eigen::MatrixXd K(R, n_c);
  for (Eigen::Index r = 0; r < R; ++r)
    for (Eigen::Index n = 0; n < n_c; ++n) K(r, n) = column(r * n_c + n);
  return K;
}

std::pair<int, int> unflatten_index(int row, int n_c) {
  require(n_c > 0 && row >= 0, "unflatten_index: need n_c > 0 and row >= 0, got row " + std::to_string(row) +
                                   " and n_c " + std::to_string(n_c));
  return {row / n_c, row % n_c};
}

}  // namespace contactrb::offline
