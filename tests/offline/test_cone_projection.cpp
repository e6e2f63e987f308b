#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <random>

#include "contactrb/common/error.hpp"
#include "contactrb/offline/cone_projection.hpp"

using namespace contactrb::offline;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Brute force: for every non-empty subset of generators (a face), unconstrained weighted
// least squares; keep the feasible (c >= 0) ones and take the best. Returns the projection.
VectorXd brute_force_projection(const MatrixXd& Xi, const VectorXd& x, const VectorXd& w) {
  const int k = static_cast<int>(Xi.cols());
  const VectorXd sq = w.size() ? VectorXd(w.cwiseSqrt()) : VectorXd::Ones(x.size());
  VectorXd best = VectorXd::Zero(x.size());
  double best_err = sq.cwiseProduct(x).norm();
  for (unsigned mask = 1; mask < (1u << k); ++mask) {
    std::vector<int> face;
    for (int j = 0; j < k; ++j)
      if (mask & (1u << j)) face.push_back(j);
    MatrixXd A(x.size(), static_cast<Eigen::Index>(face.size()));
    for (std::size_t a = 0; a < face.size(); ++a) A.col(static_cast<Eigen::Index>(a)) = Xi.col(face[a]);
    const MatrixXd WA = sq.asDiagonal() * A;
    const VectorXd c = WA.colPivHouseholderQr().solve(VectorXd(sq.cwiseProduct(x)));
    if (c.minCoeff() < 0.0) continue;
    const VectorXd p = A * c;
    const double err = sq.cwiseProduct(x - p).norm();
    if (err < best_err) {
      best_err = err;
      best = p;
    }
  }
  return best;
}

}  // namespace

TEST(ConeProjection, MatchesBruteForceOverFaces) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> U(-1.0, 1.0), Wd(0.2, 3.0);
  for (int trial = 0; trial < 150; ++trial) {
    const int n = 3 + trial % 4;       // 3..6
    const int k = 1 + trial % 5;       // 1..5 generators
    const bool weighted = trial % 2 == 1;
    const MatrixXd Xi = MatrixXd::NullaryExpr(n, k, [&] { return U(rng); });
    const VectorXd x = VectorXd::NullaryExpr(n, [&] { return U(rng); });
    const VectorXd w = weighted ? VectorXd(VectorXd::NullaryExpr(n, [&] { return Wd(rng); })) : VectorXd();
    const ConeProjection p = project_onto_cone(Xi, x, w);
    ASSERT_EQ(p.status, contactrb::solve::QPStatus::Solved);
    EXPECT_GE(p.coefficients.minCoeff(), 0.0);
    const VectorXd truth = brute_force_projection(Xi, x, w);
    EXPECT_LT((p.projection - truth).cwiseAbs().maxCoeff(), 1e-9) << "trial " << trial;
    EXPECT_NEAR(p.error, weighted_norm(x - truth, w), 1e-10) << "trial " << trial;
    // The reusable projector agrees.
    ConeProjector proj(n, w);
    for (int j = 0; j < k; ++j) proj.add_generator(Xi.col(j));
    const ConeProjection q = proj.project(x);
    EXPECT_NEAR(q.error, p.error, 1e-12);
    EXPECT_LT((q.projection - p.projection).cwiseAbs().maxCoeff(), 1e-10);
  }
}

TEST(ConeProjection, MemberProjectsOntoItself) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const MatrixXd Xi = MatrixXd::NullaryExpr(8, 4, [&] { return U(rng); });
  const VectorXd c = (VectorXd(4) << 0.5, 0.0, 2.0, 1.0).finished();
  const VectorXd x = Xi * c;
  const VectorXd w = VectorXd::LinSpaced(8, 0.5, 2.0);
  for (const VectorXd& weights : {VectorXd(), w}) {
    const ConeProjection p = project_onto_cone(Xi, x, weights);
    EXPECT_LT(p.error, 1e-12);
    EXPECT_LT((p.projection - x).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((p.coefficients - c).cwiseAbs().maxCoeff(), 1e-10);
  }
}

TEST(ConeProjection, WeightedNormChangesTheProjection) {
  // One generator (1, 1): the weighted projection of (1, 0) is t (1, 1), t = w1 / (w1 + w2).
  const MatrixXd Xi = (MatrixXd(2, 1) << 1.0, 1.0).finished();
  const VectorXd x = (VectorXd(2) << 1.0, 0.0).finished();
  const VectorXd w = (VectorXd(2) << 3.0, 1.0).finished();
  const ConeProjection p = project_onto_cone(Xi, x, w);
  EXPECT_NEAR(p.coefficients(0), 0.75, 1e-14);
  EXPECT_NEAR(p.error, std::sqrt(3.0 * 0.0625 + 0.5625), 1e-14);
  EXPECT_NEAR(project_onto_cone(Xi, x).coefficients(0), 0.5, 1e-14);
  // x in the polar cone: projection 0, error |x|_M.
  const ConeProjection z = project_onto_cone(Xi, -Xi.col(0), w);
  EXPECT_EQ(z.coefficients(0), 0.0);
  EXPECT_NEAR(z.error, 2.0, 1e-14);
  // Empty cone.
  const ConeProjection e = project_onto_cone(MatrixXd(2, 0), x, w);
  EXPECT_NEAR(e.error, std::sqrt(3.0), 1e-15);
}

TEST(ConeProjection, GeneratorConditionNumber) {
  const MatrixXd D = (MatrixXd(3, 2) << 3.0, 0.0, 0.0, 1.0, 0.0, 0.0).finished();
  EXPECT_NEAR(generator_condition_number(D), 3.0, 1e-14);
  // Weights: diag(sqrt(w)) D = diag(3, 2): condition 1.5.
  EXPECT_NEAR(generator_condition_number(D, (VectorXd(3) << 1.0, 4.0, 1.0).finished()), 1.5, 1e-14);
  // Agrees with sqrt(cond(Xi' Xi)) on a random family.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const MatrixXd Xi = MatrixXd::NullaryExpr(10, 4, [&] { return U(rng); });
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(Xi.transpose() * Xi);
  const double truth = std::sqrt(eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff());
  EXPECT_NEAR(generator_condition_number(Xi), truth, 1e-8 * truth);
  // Dependent generators.
  MatrixXd dep(3, 2);
  dep << 1, 2, 1, 2, 0, 0;
  EXPECT_EQ(generator_condition_number(dep), std::numeric_limits<double>::infinity());
  EXPECT_EQ(generator_condition_number(MatrixXd(3, 0)), 1.0);
}

TEST(ConeProjection, InvalidInputThrows) {
  const MatrixXd Xi = MatrixXd::Ones(3, 2);
  EXPECT_THROW(project_onto_cone(Xi, VectorXd::Ones(4)), contactrb::Error);
  EXPECT_THROW(project_onto_cone(Xi, VectorXd::Ones(3), VectorXd::Ones(2)), contactrb::Error);
  EXPECT_THROW(project_onto_cone(Xi, VectorXd::Ones(3), -VectorXd::Ones(3)), contactrb::Error);
  ConeProjector p(3);
  EXPECT_THROW(p.add_generator(VectorXd::Ones(2)), contactrb::Error);
  EXPECT_THROW(p.project(VectorXd::Ones(2)), contactrb::Error);
  EXPECT_THROW(cone_projection_errors(MatrixXd::Ones(3, 2), MatrixXd::Ones(4, 1)), contactrb::Error);
}
