#pragma once
// Synthetic multiplier snapshots shared by the offline tests (no HF solve needed).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace offline_fixtures {

// "Hertz-like" contact pressures: lambda(mu)(x) = sqrt(max(0, a(mu)^2 - x^2)) on n points of
// [-1, 1], contact half-width a(mu) growing with mu over P parameters.
inline Eigen::MatrixXd hertz_like_snapshots(int n = 51, int P = 31) {
  Eigen::MatrixXd S(n, P);
  for (int p = 0; p < P; ++p) {
    const double mu = 0.15 + 0.01 * p;
    const double a = 0.2 + 1.5 * mu;  // 0.425 .. 0.875
    for (int i = 0; i < n; ++i) {
      const double x = -1.0 + 2.0 * i / (n - 1);
      S(i, p) = std::sqrt(std::max(0.0, a * a - x * x)) * (1.0 + mu);
    }
  }
  return S;
}

// Lambda-norm weights |I_r| of a uniform collocation grid on [-1, 1] (half edges at the ends).
inline Eigen::VectorXd collocation_weights(int n = 51) {
  const double h = 2.0 / (n - 1);
  Eigen::VectorXd w = Eigen::VectorXd::Constant(n, h);
  w(0) = w(n - 1) = 0.5 * h;
  return w;
}

}  // namespace offline_fixtures
