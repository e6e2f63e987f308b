// The primal basis by extension (OfflineSettings::extend_basis, the greedy's): a model grown
// snapshot by snapshot through one OfflineBuildCache answers as the model built from scratch from
// the same snapshots, and as the POD model of every mode with the same supremizers (the row
// cone's rows take theirs from the first snapshot that activates them, row_cone.hpp). The bases
// differ in order and sign, so the test compares what a user sees: the reconstructed displacement
// and pressure and the error estimate at training and other parameter values; and the grown basis
// against the energy product assembled here. On hertz-3p level 0.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/theta.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/offline_greedy.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/reconstruction.hpp"

namespace {

using contactrb::cases::Mu;
using contactrb::offline::OfflineResult;
using contactrb::offline::OfflineSettings;

const contactrb::cases::CaseSpec& spec() {
  static const contactrb::cases::CaseSpec s = contactrb::cases::builtin_case_spec("hertz-3p");
  return s;
}

// The point at fractions t of each parameter's range.
Mu at(std::initializer_list<double> t) {
  Mu mu(static_cast<Eigen::Index>(spec().parameters.size()));
  Eigen::Index k = 0;
  for (double x : t) {
    const auto& q = spec().parameters[static_cast<std::size_t>(k)];
    mu(k) = q.min + x * (q.max - q.min);
    ++k;
  }
  return mu;
}

std::vector<Mu> training() {
  return {at({0.5, 0.5, 0.5}), at({0.1, 0.9, 0.2}), at({0.9, 0.2, 0.8}),
          at({0.3, 0.1, 0.9}), at({0.7, 0.8, 0.1}), at({0.95, 0.5, 0.4})};
}

const contactrb::io::SnapshotSet& snapshots() {
  static const contactrb::io::SnapshotSet set = [] {
    const contactrb::offline::SnapshotRequest r =
        contactrb::offline::make_snapshot_request(spec(), "training", 0, std::nullopt, training());
    contactrb::offline::SnapshotRunOptions run;
    run.warm_start = contactrb::offline::SnapshotRunOptions::WarmStart::Off;
    return contactrb::offline::generate_snapshots(r, run);
  }();
  return set;
}

contactrb::io::SnapshotSet leading(std::size_t count) {
  contactrb::io::SnapshotSet s = snapshots();
  s.snapshots.resize(count);
  return s;
}

OfflineSettings extension() {
  OfflineSettings s;
  s.extend_basis = true;
  return s;
}

// The sweep's online settings (the greedy's row-cone defaults).
contactrb::online::OnlineSettings sweep_settings() {
  contactrb::online::OnlineSettings s;
  s.error_estimate = true;
  s.iteration = contactrb::online::OnlineIteration::Newton;
  s.kacanov = contactrb::solve::KacanovSettings{1.0, contactrb::offline::kRowConeSweepTolerance,
                                                 contactrb::offline::kRowConeSweepIterations};
  return s;
}

struct Answer {
  Eigen::VectorXd u, lambda;
  double estimate = 0.0;
};

Answer answer(const OfflineResult& r, const Mu& mu) {
  contactrb::online::OnlineSolver solver(r.model);
  const contactrb::online::OnlineSolution s = solver.solve(mu, sweep_settings());
  EXPECT_TRUE(s.converged()) << "mu = " << mu.transpose();
  EXPECT_TRUE(s.estimate.available);
  return {contactrb::online::reconstruct_displacement(r.reconstruction, mu, s.u_hat),
          contactrb::online::reconstruct_multipliers(r.reconstruction, mu, s.lambda_hat), s.estimate.energy};
}

// Two models give the same fields (relative max-norm difference, tol) and estimates (relative,
// estimate_tol: a residual norm 1e-4 to 1e-5 of the loads', it carries the round-off of the reduced
// arrays amplified by that ratio).
void expect_same_answers(const OfflineResult& a, const OfflineResult& b, double tol, double estimate_tol) {
  std::vector<Mu> points = training();
  for (const Mu& mu : {at({0.2, 0.4, 0.6}), at({0.8, 0.6, 0.3}), at({0.05, 0.05, 0.05})}) points.push_back(mu);
  for (const Mu& mu : points) {
    const Answer x = answer(a, mu), y = answer(b, mu);
    EXPECT_LE((x.u - y.u).lpNorm<Eigen::Infinity>(), tol * x.u.lpNorm<Eigen::Infinity>()) << mu.transpose();
    EXPECT_LE((x.lambda - y.lambda).lpNorm<Eigen::Infinity>(), tol * x.lambda.lpNorm<Eigen::Infinity>())
        << mu.transpose();
    EXPECT_NEAR(x.estimate, y.estimate, estimate_tol * std::max(x.estimate, y.estimate) + 1e-14) << mu.transpose();
  }
}

// The model grown one snapshot at a time through one cache.
const OfflineResult& grown() {
  static const OfflineResult r = [] {
    contactrb::offline::OfflineBuildCache cache;
    OfflineResult last;
    for (std::size_t k = 1; k <= snapshots().snapshots.size(); ++k) {
      last = contactrb::offline::build_reduced_model(leading(k), spec(), extension(), &cache);
    }
    return last;
  }();
  return r;
}

TEST(BasisExtension, GrownModelAnswersAsTheModelBuiltFromScratch) {
  const OfflineResult scratch = contactrb::offline::build_reduced_model(snapshots(), spec(), extension());
  const OfflineResult& g = grown();
  ASSERT_EQ(g.model.N_max, scratch.model.N_max);
  ASSERT_EQ(g.model.R_max, scratch.model.R_max);
  EXPECT_EQ(g.report.N_supremizers, scratch.report.N_supremizers);
  EXPECT_EQ(g.report.N_pod, static_cast<int>(snapshots().snapshots.size()));
  // (49)'s stiffness terms, bordered at each build, are the projection of the whole basis.
  ASSERT_EQ(g.model.A_hat.size(), scratch.model.A_hat.size());
  for (std::size_t j = 0; j < g.model.A_hat.size(); ++j) {
    EXPECT_LE((g.model.A_hat[j] - scratch.model.A_hat[j]).cwiseAbs().maxCoeff(),
              1e-13 * scratch.model.A_hat[j].cwiseAbs().maxCoeff())
        << "A_hat " << j;
  }
  expect_same_answers(g, scratch, 1e-9, 1e-7);
}

// Independent of the extension code: the POD model keeping every mode spans the same snapshots,
// and its supremizers come from the same snapshots (the rows' first), so the Galerkin answers agree.
TEST(BasisExtension, GrownModelAnswersAsThePodModelOfEveryMode) {
  OfflineSettings pod;
  pod.pod_modes = static_cast<int>(snapshots().snapshots.size());
  const OfflineResult reference = contactrb::offline::build_reduced_model(snapshots(), spec(), pod);
  const OfflineResult& g = grown();
  ASSERT_EQ(reference.report.N_pod, pod.pod_modes);
  ASSERT_EQ(g.model.N_max, reference.model.N_max);
  expect_same_answers(g, reference, 1e-7, 1e-7);
}

// The grown basis is orthonormal in the energy product M = A_00(reference mu), assembled here from
// the case, and spans every snapshot's u_0.
TEST(BasisExtension, GrownBasisIsOrthonormalAndHoldsItsSnapshots) {
  const contactrb::cases::AffineTerms terms =
      contactrb::cases::assemble_affine_terms(spec(), contactrb::cases::reference_mesh(spec(), 0));
  const contactrb::fem::SparseMatrix A = contactrb::cases::combine(
      terms.A, contactrb::cases::evaluate(contactrb::cases::theta_functions(spec()).a,
                                          contactrb::cases::reference_mu(spec().parameters)));
  const std::vector<int>& free = snapshots().free_dofs;
  const Eigen::MatrixXd& Theta = grown().reconstruction.Theta;
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(A.rows(), Theta.cols());
  for (std::size_t i = 0; i < free.size(); ++i) full.row(free[i]) = Theta.row(static_cast<Eigen::Index>(i));
  const Eigen::MatrixXd MTheta = A * full;
  const Eigen::MatrixXd gram = full.transpose() * MTheta;
  EXPECT_LE((gram - Eigen::MatrixXd::Identity(Theta.cols(), Theta.cols())).lpNorm<Eigen::Infinity>(), 1e-10);
  for (const contactrb::io::Snapshot& s : snapshots().snapshots) {
    Eigen::VectorXd u0 = Eigen::VectorXd::Zero(A.rows());
    for (std::size_t i = 0; i < free.size(); ++i) u0(free[i]) = s.u0(static_cast<Eigen::Index>(i));
    const Eigen::VectorXd d = u0 - full * (MTheta.transpose() * u0);
    EXPECT_LE(std::sqrt(d.dot(A * d)), 1e-8 * std::sqrt(u0.dot(A * u0))) << s.mu.transpose();
  }
}

// A cache grown on other snapshots is not reused: the build starts again and answers as from scratch.
TEST(BasisExtension, CacheOfAnotherSetStartsAgain) {
  contactrb::offline::OfflineBuildCache cache;
  contactrb::io::SnapshotSet reordered = snapshots();
  std::swap(reordered.snapshots[0], reordered.snapshots[1]);
  (void)contactrb::offline::build_reduced_model(leading(3), spec(), extension(), &cache);
  const OfflineResult from_cache = contactrb::offline::build_reduced_model(reordered, spec(), extension(), &cache);
  const OfflineResult scratch = contactrb::offline::build_reduced_model(reordered, spec(), extension());
  expect_same_answers(from_cache, scratch, 1e-9, 1e-7);
}

TEST(BasisExtension, OtherConesAreRefused) {
  OfflineSettings s = extension();
  s.dual_method = contactrb::offline::DualConeMethod::CPG;
  EXPECT_THROW(contactrb::offline::check_settings(s), contactrb::Error);
  s = extension();
  s.compression = false;
  EXPECT_THROW(contactrb::offline::check_settings(s), contactrb::Error);
}

}  // namespace
