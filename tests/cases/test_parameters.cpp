// p parameters (docs/cases.md "Parameters"): a frozen parameter gives the
// one-parameter case, the affine decomposition of the young-modulus, traction and body-force
// kinds equals the direct assembly at random points, the traction patch test, and one clear
// error per bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <random>
#include <string>

#include "contactrb/cases/affine_assembly.hpp"
#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/cases/theta.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/traction.hpp"
#include "contactrb/hf/hf_solver.hpp"

using namespace contactrb;

namespace {

std::string example(const std::string& name) {
  return std::string(CONTACTRB_SOURCE_DIR) + "/examples/" + name + "/case.toml";
}

std::string read_example(const std::string& name) {
  std::ifstream in(example(name));
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The error message of reading `text` as a case file next to the traction example (its .msh
// resolves), or "" when it reads.
std::string toml_error(const std::string& text) {
  try {
    (void)cases::case_from_toml_string(text, example("two-block-traction"));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("test: '" + from + "' not in the text");
  return text.replace(at, from.size(), to);
}

double relative(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double scale = std::max(a.norm(), b.norm());
  return scale == 0.0 ? 0.0 : (a - b).norm() / scale;
}

double relative(const fem::SparseMatrix& a, const fem::SparseMatrix& b) {
  return Eigen::MatrixXd(a - b).norm() / std::max(Eigen::MatrixXd(a).norm(), 1e-300);
}

// A random point of the case's box (fixed seed).
cases::Mu random_point(const cases::CaseSpec& spec, std::mt19937_64& rng) {
  cases::Mu mu(spec.num_parameters());
  for (int k = 0; k < spec.num_parameters(); ++k) {
    const cases::ParameterSpec& p = spec.parameters[static_cast<std::size_t>(k)];
    mu(k) = p.min + (p.max - p.min) * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
  }
  return mu;
}

// sum theta_j(mu) terms_j against the assembly on Omega(mu) with the data at mu.
void expect_affine_equals_direct(const cases::CaseSpec& spec, int points) {
  const mesh::Mesh reference = cases::reference_mesh(spec);
  const cases::AffineTerms terms = cases::assemble_affine_terms(spec, reference);
  const cases::AffineThetas thetas = cases::theta_functions(spec);
  std::mt19937_64 rng(7);
  for (int i = 0; i < points; ++i) {
    const cases::Mu mu = random_point(spec, rng);
    const mesh::Mesh m = cases::mapped_mesh(spec, reference, mu);
    const fem::SparseMatrix A = fem::stiffness(m, cases::materials(spec, mu));
    EXPECT_LT(relative(cases::combine(terms.A, cases::evaluate(thetas.a, mu)), A), 1e-12) << spec.name << " A";
    Eigen::VectorXd f = Eigen::VectorXd::Zero(m.num_dofs());
    const std::vector<Eigen::Vector2d> loads = cases::body_loads_at(spec, mu);
    for (std::size_t b = 0; b < loads.size(); ++b) f += fem::body_load(m, static_cast<int>(b), loads[b]);
    for (const fem::TractionLoad& t : cases::tractions_at(spec, mu)) f += fem::traction_load(m, t);
    EXPECT_LT(relative(cases::combine(terms.f, cases::evaluate(thetas.f, mu), m.num_dofs()), f), 1e-12)
        << spec.name << " f";
    const Eigen::VectorXd lift = fem::DofMap(m, cases::dirichlet_at(spec, mu)).lift();
    EXPECT_LT(relative(cases::combine(terms.lift, cases::evaluate(thetas.lift, mu), m.num_dofs()), lift), 1e-12)
        << spec.name << " lift";
  }
}

}  // namespace

// hertz-3p at R2 = 1, E2 = 15 is hertz-a: the same HF solution (the stiffness is assembled per
// body there, as one matrix in hertz-a: round-off only).
TEST(Parameters, FrozenParametersGiveTheOneParameterCase) {
  const cases::CaseSpec three = cases::builtin_case_spec("hertz-3p");
  ASSERT_EQ(three.num_parameters(), 3);
  for (double delta : {0.2, 0.4}) {
    const hf::HFSolution a = hf::HFSolver(cases::make_problem(three, Eigen::Vector3d(delta, 1.0, 15.0))).solve();
    const hf::HFSolution b = hf::HFSolver(cases::make_problem("hertz-a", delta)).solve();
    ASSERT_TRUE(a.converged && b.converged);
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_LT(relative(a.u, b.u), 1e-12) << delta;
    EXPECT_LT(relative(a.lambda, b.lambda), 1e-12) << delta;
    EXPECT_NEAR(a.energy, b.energy, 1e-12 * std::abs(b.energy));
  }
}

// Moving one parameter of hertz-3p away from the frozen point changes the answer the way its
// physics says: a stiffer lower body carries more force at the same imposed displacement.
TEST(Parameters, YoungModulusParameterStiffensTheContact) {
  const cases::CaseSpec three = cases::builtin_case_spec("hertz-3p");
  const hf::HFSolution soft = hf::HFSolver(cases::make_problem(three, Eigen::Vector3d(0.3, 1.0, 7.5))).solve();
  const hf::HFSolution stiff = hf::HFSolver(cases::make_problem(three, Eigen::Vector3d(0.3, 1.0, 30.0))).solve();
  ASSERT_TRUE(soft.converged && stiff.converged);
  EXPECT_GT(stiff.contact_force, 1.2 * soft.contact_force);
}

TEST(Parameters, AffineDecompositionOfEveryKindEqualsTheDirectAssembly) {
  expect_affine_equals_direct(cases::builtin_case_spec("hertz-3p"), 4);
  expect_affine_equals_direct(cases::case_from_toml_file(example("two-block-traction")), 4);
  // Body force and a traction on a scaled body: hertz-3p with a body-force parameter on the
  // (scaled) master and a fixed pressure on the master's bottom edge (theta = s).
  cases::CaseSpec c = cases::builtin_case_spec("hertz-3p");
  c.bodies[1].load = Eigen::Vector2d(0.1, -0.2);
  cases::ParameterSpec g;
  g.name = "g";
  g.kind = cases::ParameterKind::BodyForce;
  g.body = 1;
  g.min = 0.5;
  g.max = 2.0;
  g.reference = 1.0;
  c.parameters.push_back(g);
  for (cases::ParameterSet& s : c.sets) {
    for (cases::Mu& mu : s.points) {
      mu.conservativeResize(4);
      mu(3) = 1.0;
    }
  }
  c.tractions.push_back({"bottom", true, Eigen::Vector2d::Zero(), 0.3, -1, 1});
  c.tractions.push_back({"top", false, Eigen::Vector2d(0.05, 0.0), 0.0, -1, 0});
  c.origin = "test";
  expect_affine_equals_direct(c, 4);
}

// The traction patch test (examples/two-block-traction): a uniform stress with sigma_xx = -q
// and eps_yy = -delta / 2, so every LAC row carries the same, known pressure.
TEST(Parameters, TractionPatchTestGivesTheUniformContactPressure) {
  const cases::CaseSpec spec = cases::case_from_toml_file(example("two-block-traction"));
  ASSERT_EQ(spec.num_parameters(), 2);
  const mesh::Mesh reference = cases::reference_mesh(spec);
  const double E = 10.0, nu = 0.3;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu_l = E / (2 * (1 + nu));
  hf::HFSettings settings;
  settings.kacanov.alpha = 1.0;
  settings.kacanov.tolerance = 1e-12;
  for (const Eigen::Vector2d& point : {Eigen::Vector2d(0.02, 0.1), Eigen::Vector2d(0.01, 0.2), Eigen::Vector2d(0.03, 0.0)}) {
    const double delta = point(0), q = point(1);
    const double eyy = -delta / 2, exx = (-q - lambda * eyy) / (lambda + 2 * mu_l);
    const double p = -(lambda * (exx + eyy) + 2 * mu_l * eyy);
    const hf::HFSolution s = hf::HFSolver(cases::make_problem(spec, reference, point)).solve(settings);
    ASSERT_TRUE(s.converged) << s.message;
    ASSERT_GT(s.lambda.size(), 0);
    for (Eigen::Index r = 0; r < s.lambda.size(); ++r) EXPECT_NEAR(s.lambda(r), p, 1e-10 * p) << "row " << r;
  }
  // q = 0 is the plain patch test, p = E / (1 - nu^2) delta / 2.
  const hf::HFSolution s = hf::HFSolver(cases::make_problem(spec, reference, Eigen::Vector2d(0.02, 0.0))).solve(settings);
  EXPECT_NEAR(s.lambda(0), E / (1 - nu * nu) * 0.01, 1e-10);
}

TEST(Parameters, TractionLoadOfAUniformPressureIsItsResultant) {
  // A pressure p on the right side of the upper unit block: resultant (-p, 0) x length 1.
  const cases::CaseSpec spec = cases::case_from_toml_file(example("two-block-traction"));
  const mesh::Mesh m = cases::reference_mesh(spec);
  const Eigen::VectorXd f = fem::traction_load(m, {"upper_right", true, Eigen::Vector2d::Zero(), 2.5});
  double fx = 0.0, fy = 0.0;
  for (int i = 0; i < m.num_nodes(); ++i) {
    fx += f(2 * i);
    fy += f(2 * i + 1);
  }
  EXPECT_NEAR(fx, -2.5, 1e-12);
  EXPECT_NEAR(fy, 0.0, 1e-12);
  EXPECT_EQ(fem::traction_body(m, "upper_right"), 0);
  EXPECT_EQ(fem::traction_body(m, "lower_right"), 1);
}

TEST(Parameters, BadParameterInputGivesOneClearError) {
  const std::string good = read_example("two-block-traction");
  ASSERT_EQ(toml_error(good), "");
  const auto expect_error = [&](const std::string& text, std::initializer_list<const char*> parts) {
    const std::string e = toml_error(text);
    ASSERT_FALSE(e.empty()) << "no error";
    for (const char* part : parts) EXPECT_NE(e.find(part), std::string::npos) << e << "\n(expected: " << part << ")";
  };
  // A domain inverted.
  expect_error(replaced(good, "domain = [0.0, 0.2]", "domain = [0.2, 0.0]"), {"parameter[2].domain", "not an interval"});
  // A traction naming an unknown parameter, and one naming a parameter of another kind.
  expect_error(replaced(good, "parameter = \"q\"", "parameter = \"qq\""), {"unknown parameter 'qq'", "delta, q"});
  expect_error(replaced(good, "parameter = \"q\"", "parameter = \"delta\""), {"of kind dirichlet-scale"});
  // A Dirichlet value naming an unknown parameter.
  expect_error(replaced(good, "parameter = \"delta\" }", "parameter = \"d\" }"), {"unknown parameter 'd'"});
  // A traction on a group that does not exist: found when the mesh is read.
  {
    const cases::CaseSpec spec =
        cases::case_from_toml_string(replaced(good, "group = \"upper_right\"", "group = \"nowhere\""),
                                     example("two-block-traction"));
    try {
      (void)cases::reference_mesh(spec);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("traction group 'nowhere'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("upper_right"), std::string::npos) << e.what();  // the groups present
    }
  }
  // A traction parameter no traction names; two parameters of the same name.
  expect_error(replaced(replaced(good, "parameter = \"q\"\n", "\n"), "parameter = \"q\"\n", "\n"),
               {"'q' of kind 'traction'", "no [[traction]] names it"});
  expect_error(replaced(good, "name = \"q\"", "name = \"delta\""), {"defined twice"});
  // A set point outside the box, and a set of the wrong dimension.
  expect_error(replaced(good, "training = { grid = [5, 5] }", "training = { points = [[0.02, 0.5]] }"),
               {"sets.training"});
  expect_error(replaced(good, "training = { grid = [5, 5] }", "training = { points = [[0.02]] }"), {"sets.training"});
  // A body-force parameter on a body without load.
  expect_error(replaced(good, "kind = \"traction\"", "kind = \"body-force\"\nbody = \"slave\""),
               {"body-force"});
  // Points of the wrong size or outside the box at solve time.
  const cases::CaseSpec spec = cases::case_from_toml_file(example("two-block-traction"));
  EXPECT_THROW(spec.check_mu(Eigen::Vector3d(0.02, 0.1, 0.0)), Error);
  EXPECT_THROW(spec.check_mu(Eigen::Vector2d(0.02, 0.3)), Error);
  try {
    spec.check_mu(Eigen::Vector2d(0.02, 0.3));
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("(q) is outside the domain [0, 0.2]"), std::string::npos) << e.what();
  }
}

// to_toml writes [[parameter]], [[traction]] and [sets]; reading it back gives the same case.
TEST(Parameters, MultiParameterCaseRoundTripsThroughToml) {
  for (const cases::CaseSpec& spec :
       {cases::builtin_case_spec("hertz-3p"), cases::case_from_toml_file(example("two-block-traction"))}) {
    const cases::CaseSpec back = cases::case_from_toml_string(cases::to_toml(spec), spec.origin);
    EXPECT_TRUE(cases::same_case(spec, back)) << spec.name;
  }
}
