// The registered dual cone (docs/offline-online.md, "The registered cone"): the basis map
// Xi(mu) against hand-computed interpolation, the support prediction against functions it must
// reproduce, and on hertz-a (a support that moves with mu) the model against HF:
// pressures non-negative, e_press within its cone's best, the estimate an upper bound, fewer
// generators than a global CPG cone needs for the same best approximation (level 3), the file
// round-trip (level 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/online/registered_basis.hpp"
#include "contactrb/study/evaluation.hpp"

namespace {

using contactrb::model::Registration;
using contactrb::offline::DualConeMethod;
namespace online = contactrb::online;

// Two generators on the grid xi = -0.5, 0, ..., 1.5 (step 0.5), three kept rows at s = 1, 2, 3.
Registration small_registration() {
  Registration r;
  r.row_coordinate = Eigen::Vector3d(1.0, 2.0, 3.0);
  r.grid = Eigen::VectorXd::LinSpaced(5, -0.5, 1.5);
  r.generators.resize(5, 2);
  r.generators << 0, 0, 1, 4, 2, 3, 1, 2, 0, 1;
  r.point_offset = Eigen::VectorXd::Zero(1);
  r.point_scale = Eigen::VectorXd::Ones(1);
  r.points.resize(1, 3);
  r.points << 0.0, 0.5, 1.0;
  r.support.resize(2, 3);
  r.support << 1.0, 1.0, 0.0,  // s_left
      2.0, 3.0, 4.0;           // s_right
  return r;
}

TEST(RegisteredBasis, InterpolatesTheGeneratorsAtTheRegisteredCoordinates) {
  const Registration r = small_registration();
  Eigen::MatrixXd Xi;
  // Support [1, 3]: xi = 0, 0.5, 1 at the rows: grid points 1, 2, 3 exactly.
  online::registered_basis(r, Eigen::Vector2d(1.0, 3.0), 2, Xi);
  Eigen::MatrixXd expected(3, 2);
  expected << 1, 4, 2, 3, 1, 2;
  EXPECT_EQ(Xi, expected);
  // Support [0, 4]: xi = 0.25, 0.5, 0.75: half-way between grid points 1-2, at 2, between 2-3.
  online::registered_basis(r, Eigen::Vector2d(0.0, 4.0), 2, Xi);
  expected << 1.5, 3.5, 2, 3, 1.5, 2.5;
  EXPECT_TRUE(Xi.isApprox(expected, 1e-15)) << Xi;
  // Support [2.5, 3]: rows 1 and 2 at xi = -3 and -1 (outside the grid: 0), row 3 at xi = 1.
  online::registered_basis(r, Eigen::Vector2d(2.5, 3.0), 1, Xi);
  EXPECT_EQ(Xi, Eigen::Vector3d(0.0, 0.0, 1.0));
}

TEST(RegisteredBasis, PredictsTheSupportLinearlyBetweenTrainingValues) {
  const Registration r = small_registration();
  const auto at = [&](double mu) { return online::predicted_support(r, Eigen::VectorXd::Constant(1, mu)); };
  EXPECT_EQ(at(0.5), Eigen::Vector2d(1.0, 3.0));
  EXPECT_TRUE(at(0.75).isApprox(Eigen::Vector2d(0.5, 3.5), 1e-15));
  EXPECT_EQ(at(-1.0), Eigen::Vector2d(1.0, 2.0));  // the end values outside the training range
  EXPECT_EQ(at(2.0), Eigen::Vector2d(0.0, 4.0));
}

TEST(RegisteredBasis, ThreeParameterFitReproducesAnAffineSupport) {
  Registration r;
  r.point_offset = Eigen::Vector3d(1.0, 0.0, -1.0);
  r.point_scale = Eigen::Vector3d(0.5, 1.0, 2.0);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int P = 20;
  r.points.resize(3, P);
  r.support.resize(2, P);
  const auto affine = [](const Eigen::Vector3d& x) {
    return Eigen::Vector2d(-1.0 + 0.2 * x(0) - 0.1 * x(1) + 0.3 * x(2), 2.0 + 0.5 * x(0) + 0.4 * x(1) - 0.2 * x(2));
  };
  for (int j = 0; j < P; ++j) {
    r.points.col(j) = Eigen::Vector3d(u(gen), u(gen), u(gen));
    r.support.col(j) = affine(r.points.col(j));
  }
  for (int k = 0; k < 10; ++k) {
    const Eigen::Vector3d x(u(gen), u(gen), u(gen));
    const Eigen::VectorXd mu = x.cwiseQuotient(r.point_scale) + r.point_offset;
    EXPECT_TRUE(online::predicted_support(r, mu).isApprox(affine(x), 1e-12)) << "x = " << x.transpose();
  }
  // A training point gets its own support back.
  const Eigen::VectorXd mu0 = r.points.col(3).cwiseQuotient(r.point_scale) + r.point_offset;
  EXPECT_TRUE(online::predicted_support(r, mu0).isApprox(r.support.col(3), 1e-14));
}

const contactrb::io::SnapshotSet& hertz_a(int level) {
  static std::map<int, std::unique_ptr<contactrb::io::SnapshotSet>> sets;
  auto& set = sets[level];
  if (!set) {
    contactrb::offline::SnapshotRunOptions options;
    options.jobs = 2;
    set = std::make_unique<contactrb::io::SnapshotSet>(contactrb::offline::generate_snapshots(
        contactrb::offline::make_snapshot_request(contactrb::cases::builtin_case_spec("hertz-a"), "training", level),
        options));
  }
  return *set;
}

contactrb::offline::OfflineResult build(int level, DualConeMethod method, int R) {
  contactrb::offline::OfflineSettings s;
  s.dual_method = method;
  s.dual_size = R;
  return contactrb::offline::build_reduced_model(hertz_a(level), contactrb::cases::builtin_case_spec("hertz-a"), s);
}

// The model against Newton HF references on the case's verification set.
contactrb::study::Evaluation evaluate_verification(const contactrb::cases::CaseSpec& spec,
                                                   const contactrb::offline::OfflineResult& off) {
  contactrb::study::EvaluationOptions o;
  o.jobs = 2;
  o.online_repeats = 1;
  return contactrb::study::evaluate_model(off.model, off.reconstruction, spec, spec.set("verification"), o);
}

// The estimate at every point of an evaluation: an upper bound of the energy-norm error, sharp
// (effectivity at most 10, median at most 5). The registered pressure meets the HF rows only in the
// mean, so these figures come from the complementary bound (Delta_u alone: effectivity 13-61).
void expect_sharp_upper_bound(const contactrb::study::Evaluation& e) {
  std::vector<double> effectivity;
  for (const auto& r : e.rows) {
    ASSERT_TRUE(std::isfinite(r.estimate)) << "mu = " << r.mu;
    EXPECT_GE(r.estimate, r.e_energy_norm) << "mu = " << r.mu;
    EXPECT_LE(r.estimate, 10.0 * r.e_energy_norm) << "mu = " << r.mu;
    effectivity.push_back(r.estimate / r.e_energy_norm);
  }
  ASSERT_FALSE(effectivity.empty());
  std::nth_element(effectivity.begin(), effectivity.begin() + std::ptrdiff_t(effectivity.size() / 2), effectivity.end());
  EXPECT_LE(effectivity[effectivity.size() / 2], 5.0);
}

// Measured: N 33, R 15 of 69 kept rows, max e_press 1.6e-2 against a cone's best of 1.4e-2 (a
// global CPG cone of 15 training pressures: 5.0e-2), effectivity 1.4-4.2.
TEST(RegisteredCone, FollowsTheMovingSupportOnHertzALevel3) {
  const auto spec = contactrb::cases::builtin_case_spec("hertz-a");
  const contactrb::offline::OfflineResult off = build(3, DualConeMethod::Registered, 15);
  ASSERT_EQ(off.model.registration.R(), 15);
  EXPECT_GT(off.model.R_kept(), 60);  // the row cone would need one generator per kept row
  const contactrb::study::Evaluation e = evaluate_verification(spec, off);
  EXPECT_EQ(e.summary.hf_failures + e.summary.rb_failures, 0);
  std::printf("[ registered ] N %d R %d: max e_press %.3e (cone's best %.3e), e_displ %.3e, effectivity %.2f-%.2f\n",
              e.N, e.R, e.summary.max_e_press, e.summary.max_e_press_cone, e.summary.max_e_displ,
              e.summary.min_effectivity, e.summary.max_effectivity);
  EXPECT_LT(e.summary.max_e_press, 2.5e-2);
  EXPECT_LT(e.summary.max_e_displ, 4e-3);
  EXPECT_LT(e.summary.max_e_press, 1.2 * e.summary.max_e_press_cone + 2e-3);
  for (const auto& r : e.rows) {
    EXPECT_GE(r.e_press, r.e_press_cone * (1.0 - 1e-9)) << "mu = " << r.mu;
  }
  expect_sharp_upper_bound(e);
  // The same R in a global CPG cone of the training pressures holds a worse best approximation.
  const contactrb::offline::OfflineResult cpg = build(3, DualConeMethod::CPG, 15);
  const contactrb::study::Evaluation c = evaluate_verification(spec, cpg);
  std::printf("[ cpg ] R %d: cone's best %.3e\n", c.R, c.summary.max_e_press_cone);
  EXPECT_GT(c.summary.max_e_press_cone, 2.5 * e.summary.max_e_press_cone);
}

// hertz-b: the support does not move and the kept rows are exactly the active ones, so each
// profile's edges ramp down to the rows outside the kept set (0 there). Measured: R 5, max e_press
// 1.7e-3, effectivity 2.2-3.3.
TEST(RegisteredCone, KeepsTheEdgeRowsOfASupportThatDoesNotMove) {
  const auto spec = contactrb::cases::builtin_case_spec("hertz-b");
  contactrb::offline::SnapshotRunOptions options;
  options.jobs = 2;
  const contactrb::io::SnapshotSet set =
      contactrb::offline::generate_snapshots(contactrb::offline::make_snapshot_request(spec, "training"), options);
  contactrb::offline::OfflineSettings s;
  s.dual_method = DualConeMethod::Registered;
  const contactrb::offline::OfflineResult off = contactrb::offline::build_reduced_model(set, spec, s);
  const contactrb::study::Evaluation e = evaluate_verification(spec, off);
  EXPECT_EQ(e.summary.rb_failures, 0);
  EXPECT_LT(e.summary.max_e_press, 5e-3);
  EXPECT_LT(e.R, off.model.R_kept());
  expect_sharp_upper_bound(e);
}

// The coarse mesh: the support jumps by whole rows and the reduced displacement crosses rows
// between the mean constraints. Measured: effectivity 1.07-2.6 (median 1.2).
TEST(RegisteredCone, EstimateIsASharpUpperBoundOnHertzALevel0) {
  const auto spec = contactrb::cases::builtin_case_spec("hertz-a");
  const contactrb::offline::OfflineResult off = build(0, DualConeMethod::Registered, 15);
  const contactrb::study::Evaluation e = evaluate_verification(spec, off);
  EXPECT_EQ(e.summary.hf_failures + e.summary.rb_failures, 0);
  expect_sharp_upper_bound(e);
}

// The steps evaluate only the kept rows Xi(mu) weighs, from their own slave nodes, and the
// complementary bound takes the rows from the estimate's projections; the reference path
// (restricted_rows = false) evaluates every row of the contact surface with the contact library
// at every step and projects again for the bound. Same steps, same answer, same estimate.
TEST(RegisteredCone, RowsUnderTheSupportGiveTheWholeSurfaceAnswer) {
  const contactrb::offline::OfflineResult off = build(2, DualConeMethod::Registered, 15);
  online::OnlineSolver solver(off.model);
  online::OnlineSettings full;
  full.restricted_rows = false;
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(0.15, 0.45);
  int skipped = 0, corrected = 0;
  for (int k = 0; k < 12; ++k) {
    const Eigen::VectorXd mu = Eigen::VectorXd::Constant(1, k == 0 ? 0.15 : u(gen));
    Eigen::MatrixXd Xi;
    online::registered_basis(off.model.registration, online::predicted_support(off.model.registration, mu), 15, Xi);
    for (Eigen::Index r = 0; r < Xi.rows(); ++r) skipped += Xi.row(r).isZero(0.0) ? 1 : 0;
    const online::OnlineSolution a = solver.solve(mu), b = solver.solve(mu, full);
    ASSERT_TRUE(a.converged() && b.converged()) << a.message << b.message;
    EXPECT_EQ(a.iterations, b.iterations) << "mu = " << mu(0);
    EXPECT_LT((a.u_hat - b.u_hat).norm(), 1e-10 * a.u_hat.norm()) << "mu = " << mu(0);
    // lambda_hat: the rounding of D amplified by the reduced QP's condition (measured: 3e-10).
    EXPECT_LT((a.lambda_hat - b.lambda_hat).norm(), 2e-9 * a.lambda_hat.norm()) << "mu = " << mu(0);
    ASSERT_TRUE(a.estimate.available && b.estimate.available);
    EXPECT_NEAR(a.estimate.energy, b.estimate.energy, 1e-8 * b.estimate.energy) << "mu = " << mu(0);
    EXPECT_NEAR(a.estimate.correction, b.estimate.correction, 1e-8 * b.estimate.energy) << "mu = " << mu(0);
    corrected += b.estimate.correction > 0.0 ? 1 : 0;
  }
  EXPECT_GT(skipped, 0);    // some kept rows lie outside a predicted support
  EXPECT_GT(corrected, 0);  // and the complementary bound was taken
}

TEST(RegisteredCone, PressureIsNonNegativeAndTheFileGivesTheSameAnswer) {
  const contactrb::offline::OfflineResult off = build(2, DualConeMethod::Registered, 10);
  const auto path = std::filesystem::temp_directory_path() / "contactrb_test_registered_cone.h5";
  contactrb::io::write_reduced_model_file(off.model, off.reconstruction, path.string());
  const contactrb::model::ReducedModel back = contactrb::io::read_reduced_model_file(path.string());
  const contactrb::model::ReducedReconstruction rec = contactrb::io::read_reconstruction(path.string());
  std::filesystem::remove(path);
  EXPECT_EQ(back.registration.generators, off.model.registration.generators);
  EXPECT_EQ(back.registration.support, off.model.registration.support);
  EXPECT_EQ(rec.registration.row_coordinate, off.model.registration.row_coordinate);
  online::OnlineSolver a(off.model), b(back);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(0.15, 0.45);
  for (int k = 0; k < 10; ++k) {
    const Eigen::VectorXd mu = Eigen::VectorXd::Constant(1, u(gen));
    const online::OnlineSolution x = a.solve(mu), y = b.solve(mu);
    ASSERT_TRUE(x.converged()) << "mu = " << mu(0) << ": " << x.message;
    EXPECT_EQ(x.u_hat, y.u_hat);
    EXPECT_EQ(x.lambda_hat, y.lambda_hat);
    const Eigen::VectorXd lambda = online::reconstruct_multipliers(rec, mu, y.lambda_hat);
    EXPECT_GE(lambda.minCoeff(), 0.0);
    EXPECT_GT(lambda.maxCoeff(), 0.0);
    EXPECT_EQ(lambda, online::reconstruct_multipliers(off.reconstruction, mu, x.lambda_hat));
  }
  // The EIM rows of a registered model are the rows', not Xi(mu)'s: refused.
  online::OnlineSettings eim;
  eim.contact_rows = online::ContactRows::Eim;
  EXPECT_THROW(a.solve(Eigen::VectorXd::Constant(1, 0.3), eim), contactrb::Error);
}

}  // namespace
