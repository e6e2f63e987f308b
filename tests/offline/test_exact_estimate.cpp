// The estimate with the exact contact rows on row-cone models (docs/offline-online.md, "Error
// estimate", "The geometric term"):
//  - eta_p bounds -v'Hv / v'A(mu)v over random directions that keep the active rows closed, and
//    is positive on a curved contact (an independent check of the reduced eigenproblem);
//  - the estimate's contact parts are those of the HF rows at the reconstructed displacement;
//  - at uniform random points of each shipped two-dimensional case the estimate is an upper
//    bound of |u_hf - u_rb|_A(mu) (HF reference: the semi-smooth Newton, KKT residual 1e-10)
//    and at most kMaxEffectivity times it, with a median of at most 5.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/parameter_sets.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/offline/geometric_term.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/reconstruction.hpp"

namespace {

namespace cases = contactrb::cases;
namespace offline = contactrb::offline;
using Index = Eigen::Index;

constexpr double kMaxEffectivity = 10.0;

cases::ParameterBox box_of(const cases::CaseSpec& spec) {
  cases::ParameterBox box;
  const Index p = static_cast<Index>(spec.parameters.size());
  box.min.resize(p);
  box.max.resize(p);
  for (Index i = 0; i < p; ++i) {
    const auto& q = spec.parameters[static_cast<std::size_t>(i)];
    box.names.push_back(q.name);
    box.min(i) = q.min;
    box.max(i) = q.max;
  }
  return box;
}

// Snapshots at `points` (the case's own settings), solved on two threads.
contactrb::io::SnapshotSet snapshots_at(const cases::CaseSpec& spec, const std::vector<cases::Mu>& points) {
  offline::SnapshotRequest r = offline::make_snapshot_request(spec, "training", 0, std::nullopt, points);
  offline::SnapshotRunOptions options;
  options.jobs = 2;
  return offline::generate_snapshots(r, options);
}

// The HF contact linearization at a snapshot, every free DOF movable.
contactrb::contact::ContactLinearization linearization_of(const contactrb::hf::HFSolver& solver,
                                                          const contactrb::io::Snapshot& snap) {
  const auto& dofs = solver.dofs();
  std::vector<char> movable(static_cast<std::size_t>(dofs.num_dofs()), 0);
  for (int i : dofs.free_dofs()) movable[static_cast<std::size_t>(i)] = 1;
  return contactrb::contact::linearize_contact(solver.problem().mesh, solver.pair(), solver.quadrature(), snap.u,
                                               snap.lambda, movable);
}

struct EstimateCase {
  std::string name;
  double eps_pod;
  int training;  // 0: the case's training set; else this many Latin-hypercube points
};

// The row-cone model of a case, built once per test binary run.
const offline::OfflineResult& row_cone_model(const EstimateCase& c) {
  static std::map<std::string, std::unique_ptr<offline::OfflineResult>> cache;
  auto& slot = cache[c.name];
  if (!slot) {
    const cases::CaseSpec spec = cases::builtin_case_spec(c.name);
    const contactrb::io::SnapshotSet set =
        c.training > 0 ? snapshots_at(spec, cases::latin_hypercube(box_of(spec), c.training, 5))
                       : offline::generate_snapshots(offline::make_snapshot_request(spec, "training"), {});
    offline::OfflineSettings s;
    s.dual_method = offline::DualConeMethod::Rows;
    s.eps_pod = c.eps_pod;
    slot = std::make_unique<offline::OfflineResult>(offline::build_reduced_model(set, spec, s));
  }
  return *slot;
}

class ExactEstimate : public ::testing::TestWithParam<EstimateCase> {};

// The kept rows from their own slave nodes (restricted_rows; LAC: the kept macro-segments) give
// the answer of the whole contact surface's rows.
TEST_P(ExactEstimate, RestrictedRowsGiveTheWholeSurfaceAnswer) {
  const EstimateCase c = GetParam();
  const offline::OfflineResult& off = row_cone_model(c);
  contactrb::online::OnlineSolver solver(off.model);
  contactrb::online::OnlineSettings full;
  full.restricted_rows = false;
  for (const cases::Mu& mu : cases::uniform_random(box_of(cases::builtin_case_spec(c.name)), 3, 23)) {
    const auto a = solver.solve(mu);
    const auto b = solver.solve(mu, full);
    ASSERT_TRUE(a.converged() && b.converged()) << a.message << b.message;
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_LT((a.u_hat - b.u_hat).norm(), 1e-10 * a.u_hat.norm());
    EXPECT_LT((a.lambda_hat - b.lambda_hat).norm(), 1e-10 * std::max(1.0, a.lambda_hat.norm()));
  }
}

// The estimate's contact parts (the HF rows at the returned displacement, over every row) against
// the contact library on the HF mesh of Omega(mu): the rows of the reconstructed displacement,
// their slack g - K u and the reconstructed multipliers. The violation and the complementarity
// are sums of slacks at round-off level on the active rows: compared to an absolute tolerance
// of round-off times the gap scale.
TEST_P(ExactEstimate, ContactPartsAreThoseOfTheHighFidelityRows) {
  const EstimateCase c = GetParam();
  const cases::CaseSpec spec = cases::builtin_case_spec(c.name);
  const offline::OfflineResult& off = row_cone_model(c);
  contactrb::online::OnlineSolver solver(off.model);
  const auto reference = cases::reference_mesh(spec, 0);
  for (const cases::Mu& mu : cases::uniform_random(box_of(spec), 3, 29)) {
    const auto rb = solver.solve(mu);
    ASSERT_TRUE(rb.converged()) << rb.message;
    ASSERT_TRUE(rb.estimate.available && rb.estimate.exact);
    const auto problem = cases::make_problem(spec, reference, mu, off.model.surface.discretization);
    const auto pair = contactrb::contact::make_contact_pair(problem.mesh);
    const auto quadrature = contactrb::contact::make_quadrature(problem.mesh, pair, problem.discretization);
    const Eigen::VectorXd u = contactrb::online::reconstruct_displacement(off.reconstruction, mu, rb.u_hat);
    const auto pointwise = contactrb::contact::project_slave_nodes(problem.mesh, pair, u);
    const auto rows = contactrb::contact::constraint_rows(problem.mesh, pair, quadrature, pointwise, u);
    const Eigen::VectorXd slack = rows.g - rows.K * u;
    const Eigen::VectorXd lambda = contactrb::online::reconstruct_multipliers(off.reconstruction, mu, rb.lambda_hat);
    const auto hf = contactrb::online::constraint_measures(slack, lambda, quadrature.weight);
    const double round_off = 1e-13 * rows.g.cwiseAbs().maxCoeff();
    EXPECT_NEAR(rb.estimate.multiplier_norm, hf.multiplier_norm, 1e-10 * hf.multiplier_norm) << mu.transpose();
    EXPECT_NEAR(rb.estimate.violation, hf.violation, round_off / std::sqrt(quadrature.weight.minCoeff()))
        << mu.transpose();
    EXPECT_NEAR(rb.estimate.complementarity, hf.complementarity, round_off * lambda.cwiseAbs().sum())
        << mu.transpose();
  }
}

TEST_P(ExactEstimate, IsAnUpperBoundAtRandomPoints) {
  const EstimateCase c = GetParam();
  const cases::CaseSpec spec = cases::builtin_case_spec(c.name);
  const cases::ParameterBox box = box_of(spec);
  const offline::OfflineResult& off = row_cone_model(c);
  const double eta = off.model.estimate.geometric_ratio;
  EXPECT_GT(eta, 0.0);  // curved contact surfaces: the contact forces have a geometric stiffness
  EXPECT_LT(eta, 1.0);

  contactrb::online::OnlineSolver solver(off.model);
  const auto reference = cases::reference_mesh(spec, 0);
  contactrb::hf::HFSettings newton;
  newton.method = contactrb::hf::HFMethod::Newton;
  std::vector<double> effectivity;
  for (const cases::Mu& mu : cases::uniform_random(box, 8, 17)) {
    const auto rb = solver.solve(mu);
    ASSERT_TRUE(rb.converged()) << rb.message;
    ASSERT_TRUE(rb.estimate.available && rb.estimate.exact);
    const contactrb::hf::HFSolver hf_solver(cases::make_problem(spec, reference, mu, off.model.surface.discretization));
    const auto hf = hf_solver.solve(newton);
    ASSERT_TRUE(hf.converged) << hf.message;
    const Eigen::VectorXd e = hf.u - contactrb::online::reconstruct_displacement(off.reconstruction, mu, rb.u_hat);
    const double error = std::sqrt(e.dot(hf_solver.stiffness() * e));
    const double ratio = rb.estimate.energy / error;
    std::printf("[ %s ] |e|_A %.3e estimate %.3e effectivity %.2f (eta %.3f)\n", c.name.c_str(), error,
                rb.estimate.energy, ratio, eta);
    EXPECT_GE(ratio, 1.0) << "mu = " << mu.transpose();
    EXPECT_LE(ratio, kMaxEffectivity) << "mu = " << mu.transpose();
    effectivity.push_back(ratio);
  }
  std::sort(effectivity.begin(), effectivity.end());
  std::printf("[ %s ] effectivity min %.2f median %.2f max %.2f\n", c.name.c_str(), effectivity.front(),
              effectivity[effectivity.size() / 2], effectivity.back());
  EXPECT_LE(effectivity[effectivity.size() / 2], 5.0);
}

INSTANTIATE_TEST_SUITE_P(Cases, ExactEstimate,
                         ::testing::Values(EstimateCase{"hertz-a", 3e-5, 0}, EstimateCase{"hertz-b", 3e-5, 0},
                                           EstimateCase{"ring-block", 1e-6, 0},
                                           EstimateCase{"hertz-3p", 1e-7, 40}),
                         [](const auto& info) {
                           std::string n;
                           for (char ch : info.param.name) n += ch == '-' ? '_' : ch;
                           return n;
                         });

// The preconditioned accelerated iteration (docs/offline-online.md, "Online: the preconditioned
// iteration") on the three-parameter case, whose contact forces have the largest geometric
// stiffness: steps with the Jacobian of the nearest training point reach the plain iteration's
// fixed point (both stop within 1e-8 of it) in fewer steps.
TEST(PreconditionedIteration, ReachesThePlainFixedPointInFewerSteps) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-3p");
  const offline::OfflineResult& off = row_cone_model(EstimateCase{"hertz-3p", 1e-7, 40});
  const auto& m = off.model;
  ASSERT_EQ(m.training_jacobian.rows(), m.N_max);
  ASSERT_EQ(m.training_jacobian.cols(), m.N_max * m.training_mu.cols());
  contactrb::online::OnlineSolver solver(m);
  contactrb::online::OnlineSettings plain;
  plain.preconditioned = false;
  std::vector<int> with, without;
  for (const cases::Mu& mu : cases::uniform_random(box_of(spec), 30, 41)) {
    const auto a = solver.solve(mu);
    const auto b = solver.solve(mu, plain);
    ASSERT_TRUE(a.converged() && b.converged()) << a.message << b.message;
    EXPECT_LT((a.u_hat - b.u_hat).norm(), 1e-8 * b.u_hat.norm()) << mu.transpose();
    EXPECT_LT((a.lambda_hat - b.lambda_hat).norm(), 1e-7 * b.lambda_hat.norm()) << mu.transpose();
    with.push_back(a.iterations);
    without.push_back(b.iterations);
  }
  std::sort(with.begin(), with.end());
  std::sort(without.begin(), without.end());
  std::printf("[ hertz-3p ] steps: preconditioned median %d max %d, plain median %d max %d\n", with[with.size() / 2],
              with.back(), without[without.size() / 2], without.back());
  EXPECT_LT(with[with.size() / 2], without[without.size() / 2]);
  EXPECT_LE(with.back(), without.back());
}

// The first-order start (ReducedModel::training_u_sensitivity, one-sided differences of step 1e-3
// of each range) against the online answers: S_i agrees with central differences of step 1e-4 at a
// training point, and at random points u_hat_i + S_i (mu - mu_i) of the nearest training point i
// (found here by its own scan) is nearer the answer than u_hat_i, and the median query takes
// fewer steps from it than from u_hat_i.
TEST(PreconditionedIteration, FirstOrderStartIsNearerTheAnswer) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-3p");
  const offline::OfflineResult& off = row_cone_model(EstimateCase{"hertz-3p", 1e-7, 40});
  const auto& m = off.model;
  const Eigen::Index p = 3, N = m.N_max, P = m.training_mu.cols();
  ASSERT_EQ(m.training_u_sensitivity.rows(), N);
  ASSERT_EQ(m.training_u_sensitivity.cols(), p * P);
  contactrb::online::OnlineSolver solver(m);
  Eigen::Vector3d range;
  for (Eigen::Index k = 0; k < p; ++k) range(k) = spec.parameters[static_cast<std::size_t>(k)].max - spec.parameters[static_cast<std::size_t>(k)].min;
  const cases::Mu mu0 = m.training_mu.col(2);
  for (Eigen::Index k = 0; k < p; ++k) {
    cases::Mu lo = mu0, hi = mu0;
    lo(k) -= 1e-4 * range(k);
    hi(k) += 1e-4 * range(k);
    if (hi(k) > spec.parameters[static_cast<std::size_t>(k)].max) continue;
    const auto a = solver.solve(lo), b = solver.solve(hi);
    ASSERT_TRUE(a.converged() && b.converged());
    const Eigen::VectorXd central = (b.u_hat - a.u_hat) / (2e-4 * range(k));
    EXPECT_LT((m.training_u_sensitivity.col(2 * p + k) - central).norm(), 2e-2 * central.norm() + 1e-12) << k;
  }
  std::vector<double> ratio;
  std::vector<int> first_order, zero_order;
  contactrb::online::OnlineSettings from_point;
  for (const cases::Mu& mu : cases::uniform_random(box_of(spec), 30, 43)) {
    Eigen::Index nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < P; ++i) {
      const double d = (m.training_mu.col(i) - mu).cwiseQuotient(range).squaredNorm();
      if (d < best) {
        best = d;
        nearest = i;
      }
    }
    const auto answer = solver.solve(mu);
    ASSERT_TRUE(answer.converged()) << answer.message;
    const Eigen::VectorXd zero = m.training_u_hat.col(nearest);
    const Eigen::VectorXd first = zero + m.training_u_sensitivity.middleCols(nearest * p, p) * (mu - m.training_mu.col(nearest));
    ratio.push_back((first - answer.u_hat).norm() / (zero - answer.u_hat).norm());
    Eigen::VectorXd start(N + m.R_max);
    start << zero, m.training_lambda_hat.col(nearest);
    from_point.start = start;
    const auto plain = solver.solve(mu, from_point);
    ASSERT_TRUE(plain.converged()) << plain.message;
    first_order.push_back(answer.iterations);
    zero_order.push_back(plain.iterations);
  }
  std::sort(ratio.begin(), ratio.end());
  std::sort(first_order.begin(), first_order.end());
  std::sort(zero_order.begin(), zero_order.end());
  std::printf("[ hertz-3p ] start error ratio first/zero order: median %.3f max %.3f; steps median %d against %d\n",
              ratio[ratio.size() / 2], ratio.back(), first_order[first_order.size() / 2], zero_order[zero_order.size() / 2]);
  EXPECT_LT(ratio[ratio.size() / 2], 0.5);
  EXPECT_LT(first_order[first_order.size() / 2], zero_order[zero_order.size() / 2]);
}

// The Jacobian is a function of the model, mu and u_hat only (each step's QP starts from the
// same passive set): the same bits after other solves; and its eigenvalues are those of a
// contraction at a converged training point (the plain iteration converges there).
TEST(PreconditionedIteration, JacobianDependsOnItsArgumentsOnly) {
  const offline::OfflineResult& off = row_cone_model(EstimateCase{"hertz-3p", 1e-7, 40});
  const auto& m = off.model;
  contactrb::online::OnlineSolver solver(m);
  const cases::Mu mu = m.training_mu.col(3);
  const auto sol = solver.solve(mu);
  ASSERT_TRUE(sol.converged()) << sol.message;
  const Eigen::MatrixXd first = solver.fixed_point_jacobian(mu, sol.u_hat);
  (void)solver.solve(m.training_mu.col(7));
  const Eigen::MatrixXd second = solver.fixed_point_jacobian(mu, sol.u_hat);
  ASSERT_EQ(first.rows(), m.N_max);
  EXPECT_EQ((first - second).cwiseAbs().maxCoeff(), 0.0);
  const double rho = first.eigenvalues().cwiseAbs().maxCoeff();
  EXPECT_GT(rho, 0.0);
  EXPECT_LT(rho, 1.0);
  EXPECT_THROW((void)solver.fixed_point_jacobian(mu, Eigen::VectorXd::Zero(m.N_max + 1)), contactrb::Error);
}

// The linearized Jacobian (one KKT system from the reduced Newton's contact linearization) is the
// difference one at converged points: relative Frobenius difference at the level of the
// differences' error (step 1e-7 |u_hat|) on hertz-3p's training points, and of the wrong sizes
// refused.
TEST(PreconditionedIteration, LinearizedJacobianIsTheDifferenceOne) {
  const offline::OfflineResult& off = row_cone_model(EstimateCase{"hertz-3p", 1e-7, 40});
  const auto& m = off.model;
  contactrb::online::OnlineSolver solver(m);
  contactrb::online::OnlineSettings tight;
  tight.kacanov = contactrb::solve::KacanovSettings{1.0, 1e-12, 200};
  tight.error_estimate = false;
  double worst = 0.0;
  for (Eigen::Index i = 0; i < std::min<Eigen::Index>(m.training_mu.cols(), 8); ++i) {
    const cases::Mu mu = m.training_mu.col(i);
    const auto sol = solver.solve(mu, tight);
    ASSERT_TRUE(sol.converged()) << sol.message;
    const Eigen::MatrixXd differences = solver.fixed_point_jacobian(mu, sol.u_hat);
    const Eigen::MatrixXd linearized = solver.linearized_fixed_point_jacobian(mu, sol.u_hat, sol.lambda_hat);
    ASSERT_EQ(linearized.rows(), m.N_max);
    ASSERT_EQ(linearized.cols(), m.N_max);
    ASSERT_GT(differences.norm(), 0.0);
    worst = std::max(worst, (linearized - differences).norm() / differences.norm());
  }
  std::printf("[ hertz-3p ] linearized against difference Jacobian: max relative difference %.2e\n", worst);
  EXPECT_LT(worst, 1e-4);
  EXPECT_THROW((void)solver.linearized_fixed_point_jacobian(m.training_mu.col(0), Eigen::VectorXd::Zero(m.N_max),
                                                            Eigen::VectorXd::Zero(m.R_max + 1)),
               contactrb::Error);
}

// Below the model's N the map is another one: no preconditioner, the plain iteration's bits; a
// model whose Jacobians have the wrong shape is refused by name.
TEST(PreconditionedIteration, TruncatedSizesAndMalformedJacobians) {
  const offline::OfflineResult& off = row_cone_model(EstimateCase{"hertz-3p", 1e-7, 40});
  contactrb::online::OnlineSolver truncated(off.model, {off.model.N_max - 1, -1, -1, -1});
  contactrb::online::OnlineSettings plain;
  plain.preconditioned = false;
  const cases::Mu mu = off.model.training_mu.col(0) * 0.5 + off.model.training_mu.col(1) * 0.5;
  const auto a = truncated.solve(mu);
  const auto b = truncated.solve(mu, plain);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ((a.u_hat - b.u_hat).cwiseAbs().maxCoeff(), 0.0);
  auto bad = off.model;
  bad.training_jacobian.conservativeResize(bad.N_max, bad.N_max);
  try {
    contactrb::online::OnlineSolver refused(bad);
    ADD_FAILURE() << "a model with one Jacobian for " << bad.training_mu.cols() << " training points was accepted";
  } catch (const contactrb::Error& e) {
    EXPECT_NE(std::string(e.what()).find("training_jacobian is"), std::string::npos) << e.what();
  }
}

// eta_p against its definition: -v'Hv / v'A v <= eta_p for directions v with D_A v = 0 (random,
// projected), over every free DOF rather than the Schur-reduced few.
TEST(GeometricRatio, BoundsRandomDirectionsThatKeepTheActiveRowsClosed) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-a");
  const cases::Mu mu = cases::Mu::Constant(1, 0.4);
  const contactrb::io::SnapshotSet set = snapshots_at(spec, {mu});
  const contactrb::io::Snapshot& snap = set.snapshots.front();
  const auto reference = cases::reference_mesh(spec, 0);
  const auto d = contactrb::contact::discretization_from_string(set.constraint);
  const double eta = offline::geometric_ratio(spec, reference, d, snap);
  ASSERT_GT(eta, 0.0);

  const contactrb::hf::HFSolver solver(cases::make_problem(spec, reference, mu, d));
  const auto& dofs = solver.dofs();
  const auto lin = linearization_of(solver, snap);
  std::vector<char> movable(static_cast<std::size_t>(dofs.num_dofs()), 0);
  for (int i : dofs.free_dofs()) movable[static_cast<std::size_t>(i)] = 1;
  std::vector<Index> active;
  for (Index r = 0; r < snap.lambda.size(); ++r) {
    if (snap.lambda(r) > 0.0) active.push_back(r);
  }
  ASSERT_GE(active.size(), 2u);
  Eigen::MatrixXd DA(static_cast<Index>(active.size()), dofs.num_dofs());
  for (std::size_t a = 0; a < active.size(); ++a) DA.row(static_cast<Index>(a)) = lin.D.row(active[a]);
  const Eigen::MatrixXd gram = DA * DA.transpose();
  const Eigen::LDLT<Eigen::MatrixXd> gram_ldlt(gram);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  double largest = 0.0;
  for (int k = 0; k < 200; ++k) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(dofs.num_dofs());
    // Random values on the contact DOFs H touches (elsewhere the ratio only falls), then on
    // every free DOF, projected on D_A v = 0 and zero on the prescribed DOFs.
    for (Index i = 0; i < v.size(); ++i) {
      if (movable[static_cast<std::size_t>(i)] && (k % 2 == 1 || lin.H.col(i).norm() > 0.0)) v(i) = normal(rng);
    }
    v -= DA.transpose() * gram_ldlt.solve(DA * v);
    for (Index i = 0; i < v.size(); ++i) {
      if (!movable[static_cast<std::size_t>(i)]) v(i) = 0.0;
    }
    ASSERT_LT((DA * v).norm(), 1e-8 * DA.norm() * v.norm());
    const double ratio = -v.dot(lin.H * v) / v.dot(solver.stiffness() * v);
    EXPECT_LE(ratio, eta * (1.0 + 1e-8)) << "direction " << k;
    largest = std::max(largest, ratio);
  }
  std::printf("[ hertz-a mu 0.4 ] eta_p %.4f, largest random ratio %.4f\n", eta, largest);
}

// The block of A_00^-1 a Kacanov solver holds against the dense inverse of A_00, and eta_p from
// the snapshot's own solver (that block, no second factorization) against eta_p from a fresh
// factorization (CHOLMOD): the same to round-off, on the greedy's three-parameter case.
TEST(GeometricRatio, FromTheSolversOwnFactorEqualsTheFreshlyFactoredOne) {
  for (const char* name : {"hertz-a", "hertz-3p"}) {
    const cases::CaseSpec spec = cases::builtin_case_spec(name);
    const auto reference = cases::reference_mesh(spec, 0);
    std::vector<cases::Mu> points;
    for (double t : {0.3, 0.7}) {
      cases::Mu mu(static_cast<Index>(spec.parameters.size()));
      for (Index k = 0; k < mu.size(); ++k) {
        const auto& q = spec.parameters[static_cast<std::size_t>(k)];
        mu(k) = q.min + t * (q.max - q.min);
      }
      points.push_back(mu);
    }
    offline::SnapshotRequest r = offline::make_snapshot_request(spec, "training", 0, std::nullopt, points);
    ASSERT_EQ(r.settings.method, contactrb::hf::HFMethod::Kacanov) << name;  // level 0: the condensation's factor
    std::vector<double> held(points.size(), -1.0), block_error(points.size(), -1.0);
    offline::SnapshotRunOptions options;
    options.after_solve = [&](std::size_t k, const contactrb::io::Snapshot& snap,
                              const contactrb::hf::HFSolver& solver) {
      const auto& dofs = solver.dofs();
      std::vector<int> idx;  // every free DOF of the slave boundary
      for (int node : solver.pair().slave) {
        for (int c = 0; c < 2; ++c) {
          const auto at = std::find(dofs.free_dofs().begin(), dofs.free_dofs().end(), 2 * node + c);
          if (at != dofs.free_dofs().end()) idx.push_back(static_cast<int>(at - dofs.free_dofs().begin()));
        }
      }
      const std::optional<Eigen::MatrixXd> block = solver.held_inverse_block(idx);
      if (!block) return;
      const Eigen::MatrixXd inverse =
          Eigen::MatrixXd(dofs.restrict_matrix(solver.stiffness())).ldlt().solve(
              Eigen::MatrixXd::Identity(dofs.num_free(), dofs.num_free()));
      const std::vector<Index> at(idx.begin(), idx.end());
      block_error[k] = (*block - inverse(at, at)).cwiseAbs().maxCoeff() / inverse(at, at).cwiseAbs().maxCoeff();
      std::vector<char> on_contact(static_cast<std::size_t>(dofs.num_dofs()), 0);
      for (const std::vector<int>* nodes : {&solver.pair().slave, &solver.pair().master}) {
        for (int node : *nodes) {
          for (int c = 0; c < 2; ++c) on_contact[static_cast<std::size_t>(2 * node + c)] = 1;
        }
      }
      int outside = 0;  // a free DOF off the contact boundaries: no entry of the held block
      while (on_contact[static_cast<std::size_t>(dofs.free_dofs()[static_cast<std::size_t>(outside)])]) ++outside;
      EXPECT_FALSE(solver.held_inverse_block({outside})) << name;
      held[k] = offline::geometric_ratio(solver, snap);
    };
    const contactrb::io::SnapshotSet set = offline::generate_snapshots(r, options);
    const auto d = contactrb::contact::discretization_from_string(set.constraint);
    for (std::size_t k = 0; k < points.size(); ++k) {
      ASSERT_TRUE(set.snapshots[k].converged) << name << " point " << k;
      ASSERT_GE(held[k], 0.0) << name << " point " << k << ": the solver held no factor";
      EXPECT_LT(block_error[k], 1e-10) << name << " point " << k;
      const double fresh = offline::geometric_ratio(spec, reference, d, set.snapshots[k]);
      EXPECT_GT(fresh, 0.0);
      EXPECT_NEAR(held[k], fresh, 1e-10 * fresh) << name << " point " << k;
      std::printf("[ %s point %zu ] eta_p from the held factor %.17g, fresh %.17g\n", name, k, held[k], fresh);
    }
  }
}

// The Newton method's factor (CHOLMOD, supernodal), kept with the solver for after_solve: the
// block of A_00^-1 on any free DOFs against the dense inverse, and eta_p from it against eta_p
// from a fresh factorization. A solver not asked to keep it holds none.
TEST(GeometricRatio, FromTheNewtonSolversFactorEqualsTheFreshlyFactoredOne) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-a");
  const auto reference = cases::reference_mesh(spec, 0);
  const cases::Mu mu = cases::Mu::Constant(1, 0.4);
  offline::SnapshotRequest r =
      offline::make_snapshot_request(spec, "training", 0, std::nullopt, std::vector<cases::Mu>{mu});
  r.settings.method = contactrb::hf::HFMethod::Newton;
  double held = -1.0, block_error = -1.0;
  offline::SnapshotRunOptions options;
  options.after_solve = [&](std::size_t, const contactrb::io::Snapshot& snap, const contactrb::hf::HFSolver& solver) {
    const auto& dofs = solver.dofs();
    const std::vector<int> idx{0, 7, dofs.num_free() / 2, dofs.num_free() - 1};
    const std::optional<Eigen::MatrixXd> block = solver.held_inverse_block(idx);
    if (!block) return;
    const Eigen::MatrixXd inverse = Eigen::MatrixXd(dofs.restrict_matrix(solver.stiffness()))
                                        .ldlt()
                                        .solve(Eigen::MatrixXd::Identity(dofs.num_free(), dofs.num_free()));
    const std::vector<Index> at(idx.begin(), idx.end());
    block_error = (*block - inverse(at, at)).cwiseAbs().maxCoeff() / inverse(at, at).cwiseAbs().maxCoeff();
    held = offline::geometric_ratio(solver, snap);
  };
  const contactrb::io::SnapshotSet set = offline::generate_snapshots(r, options);
  ASSERT_TRUE(set.snapshots.front().converged);
  ASSERT_GE(held, 0.0) << "the Newton solver kept no factor";
  EXPECT_LT(block_error, 1e-10);
  const auto d = contactrb::contact::discretization_from_string(set.constraint);
  const double fresh = offline::geometric_ratio(spec, reference, d, set.snapshots.front());
  EXPECT_NEAR(held, fresh, 1e-10 * fresh);

  const contactrb::hf::HFSolver plain(cases::make_problem(spec, reference, mu, d));
  ASSERT_TRUE(plain.solve(r.settings).converged);
  EXPECT_FALSE(plain.held_inverse_block({0}));
}

// A solver that has not solved holds no factor: the ratio from it factors A_00 itself.
TEST(GeometricRatio, FromASolverWithoutAFactorFactorsAZeroZeroItself) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-a");
  const cases::Mu mu = cases::Mu::Constant(1, 0.4);
  const contactrb::io::SnapshotSet set = snapshots_at(spec, {mu});
  const auto reference = cases::reference_mesh(spec, 0);
  const auto d = contactrb::contact::discretization_from_string(set.constraint);
  const contactrb::hf::HFSolver solver(cases::make_problem(spec, reference, mu, d));
  EXPECT_FALSE(solver.held_inverse_block({0}));
  EXPECT_EQ(offline::geometric_ratio(solver, set.snapshots.front()),
            offline::geometric_ratio(spec, reference, d, set.snapshots.front()));
}

// eta_p against an independent dense computation of its definition over every free DOF (no Schur
// reduction, no Lanczos): Z a basis of ker D_A on the free DOFs, then the largest eigenvalue of the
// dense pencil (Z'(-H)Z, Z'A_00 Z).
TEST(GeometricRatio, EqualsTheDenseGeneralizedEigenvalueOverEveryFreeDof) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-a");
  const auto reference = cases::reference_mesh(spec, 0);
  for (double value : {0.2, 0.4}) {
    const cases::Mu mu = cases::Mu::Constant(1, value);
    const contactrb::io::SnapshotSet set = snapshots_at(spec, {mu});
    const contactrb::io::Snapshot& snap = set.snapshots.front();
    const auto d = contactrb::contact::discretization_from_string(set.constraint);
    const double eta = offline::geometric_ratio(spec, reference, d, snap);

    const contactrb::hf::HFSolver solver(cases::make_problem(spec, reference, mu, d));
    const auto& dofs = solver.dofs();
    const auto lin = linearization_of(solver, snap);
    const Index n = dofs.num_free();
    const Eigen::MatrixXd H = Eigen::MatrixXd(lin.H);
    Eigen::MatrixXd minus_H(n, n);
    for (Index j = 0; j < n; ++j) {
      const Index gj = dofs.free_dofs()[static_cast<std::size_t>(j)];
      for (Index i = 0; i < n; ++i) {
        const Index gi = dofs.free_dofs()[static_cast<std::size_t>(i)];
        minus_H(i, j) = -0.5 * (H(gi, gj) + H(gj, gi));
      }
    }
    const Eigen::MatrixXd A = Eigen::MatrixXd(dofs.restrict_matrix(solver.stiffness()));
    std::vector<Index> active;
    for (Index r = 0; r < snap.lambda.size(); ++r) {
      if (snap.lambda(r) > 0.0) active.push_back(r);
    }
    ASSERT_GE(active.size(), 2u);
    const Eigen::MatrixXd D = Eigen::MatrixXd(dofs.restrict_columns(lin.D));
    Eigen::MatrixXd DA(static_cast<Index>(active.size()), n);
    for (std::size_t a = 0; a < active.size(); ++a) DA.row(static_cast<Index>(a)) = D.row(active[a]);
    const Eigen::MatrixXd Z = Eigen::FullPivLU<Eigen::MatrixXd>(DA).kernel();
    ASSERT_EQ(Z.cols(), n - static_cast<Index>(active.size()));
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
        Z.transpose() * minus_H * Z, Z.transpose() * A * Z, Eigen::EigenvaluesOnly);
    ASSERT_EQ(eig.info(), Eigen::Success);
    const double dense = eig.eigenvalues().maxCoeff();
    std::printf("[ hertz-a mu %.2f ] eta_p %.15f, dense over %ld free DOFs %.15f\n", value, eta,
                static_cast<long>(n), dense);
    ASSERT_GT(dense, 0.0);
    EXPECT_NEAR(eta, dense, 1e-10 * dense);
  }
}

}  // namespace
