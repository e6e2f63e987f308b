// The example cases in examples/ (docs/cases.md): each one is read, solved and checked
// against an independent truth.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/hf/hf_solver.hpp"

using namespace contactrb;

namespace {
std::string example(const std::string& name) {
  return std::string(CONTACTRB_SOURCE_DIR) + "/examples/" + name + "/case.toml";
}
}  // namespace

// examples/hertz-a: the built-in hertz-a written as a TOML case on the .msh exported by
// `contactrb mesh --case hertz-a`. Same mesh, same data: the same solution to round-off.
TEST(Examples, HertzATomlGivesTheBuiltinSolution) {
  const cases::CaseSpec toml = cases::case_from_toml_file(example("hertz-a"));
  const cases::CaseSpec builtin = cases::builtin_case_spec("hertz-a");
  EXPECT_EQ(cases::values_1d(toml.set("training")), cases::values_1d(builtin.set("training")));
  EXPECT_EQ(cases::values_1d(toml.set("verification")).size(), cases::values_1d(builtin.set("verification")).size());
  const mesh::Mesh toml_mesh = cases::reference_mesh(toml);
  const mesh::Mesh builtin_mesh = cases::reference_mesh(builtin);
  ASSERT_EQ(toml_mesh.num_nodes(), builtin_mesh.num_nodes());
  ASSERT_EQ(toml_mesh.triangles, builtin_mesh.triangles);
  for (int i = 0; i < toml_mesh.num_nodes(); ++i) {
    ASSERT_EQ(toml_mesh.nodes[static_cast<std::size_t>(i)], builtin_mesh.nodes[static_cast<std::size_t>(i)]) << i;
  }
  for (double mu : {0.15, 0.3}) {
    const hf::HFSolution a = hf::HFSolver(cases::make_problem(toml, toml_mesh, mu)).solve();
    const hf::HFSolution b = hf::HFSolver(cases::make_problem("hertz-a", mu)).solve();
    ASSERT_TRUE(a.converged && b.converged) << a.message << b.message;
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_LE((a.u - b.u).norm(), 1e-12 * b.u.norm()) << mu;
    ASSERT_EQ(a.lambda.size(), b.lambda.size());
    EXPECT_LE((a.lambda - b.lambda).norm(), 1e-12 * b.lambda.norm()) << mu;
    std::cout << "[ hertz-a toml ] mu = " << mu << ": |du|/|u| = " << (a.u - b.u).norm() / b.u.norm()
              << ", |dlambda|/|lambda| = " << (a.lambda - b.lambda).norm() / b.lambda.norm() << "\n";
  }
}

// examples/two-block-patch: the contact patch test through a user .msh with its own group
// names. Exact solution: uniaxial stress, uniform pressure p = E/(1 - nu^2) mu / 2.
TEST(Examples, TwoBlockPatchRecoversTheUniformPressureWithLac) {
  const cases::CaseSpec spec = cases::case_from_toml_file(example("two-block-patch"));
  EXPECT_EQ(spec.constraint, contact::Discretization::LAC);
  const mesh::Mesh ref = cases::reference_mesh(spec);
  EXPECT_EQ(mesh::boundary_nodes(ref, mesh::kSlaveBoundary).size(), 9u);
  EXPECT_EQ(mesh::boundary_nodes(ref, mesh::kMasterBoundary).size(), 12u);
  hf::HFSettings settings;
  settings.kacanov.alpha = 1.0;
  settings.kacanov.tolerance = 1e-12;
  for (double mu : cases::values_1d(spec.set("training"))) {
    const hf::HFSolution s = hf::HFSolver(cases::make_problem(spec, ref, mu)).solve(settings);
    ASSERT_TRUE(s.converged) << s.message;
    const double p = spec.bodies[0].E / (1.0 - spec.bodies[0].nu * spec.bodies[0].nu) * mu / 2.0;
    double worst = 0.0;
    for (int r = 0; r < s.lambda.size(); ++r) worst = std::max(worst, std::abs(s.lambda(r) - p) / p);
    EXPECT_LT(worst, 1e-10) << mu;
    std::cout << "[ patch ] mu = " << mu << ": p = " << p << ", max relative pressure error " << worst << ", "
              << s.iterations << " Kacanov iterations\n";
    EXPECT_NEAR(s.contact_force, p, 1e-10 * p) << mu;
  }
}

TEST(Examples, MshCaseRejectsRefinementAndMissingGroups) {
  cases::CaseSpec spec = cases::case_from_toml_file(example("two-block-patch"));
  EXPECT_THROW(cases::reference_mesh(spec, 1), Error);
  spec.dirichlet.push_back({"nowhere", cases::AffineValue{0.0, 0.0}, std::nullopt});
  try {
    cases::reference_mesh(spec);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'nowhere'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("two-block-patch.msh"), std::string::npos) << e.what();
  }
  spec = cases::case_from_toml_file(example("two-block-patch"));
  spec.mesh.slave_group = "upper_side";
  EXPECT_THROW(cases::reference_mesh(spec), Error);
}

// A parameter domain and the loads it scales are capped like the case's other data (1e50): a
// traction parameter on [0, 1e60], or a pressure of 1e40 scaled by a q up to 1e20, is refused.
TEST(Examples, TractionDomainsAreCappedLikeTheOtherData) {
  cases::CaseSpec spec = cases::case_from_toml_file(example("two-block-traction"));
  EXPECT_NO_THROW(cases::check_case_spec(spec));
  const auto q = static_cast<std::size_t>(cases::parameter_index(spec.parameters, "q"));
  cases::CaseSpec wide = spec;
  wide.parameters[q].max = 1e60;
  try {
    cases::check_case_spec(wide);
    ADD_FAILURE() << "a domain up to 1e60 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("parameter 'q': domain [") , std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reaches above 1e50 in magnitude"), std::string::npos) << e.what();
  }
  cases::CaseSpec heavy = spec;
  heavy.parameters[q].max = 1e20;
  for (cases::TractionSpec& t : heavy.tractions) t.pressure = 1e40;
  try {
    cases::check_case_spec(heavy);
    ADD_FAILURE() << "a load reaching 1e60 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the load scaled by 'q' reaches 1e+60 on the parameter domain, above 1e50"),
              std::string::npos)
        << e.what();
  }
}
