#include "contactrb/offline/row_cone.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace contactrb::offline {

DualConeResult build_row_cone(const Eigen::MatrixXd& snapshots, const DualConeSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  check_dual_snapshots("build_row_cone", snapshots, settings.weights);
  const Eigen::Index R = snapshots.rows(), P = snapshots.cols();
  const Eigen::VectorXd w = settings.weights.size() == R ? settings.weights : Eigen::VectorXd::Ones(R);
  DualConeResult out;
  out.method = DualConeMethod::Rows;
  out.status = GreedyStatus::Exhausted;
  out.generators = Eigen::MatrixXd::Identity(R, R);
  out.errors.assign(static_cast<std::size_t>(R + 1), 0.0);
  out.relative_errors.assign(static_cast<std::size_t>(R + 1), 0.0);
  out.selected.assign(static_cast<std::size_t>(R), 0);
  for (Eigen::Index k = 0; k < R; ++k) {
    for (Eigen::Index p = 0; p < P; ++p) {
      if (snapshots(k, p) > 0.0) {
        out.selected[static_cast<std::size_t>(k)] = static_cast<int>(p);
        break;
      }
    }
  }
  for (Eigen::Index p = 0; p < P; ++p) {
    const double total = std::sqrt(w.dot(snapshots.col(p).cwiseAbs2()));
    double tail2 = 0.0;  // |lambda_p on rows >= k|^2, k from R down to 0
    for (Eigen::Index k = R; k >= 0; --k) {
      if (k < R) tail2 += w(k) * snapshots(k, p) * snapshots(k, p);
      const double e = std::sqrt(tail2);
      auto& err = out.errors[static_cast<std::size_t>(k)];
      auto& rel = out.relative_errors[static_cast<std::size_t>(k)];
      err = std::max(err, e);
      rel = std::max(rel, total > 0.0 ? e / total : 0.0);
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace contactrb::offline
