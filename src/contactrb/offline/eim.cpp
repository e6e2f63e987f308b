#include "contactrb/offline/eim.hpp"

#include <chrono>
#include <cmath>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::offline {

void check_settings(const EIMSettings& s) {
  require(std::isfinite(s.tolerance) && s.tolerance >= 0.0,
          "eim: tolerance must be finite and >= 0, got " + number_text(s.tolerance));
  require(s.max_size >= -1, "eim: max_size must be >= -1 (-1: no limit), got " + std::to_string(s.max_size));
  require(std::isfinite(s.rank_tolerance) && s.rank_tolerance >= 0.0 && s.rank_tolerance < 1.0,
          "eim: rank_tolerance must lie in [0, 1), got " + number_text(s.rank_tolerance));
}

EIMProblem::EIMProblem(const Eigen::MatrixXd& F) : residual_(F), Q_(F.rows(), 0), norms_(F.cols()) {
  require(F.allFinite(), "eim: the snapshot matrix F (" + std::to_string(F.rows()) + "x" +
                             std::to_string(F.cols()) + ") has non-finite entries");
  for (Eigen::Index p = 0; p < F.cols(); ++p) norms_(p) = F.rows() ? F.col(p).cwiseAbs().maxCoeff() : 0.0;
}

Eigen::VectorXd EIMProblem::evaluate() {
  Eigen::VectorXd e(residual_.cols());
  for (Eigen::Index p = 0; p < residual_.cols(); ++p)
    e(p) = residual_.rows() ? residual_.col(p).cwiseAbs().maxCoeff() : 0.0;
  return e;
}

void EIMProblem::extend(int index) {
  require(index >= 0 && index < training_size(), "EIMProblem::extend: index " + std::to_string(index) +
                                                     " outside the training set of size " +
                                                     std::to_string(training_size()));
  const Eigen::VectorXd r = residual_.col(index);
  Eigen::Index x = 0;
  for (Eigen::Index i = 1; i < r.size(); ++i)
    if (std::abs(r(i)) > std::abs(r(x))) x = i;
  require(r.size() > 0 && r(x) != 0.0, "EIMProblem::extend: the residual of parameter " + std::to_string(index) +
                                           " vanishes (nothing left to interpolate)");
  Eigen::VectorXd q = r / r(x);
  for (int xi : magic_) q(xi) = 0.0;  // exact zeros at the earlier magic points (round-off)
  q(x) = 1.0;
  const Eigen::Index m = Q_.cols();
  Q_.conservativeResize(Eigen::NoChange, m + 1);
  Q_.col(m) = q;
  magic_.push_back(static_cast<int>(x));
  // r_{m+1}(mu) = r_m(mu) - r_m(mu)(x) q_{m+1}: vanishes at x_1 .. x_{m+1}.
  const Eigen::RowVectorXd at_x = residual_.row(x);
  residual_.noalias() -= q * at_x;
  for (int xi : magic_) residual_.row(xi).setZero();
}

EIMResult eim(const Eigen::MatrixXd& F, const EIMSettings& settings) {
  check_settings(settings);
  const auto t0 = std::chrono::steady_clock::now();
  EIMProblem problem(F);
  GreedySettings g;
  const double largest = F.size() > 0 ? F.cwiseAbs().maxCoeff() : 0.0;
  g.tolerance = settings.relative ? settings.tolerance * largest : settings.tolerance;
  g.max_size = settings.max_size;
  g.exhaustion_tolerance = settings.rank_tolerance;
  const GreedyResult gr = run_greedy(problem, g);
  EIMResult out;
  out.status = gr.status;
  out.selected = gr.selected;
  out.magic_points = problem.magic_points();
  out.Q = problem.basis();
  out.errors = gr.max_errors;
  out.threshold = g.tolerance;
  const Eigen::Index M = out.Q.cols();
  out.B.resize(M, M);
  for (Eigen::Index i = 0; i < M; ++i) out.B.row(i) = out.Q.row(out.magic_points[static_cast<std::size_t>(i)]);
  if (M > 0) out.lu.compute(out.B);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

Eigen::VectorXd EIMResult::interpolate(const Eigen::VectorXd& values) const {
  const Eigen::Index m = values.size();
  require(m <= B.rows(), "EIMResult::interpolate: " + std::to_string(m) + " values but only " +
                             std::to_string(B.rows()) + " magic points");
  if (m == B.rows()) return m ? Eigen::VectorXd(lu.solve(values)) : Eigen::VectorXd(0);
  // Leading block of a unit lower-triangular matrix: forward substitution.
  return B.topLeftCorner(m, m).triangularView<Eigen::UnitLower>().solve(values);
}

Eigen::VectorXd EIMResult::evaluate(const Eigen::VectorXd& coefficients) const {
  require(coefficients.size() <= Q.cols(), "EIMResult::evaluate: " + std::to_string(coefficients.size()) +
                                               " coefficients but only " + std::to_string(Q.cols()) +
                                               " basis functions");
  return Q.leftCols(coefficients.size()) * coefficients;
}

Eigen::VectorXd EIMResult::restrict(const Eigen::VectorXd& f) const {
  require(f.size() == Q.rows(), "EIMResult::restrict: f has size " + std::to_string(f.size()) + " but F has " +
                                    std::to_string(Q.rows()) + " rows");
  Eigen::VectorXd v(static_cast<Eigen::Index>(magic_points.size()));
  for (std::size_t i = 0; i < magic_points.size(); ++i) v(static_cast<Eigen::Index>(i)) = f(magic_points[i]);
  return v;
}

}  // namespace contactrb::offline
