// Affine decomposition (paper (46), (49)): theta functions x offline terms on the reference
// mesh equal the direct assembly on the mapped mesh Omega(mu), for the three paper cases.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/geometric_map.hpp"
#include "contactrb/cases/theta.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"

using namespace contactrb;

namespace {

constexpr double kRelTol = 1e-12;

// Gmsh meshes are generated once per case for the whole test program.
const mesh::Mesh& reference(const std::string& name) {
  static std::map<std::string, mesh::Mesh> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, cases::reference_mesh(cases::builtin_case_spec(name))).first;
  return it->second;
}

double rel_diff(const fem::SparseMatrix& a, const fem::SparseMatrix& b) {
  return (a - b).norm() / std::max(a.norm(), b.norm());
}
double rel_diff(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm() / std::max(a.norm(), b.norm());
}

// Compares sum theta_j(mu) X_j with the direct assembly at mu for A, f and u_D.
void expect_decomposition_exact(const cases::CaseSpec& spec, const mesh::Mesh& ref, double value) {
  SCOPED_TRACE(spec.name + " at mu = " + std::to_string(value));
  const cases::Mu mu = cases::Mu::Constant(1, value);
  const cases::AffineTerms terms = cases::assemble_affine_terms(spec, ref);
  const cases::AffineThetas thetas = cases::theta_functions(spec);
  ASSERT_EQ(terms.A.size(), thetas.a.size());
  ASSERT_EQ(terms.f.size(), thetas.f.size());
  ASSERT_EQ(terms.lift.size(), thetas.lift.size());

  const hf::ContactProblem p = cases::make_problem(spec, ref, mu);
  const fem::SparseMatrix A_direct = fem::stiffness(p.mesh, p.materials);
  EXPECT_LT(rel_diff(A_direct, cases::combine(terms.A, cases::evaluate(thetas.a, mu))), kRelTol);

  Eigen::VectorXd f_direct = Eigen::VectorXd::Zero(p.mesh.num_dofs());
  for (std::size_t b = 0; b < p.body_loads.size(); ++b) {
    f_direct += fem::body_load(p.mesh, static_cast<int>(b), p.body_loads[b]);
  }
  const Eigen::VectorXd f_affine = cases::combine(terms.f, cases::evaluate(thetas.f, mu), p.mesh.num_dofs());
  if (f_direct.norm() == 0.0) {
    EXPECT_EQ(f_affine.norm(), 0.0);
  } else {
    EXPECT_LT(rel_diff(f_direct, f_affine), kRelTol);
  }

  const Eigen::VectorXd lift_direct = fem::DofMap(p.mesh, p.dirichlet).lift();
  const Eigen::VectorXd lift_affine =
      cases::combine(terms.lift, cases::evaluate(thetas.lift, mu), p.mesh.num_dofs());
  if (lift_direct.norm() == 0.0) {
    EXPECT_EQ(lift_affine.norm(), 0.0);
  } else {
    EXPECT_LT(rel_diff(lift_direct, lift_affine), kRelTol);
  }
}

std::vector<double> sample(const cases::ParameterSpec& p) {
  return {p.min, p.reference, 0.5 * (p.min + p.max) + 0.0123 * (p.max - p.min), p.max};
}

}  // namespace

class AffineDecomposition : public ::testing::TestWithParam<std::string> {};

TEST_P(AffineDecomposition, EqualsDirectAssemblyOnTheMappedMesh) {
  const cases::CaseSpec spec = cases::builtin_case_spec(GetParam());
  for (double mu : sample(spec.parameters.front())) expect_decomposition_exact(spec, reference(GetParam()), mu);
}

// The paper cases have no body load; with loads on both bodies f(mu) has one term per
// body, theta = s^2 on the scaled one (paper (48)).
TEST_P(AffineDecomposition, BodyLoadsScaleWithTheJacobian) {
  cases::CaseSpec spec = cases::builtin_case_spec(GetParam());
  spec.bodies[0].load = Eigen::Vector2d(0.3, -1.0);
  spec.bodies[1].load = Eigen::Vector2d(-0.7, 0.2);
  const cases::AffineThetas thetas = cases::theta_functions(spec);
  ASSERT_EQ(thetas.f.size(), 2u);
  for (double mu : sample(spec.parameters.front())) expect_decomposition_exact(spec, reference(GetParam()), mu);
}

INSTANTIATE_TEST_SUITE_P(PaperCases, AffineDecomposition, ::testing::Values("hertz-a", "hertz-b", "ring-block"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n) c = c == '-' ? '_' : c;
                           return n;
                         });

TEST(AffineDecomposition, TermCountsOfThePaperCases) {
  // (a): u_D affine in mu, A and f independent of mu: J^a = 1, J^D = 2.
  const cases::AffineThetas a = cases::theta_functions(cases::builtin_case_spec("hertz-a"));
  EXPECT_EQ(a.a.size(), 1u);
  EXPECT_EQ(a.f.size(), 0u);
  ASSERT_EQ(a.lift.size(), 2u);
  EXPECT_DOUBLE_EQ(a.lift[1](cases::Mu::Constant(1, 0.37)), 0.37);
  // (b), (c): uniform scaling, J^a = 1 (2D stiffness invariant), constant lift.
  for (const char* name : {"hertz-b", "ring-block"}) {
    const cases::AffineThetas t = cases::theta_functions(cases::builtin_case_spec(name));
    EXPECT_EQ(t.a.size(), 1u) << name;
    EXPECT_DOUBLE_EQ(t.a[0](cases::Mu::Constant(1, 1.1)), 1.0) << name;
    EXPECT_EQ(t.lift.size(), 1u) << name;
  }
}

TEST(ThetaMonomial, Evaluates) {
  const auto one = [](double x) { return cases::Mu::Constant(1, x); };
  EXPECT_DOUBLE_EQ((cases::ThetaMonomial{2.0, {}})(one(5.0)), 2.0);
  EXPECT_DOUBLE_EQ((cases::ThetaMonomial{1.0, {{0, 2.0, 2}}})(one(3.0)), 2.25);
  EXPECT_DOUBLE_EQ((cases::ThetaMonomial{1.0, {{0, 1.0, -1}}})(one(4.0)), 0.25);
  EXPECT_EQ(cases::evaluate({}, one(1.0)).size(), 0);
  // A product over parameters: 3 (mu_0 / 2)^2 (mu_2 / 1)^-1.
  EXPECT_DOUBLE_EQ((cases::ThetaMonomial{3.0, {{0, 2.0, 2}, {2, 1.0, -1}}})(Eigen::Vector3d(4.0, 9.0, 0.5)), 24.0);
}

TEST(AffineCombination, SizeMismatchThrows) {
  EXPECT_THROW(cases::combine(std::vector<fem::SparseMatrix>(2), Eigen::VectorXd::Ones(1)), Error);
  EXPECT_THROW(cases::combine(std::vector<Eigen::VectorXd>{Eigen::VectorXd::Zero(3)}, Eigen::VectorXd::Ones(1), 4),
               Error);
}

TEST(GeometricMap, IdentityAtTheReferenceAndScalingAboutTheCenter) {
  const std::vector<cases::ParameterSpec> ps = cases::builtin_case_spec("hertz-b").parameters;
  const cases::ParameterSpec& p = ps.front();
  for (const cases::AffineMap& h : cases::geometric_maps(ps, cases::Mu::Constant(1, p.reference))) {
    EXPECT_TRUE(h.is_identity());
  }
  const auto maps = cases::geometric_maps(ps, cases::Mu::Constant(1, 1.1));
  EXPECT_TRUE(maps[0].is_identity());
  EXPECT_NEAR(maps[1].jacobian(), 1.21, 1e-15);
  EXPECT_LT((maps[1](p.center) - p.center).norm(), 1e-15);
  const Eigen::Vector2d x(0.3, -0.8);
  EXPECT_LT((maps[1](x) - (p.center + 1.1 * (x - p.center))).norm(), 1e-15);
}
