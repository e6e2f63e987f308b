#include "contactrb/offline/cone_projection.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <string>

#include "contactrb/common/error.hpp"

namespace contactrb::offline {

double weighted_norm(const Eigen::VectorXd& v, const Eigen::VectorXd& weights) {
  if (weights.size() == 0) return v.norm();
  return std::sqrt(std::max(0.0, (v.array().square() * weights.array()).sum()));
}

namespace {

std::string dims(Eigen::Index r, Eigen::Index c) { return std::to_string(r) + "x" + std::to_string(c); }

void check_weights(const char* who, const Eigen::VectorXd& weights, Eigen::Index dimension) {
  require(weights.size() == 0 || weights.size() == dimension,
          std::string(who) + ": weights have size " + std::to_string(weights.size()) +
              " but the vectors have size " + std::to_string(dimension) + " (must be empty or match)");
  require(weights.allFinite() && (weights.size() == 0 || weights.minCoeff() >= 0.0),
          std::string(who) + ": weights must be finite and >= 0");
}

// Polishing: least squares on the passive (face) columns by column-pivoted QR of
// diag(sqrt(w)) Xi_P, accepted when its coefficients are >= 0 and its residual is smaller. The QP
// works with the normal equations Q = Xi' M Xi, whose accuracy degrades as cond(Xi_P)^2 on nearly
// dependent faces; the QR solve on the same face degrades as cond(Xi_P) only. At the optimum the
// residual is M-orthogonal to the face, so a coefficient error dy changes the error norm only by
// ~ |Xi dy|^2 / (2 error): polishing matters only when the error is small against |x|_M
// (kPolishBelow), which keeps the greedies' evaluate step cheap.
constexpr double kPolishBelow = 1e-6;

void polish(const Eigen::MatrixXd& generators, const Eigen::VectorXd& weights, const Eigen::VectorXd& x,
            ConeProjection& out) {
  const auto k = static_cast<Eigen::Index>(out.passive.size());
  if (k == 0 || out.error > kPolishBelow * weighted_norm(x, weights)) return;
  Eigen::MatrixXd A(generators.rows(), k);
  for (Eigen::Index a = 0; a < k; ++a) A.col(a) = generators.col(out.passive[static_cast<std::size_t>(a)]);
  Eigen::VectorXd b = x;
  if (weights.size()) {
    const Eigen::VectorXd sq = weights.cwiseSqrt();
    A = sq.asDiagonal() * A;
    b = sq.cwiseProduct(x);
  }
  const Eigen::VectorXd y = A.colPivHouseholderQr().solve(b);
  if (!y.allFinite() || y.minCoeff() < 0.0) return;
  Eigen::VectorXd projection = Eigen::VectorXd::Zero(x.size());
  for (Eigen::Index a = 0; a < k; ++a)
    projection += y(a) * generators.col(out.passive[static_cast<std::size_t>(a)]);
  const double error = weighted_norm(x - projection, weights);
  if (!(error < out.error)) return;
  for (Eigen::Index a = 0; a < k; ++a) out.coefficients(out.passive[static_cast<std::size_t>(a)]) = y(a);
  out.projection = std::move(projection);
  out.error = error;
}

}  // namespace

ConeProjection project_onto_cone(const Eigen::MatrixXd& generators, const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& weights, const solve::QPSettings& qp) {
  check_weights("project_onto_cone", weights, x.size());
  require(generators.rows() == x.size(), "project_onto_cone: the generators are " +
                                             dims(generators.rows(), generators.cols()) + " but x has size " +
                                             std::to_string(x.size()));
  ConeProjection out;
  if (generators.cols() == 0) {
    require(x.allFinite(), "project_onto_cone: x has non-finite entries");
    out.coefficients = Eigen::VectorXd::Zero(0);
    out.projection = Eigen::VectorXd::Zero(x.size());
    out.error = weighted_norm(x, weights);
    return out;
  }
  const solve::QPResult r = solve::solve_nnls(generators, x, weights, qp);
  out.status = r.status;
  out.coefficients = r.x.cwiseMax(0.0);
  out.projection = generators * out.coefficients;
  out.error = weighted_norm(x - out.projection, weights);
  out.passive = r.passive;
  out.iterations = r.iterations;
  polish(generators, weights, x, out);
  return out;
}

double generator_condition_number(const Eigen::MatrixXd& generators, const Eigen::VectorXd& weights) {
  check_weights("generator_condition_number", weights, generators.rows());
  if (generators.cols() == 0) return 1.0;
  require(generators.allFinite(), "generator_condition_number: the generators have non-finite entries");
  Eigen::MatrixXd W = generators;
  if (weights.size() > 0) W = weights.cwiseSqrt().asDiagonal() * generators;
  if (W.rows() < W.cols()) return std::numeric_limits<double>::infinity();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(W);
  const Eigen::VectorXd& s = svd.singularValues();
  const double smax = s(0);
  const double smin = s(s.size() - 1);
  if (!(smin > 0.0)) return std::numeric_limits<double>::infinity();
  return smax / smin;
}

ConeProjector::ConeProjector(Eigen::Index dimension, const Eigen::VectorXd& weights, const solve::QPSettings& qp)
    : dimension_(dimension), weights_(weights), generators_(dimension, 0), weighted_(dimension, 0),
      gram_(0, 0), solver_(qp) {
  require(dimension >= 0, "ConeProjector: dimension must be >= 0, got " + std::to_string(dimension));
  check_weights("ConeProjector", weights, dimension);
}

void ConeProjector::add_generator(const Eigen::VectorXd& xi) {
  require(xi.size() == dimension_, "ConeProjector::add_generator: the generator has size " +
                                       std::to_string(xi.size()) + " but the projector has dimension " +
                                       std::to_string(dimension_));
  require(xi.allFinite(), "ConeProjector::add_generator: the generator has non-finite entries");
  const Eigen::Index R = generators_.cols();
  generators_.conservativeResize(Eigen::NoChange, R + 1);
  generators_.col(R) = xi;
  weighted_.conservativeResize(Eigen::NoChange, R + 1);
  weighted_.col(R) = weights_.size() ? Eigen::VectorXd(weights_.cwiseProduct(xi)) : xi;
  gram_.conservativeResize(R + 1, R + 1);
  for (Eigen::Index j = 0; j <= R; ++j) {
    const double q = weighted_.col(j).dot(xi);
    gram_(j, R) = q;
    gram_(R, j) = q;
  }
}

ConeProjection ConeProjector::project(const Eigen::VectorXd& x, const std::vector<int>& warm_passive) {
  require(x.size() == dimension_, "ConeProjector::project: x has size " + std::to_string(x.size()) +
                                      " but the projector has dimension " + std::to_string(dimension_));
  ConeProjection out;
  if (generators_.cols() == 0) {
    require(x.allFinite(), "ConeProjector::project: x has non-finite entries");
    out.coefficients = Eigen::VectorXd::Zero(0);
    out.projection = Eigen::VectorXd::Zero(dimension_);
    out.error = weighted_norm(x, weights_);
    return out;
  }
  const Eigen::VectorXd c = weighted_.transpose() * x;
  const solve::QPResult& r = solver_.solve(gram_, c, warm_passive);
  out.status = r.status;
  out.coefficients = r.x.cwiseMax(0.0);
  out.projection = Eigen::VectorXd::Zero(dimension_);
  for (int j : r.passive) out.projection += out.coefficients(j) * generators_.col(j);
  out.error = weighted_norm(x - out.projection, weights_);
  out.passive = r.passive;
  out.iterations = r.iterations;
  polish(generators_, weights_, x, out);
  return out;
}

Eigen::VectorXd cone_projection_errors(const Eigen::MatrixXd& snapshots, const Eigen::MatrixXd& generators,
                                       const Eigen::VectorXd& weights, const solve::QPSettings& qp,
                                       int* qp_failures) {
  require(generators.rows() == snapshots.rows(),
          "cone_projection_errors: the generators are " + dims(generators.rows(), generators.cols()) +
              " but the snapshots are " + dims(snapshots.rows(), snapshots.cols()));
  ConeProjector projector(snapshots.rows(), weights, qp);
  for (Eigen::Index j = 0; j < generators.cols(); ++j) projector.add_generator(generators.col(j));
  Eigen::VectorXd errors(snapshots.cols());
  int failures = 0;
  for (Eigen::Index p = 0; p < snapshots.cols(); ++p) {
    const ConeProjection pr = projector.project(snapshots.col(p));
    if (pr.status != solve::QPStatus::Solved) ++failures;
    errors(p) = pr.error;
  }
  if (qp_failures) *qp_failures = failures;
  return errors;
}

}  // namespace contactrb::offline
