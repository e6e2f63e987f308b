#pragma once
// Independent truths for the non-negative QP tests: brute-force enumeration of the faces of
// the orthant, a relative KKT checker and random problem generators.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "contactrb/solve/nonnegative_qp.hpp"

namespace qpref {

inline double objective(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c, const Eigen::VectorXd& x) {
  return 0.5 * x.dot(Q * x) - c.dot(x);
}

// Magnitude of the terms of f at x: the scale for relative comparisons of objectives.
inline double objective_scale(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c, const Eigen::VectorXd& x) {
  return 0.5 * x.cwiseAbs().dot(Q.cwiseAbs() * x.cwiseAbs()) + c.cwiseAbs().dot(x.cwiseAbs());
}

struct Reference {
  double f = 0.0;
  Eigen::VectorXd x;
};

// Minimum of f over x >= 0 for a bounded problem, by enumeration of all 2^n faces {x_A = 0}:
// some minimizer has a support P with Q_PP nonsingular (move along a null vector of Q_PP,
// on which f is constant at a face minimizer, until a component vanishes), so faces with a
// singular Q_PP are skipped; every candidate is a feasible point, evaluated directly.
inline Reference brute_force(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c) {
  const int n = static_cast<int>(Q.rows());
  Reference best;
  best.x = Eigen::VectorXd::Zero(n);
  best.f = 0.0;
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    std::vector<int> P;
    for (int i = 0; i < n; ++i)
      if (mask & (1u << i)) P.push_back(i);
    const int p = static_cast<int>(P.size());
    Eigen::MatrixXd QPP(p, p);
    Eigen::VectorXd cP(p);
    for (int a = 0; a < p; ++a) {
      cP[a] = c[P[a]];
      for (int b = 0; b < p; ++b) QPP(a, b) = Q(P[a], P[b]);
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(QPP);
    lu.setThreshold(1e-10);
    if (lu.rank() < p) continue;
    const Eigen::VectorXd z = lu.solve(cP);
    if (z.minCoeff() < -1e-12 * std::max(1.0, z.cwiseAbs().maxCoeff())) continue;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    for (int a = 0; a < p; ++a) x[P[a]] = std::max(z[a], 0.0);
    const double f = objective(Q, c, x);
    if (f < best.f) best.f = f, best.x = x;
  }
  return best;
}

// True when the KKT residuals of x are below tol relative to the scales of the problem.
inline ::testing::AssertionResult kkt_ok(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c,
                                         const Eigen::VectorXd& x, double tol = 1e-10) {
  const auto k = contactrb::solve::kkt_residuals(Q, c, x);
  const double xmax = x.size() ? x.cwiseAbs().maxCoeff() : 0.0;
  const double qn = Q.size() ? Q.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  const double s = std::max(c.size() ? c.cwiseAbs().maxCoeff() : 0.0, qn * xmax);
  if (k.primal <= tol * xmax && k.dual <= tol * s && k.complementarity <= tol * s * xmax)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "KKT residuals primal " << k.primal << " dual " << k.dual << " complementarity "
         << k.complementarity << " scale " << s << " |x| " << xmax;
}

inline Eigen::MatrixXd randn(std::mt19937& rng, int r, int c) {
  std::normal_distribution<double> N(0.0, 1.0);
  Eigen::MatrixXd A(r, c);
  for (int j = 0; j < c; ++j)
    for (int i = 0; i < r; ++i) A(i, j) = N(rng);
  return A;
}

inline Eigen::MatrixXd gram(const Eigen::MatrixXd& B) {
  Eigen::MatrixXd Q = B.transpose() * B;
  return 0.5 * (Q + Q.transpose());
}

}  // namespace qpref
