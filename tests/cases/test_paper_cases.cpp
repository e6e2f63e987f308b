// The three paper cases (Section 6) through CaseSpec: data, parameter sets, hertz-b
// geometry invariants, ring-block contact zone varying with mu (Fig. 18).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/catalog.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/hf/hf_solver.hpp"

using namespace contactrb;

namespace {

void expect_set(const std::vector<double>& v, double start, double step, int count) {
  ASSERT_EQ(static_cast<int>(v.size()), count);
  for (int i = 0; i < count; ++i) EXPECT_NEAR(v[static_cast<std::size_t>(i)], start + step * i, 1e-14) << i;
}

std::set<int> active_set(const hf::HFSolution& s) {
  std::set<int> a;
  for (int r = 0; r < s.lambda.size(); ++r) {
    if (s.lambda(r) > 0.0) a.insert(r);
  }
  return a;
}

}  // namespace

TEST(PaperCases, ParameterSetsAreThePapers) {
  const cases::CaseSpec a = cases::builtin_case_spec("hertz-a");
  expect_set(cases::values_1d(a.set("training")), 0.15, 0.01, 31);
  expect_set(cases::values_1d(a.set("verification")), 0.155, 0.01, 30);
  const cases::CaseSpec b = cases::builtin_case_spec("hertz-b");
  expect_set(cases::values_1d(b.set("training")), 0.905, 0.01, 22);  // i = 0..21: inside [0.9, 1.12] (docs/cases.md)
  expect_set(cases::values_1d(b.set("verification")), 0.91, 0.01, 21);
  const cases::CaseSpec c = cases::builtin_case_spec("ring-block");
  expect_set(cases::values_1d(c.set("training")), 0.95, 0.01, 21);
  expect_set(cases::values_1d(c.set("verification")), 0.9575, 0.02, 10);  // i = 0..9: inside P (docs/cases.md)
  EXPECT_THROW(c.set("test"), Error);
}

TEST(PaperCases, SpecsAreValidAndNamedLikeTheCatalog) {
  for (const cases::CaseInfo& info : cases::builtin_cases()) {
    const cases::CaseSpec spec = cases::builtin_case_spec(info.name);
    EXPECT_EQ(spec.name, info.name);
    EXPECT_NO_THROW(cases::check_case_spec(spec));
    const cases::ParameterDomain& d = cases::parameter_domain(info.name);
    EXPECT_EQ(d.min, spec.parameters.front().min);
    EXPECT_EQ(d.max, spec.parameters.front().max);
  }
  EXPECT_THROW(cases::builtin_case_spec("hertz-c"), Error);
  EXPECT_EQ(cases::builtin_case_spec("ring-block").constraint, contact::Discretization::LAC);
  EXPECT_EQ(cases::builtin_case_spec("hertz-b").constraint, contact::Discretization::Collocation);
}

TEST(PaperCases, ParameterOutsideTheDomainIsRejected) {
  EXPECT_THROW(cases::make_problem("hertz-a", 0.5), Error);
  EXPECT_THROW(cases::make_problem(cases::builtin_case_spec("hertz-b"), std::nan("")), Error);
  try {
    cases::check_parameter("ring-block", 1.2);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ring-block"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("[0.95, 1.15]"), std::string::npos) << e.what();
  }
}

TEST(PaperCases, HertzADirichletDataAreAffineInMu) {
  const hf::ContactProblem p = cases::make_problem("hertz-a", 0.2);
  ASSERT_EQ(p.dirichlet.size(), 2u);
  EXPECT_EQ(p.dirichlet[0].group, "top");
  EXPECT_DOUBLE_EQ(*p.dirichlet[0].uy, -0.1);
  EXPECT_DOUBLE_EQ(*p.dirichlet[1].uy, 0.1);
  EXPECT_DOUBLE_EQ(*p.dirichlet[1].ux, 0.0);
}

// Uniform scaling of body 2 by s: grad phi scales by 1/s, the area by s^2, so the 2D
// stiffness matrix of the body is unchanged (the J^a = 1 the affine decomposition uses).
TEST(PaperCases, HertzBScalingLeavesTheStiffnessOfBody2Unchanged) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-b");
  const mesh::Mesh ref = cases::reference_mesh(spec);
  const fem::Material material{spec.bodies[1].E, spec.bodies[1].nu};
  const fem::SparseMatrix K_ref = fem::stiffness_body(ref, mesh::kMasterBody, material);
  for (double mu : {0.9, 0.955, 1.12}) {
    const mesh::Mesh m = cases::mapped_mesh(spec, ref, mu);
    EXPECT_GT((m.nodes[ref.triangles.back()[0]] - ref.nodes[ref.triangles.back()[0]]).norm(), 1e-3);
    const fem::SparseMatrix K = fem::stiffness_body(m, mesh::kMasterBody, material);
    EXPECT_LT((K - K_ref).norm() / K_ref.norm(), 1e-13) << mu;
  }
}

TEST(PaperCases, HertzBInitialGapOnTheVerticalAxisIs01) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-b");
  const mesh::Mesh ref = cases::reference_mesh(spec);
  for (double mu : cases::values_1d(spec.set("training"))) {
    const mesh::Mesh m = cases::mapped_mesh(spec, ref, mu);
    double slave_low = INFINITY, master_high = -INFINITY;
    for (int n : mesh::boundary_nodes(m, mesh::kSlaveBoundary)) slave_low = std::min(slave_low, m.nodes[n].y());
    for (int n : mesh::boundary_nodes(m, mesh::kMasterBoundary)) master_high = std::max(master_high, m.nodes[n].y());
    EXPECT_NEAR(slave_low - master_high, 0.1, 1e-12) << mu;
    // The master arc's radius is mu: its width is 2 mu.
    double xmin = INFINITY, xmax = -INFINITY;
    for (int n : mesh::boundary_nodes(m, mesh::kMasterBoundary)) {
      xmin = std::min(xmin, m.nodes[n].x());
      xmax = std::max(xmax, m.nodes[n].x());
    }
    EXPECT_NEAR(xmax - xmin, 2.0 * mu, 1e-12) << mu;
  }
}

// Paper Fig. 18: the contact zone of the ring depends on its radius.
TEST(PaperCases, RingBlockActiveSetsDifferBetweenMu1And113) {
  const cases::CaseSpec spec = cases::builtin_case_spec("ring-block");
  const mesh::Mesh ref = cases::reference_mesh(spec);
  std::vector<std::set<int>> active;
  for (double mu : {1.0, 1.13}) {
    const hf::HFSolver solver(cases::make_problem(spec, ref, mu));
    const hf::HFSolution s = solver.solve();
    ASSERT_TRUE(s.converged) << mu << ": " << s.message;
    active.push_back(active_set(s));
    std::cout << "[ ring-block ] mu = " << mu << ": " << active.back().size() << " active of " << s.lambda.size()
              << " (rows " << *active.back().begin() << ".." << *active.back().rbegin() << "), "
              << s.iterations << " Kacanov iterations, contact force " << s.contact_force << "\n";
    EXPECT_GT(active.back().size(), 2u);
  }
  EXPECT_NE(active[0], active[1]);
}
