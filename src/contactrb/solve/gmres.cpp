#include "contactrb/solve/gmres.hpp"

#include <cmath>
#include <vector>

namespace contactrb::solve {

GmresResult gmres(const LinearOperator& A, const LinearOperator& P_inverse, const Eigen::VectorXd& b, double tolerance,
                  int max_iterations, int restart) {
  GmresResult res;
  const Eigen::Index n = b.size();
  res.x = Eigen::VectorXd::Zero(n);
  const double b_norm = b.norm();
  if (b_norm == 0.0 || n == 0) {
    res.converged = true;
    return res;
  }
  if (!std::isfinite(b_norm)) return res;
  restart = std::max(1, restart);
  Eigen::VectorXd r = b;
  double beta = b_norm;
  while (res.iterations < max_iterations) {
    const int m = std::min(restart, max_iterations - res.iterations);
    Eigen::MatrixXd V(n, m + 1);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m + 1, m);
    std::vector<double> cs(static_cast<std::size_t>(m)), sn(static_cast<std::size_t>(m));
    Eigen::VectorXd g = Eigen::VectorXd::Zero(m + 1);
    V.col(0) = r / beta;
    g(0) = beta;
    int k = 0;
    bool breakdown = false;
    for (; k < m; ++k) {
      Eigen::VectorXd w = A(P_inverse(V.col(k)));
      ++res.iterations;
      if (!w.allFinite()) return res;
      for (int pass = 0; pass < 2; ++pass) {  // MGS, twice
        for (int i = 0; i <= k; ++i) {
          const double h = V.col(i).dot(w);
          H(i, k) += h;
          w -= h * V.col(i);
        }
      }
      const double h_next = w.norm();
      H(k + 1, k) = h_next;
      for (int i = 0; i < k; ++i) {  // the earlier rotations on the new column
        const double a = H(i, k), c = H(i + 1, k);
        H(i, k) = cs[static_cast<std::size_t>(i)] * a + sn[static_cast<std::size_t>(i)] * c;
        H(i + 1, k) = -sn[static_cast<std::size_t>(i)] * a + cs[static_cast<std::size_t>(i)] * c;
      }
      const double denom = std::hypot(H(k, k), H(k + 1, k));
      if (denom == 0.0) {
        breakdown = true;
        break;
      }
      cs[static_cast<std::size_t>(k)] = H(k, k) / denom;
      sn[static_cast<std::size_t>(k)] = H(k + 1, k) / denom;
      H(k, k) = denom;
      H(k + 1, k) = 0.0;
      g(k + 1) = -sn[static_cast<std::size_t>(k)] * g(k);
      g(k) = cs[static_cast<std::size_t>(k)] * g(k);
      if (std::abs(g(k + 1)) <= tolerance * b_norm || h_next == 0.0) {
        ++k;
        break;
      }
      V.col(k + 1) = w / h_next;
    }
    if (k > 0) {
      const Eigen::VectorXd y =
          H.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
      res.x += P_inverse(V.leftCols(k) * y);
    }
    r = b - A(res.x);
    beta = r.norm();
    res.relative_residual = beta / b_norm;
    if (!std::isfinite(beta)) return res;
    if (res.relative_residual <= tolerance) {
      res.converged = true;
      return res;
    }
    if (breakdown) return res;
  }
  return res;
}

}  // namespace contactrb::solve
