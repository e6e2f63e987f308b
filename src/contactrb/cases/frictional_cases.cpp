#include "contactrb/cases/frictional_cases.hpp"

#include <cmath>
#include <string>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "contactrb/mesh/structured.hpp"

namespace contactrb::cases {

namespace {

// The load path of the Cattaneo-type cases: the approach (no tangential displacement), then
// `tangential` in `steps` equal steps, under Coulomb friction with `coefficient`.
template <int Dim, class Step, class Tangential>
void approach_then_slide(BasicFrictionalCase<Dim>& c, const Step& step, const Tangential& tangential, int steps,
                         double coefficient) {
  c.path.push_back(step(Tangential(tangential * 0.0)));
  for (int i = 1; i <= steps; ++i) c.path.push_back(step(Tangential(tangential * i / steps)));
  c.problem.dirichlet = c.path.front().dirichlet;
  c.friction.law = hf::FrictionLaw::Coulomb;
  c.friction.coefficient = coefficient;
}

}  // namespace

FrictionalCase cattaneo_case(int level, const CattaneoData& d) {
  const mesh::HertzGeometry geometry;
  const CaseSpec hertz_a = builtin_case_spec("hertz-a");
  const double max_approach = hertz_a.parameters.front().max;
  require(std::isfinite(d.approach) && d.approach > geometry.gap && d.approach <= max_approach,
          "cattaneo: the approach must close the gap " + number_text(geometry.gap) + " and stay within hertz-a's " +
              number_text(max_approach) + " (got " + number_text(d.approach) + ")");
  require(std::isfinite(d.tangential), "cattaneo: the tangential displacement is not finite");
  require(std::isfinite(d.coefficient) && d.coefficient >= 0.0,
          "cattaneo: the friction coefficient must be >= 0 (got " + number_text(d.coefficient) + ")");
  require(d.tangential_steps >= 1, "cattaneo: tangential_steps must be >= 1 (got " + std::to_string(d.tangential_steps) + ")");
  mesh::HertzGeometry g = geometry;
  g.slave_arc_nodes = mesh::hertz_arc_nodes_for_level(level);
  FrictionalCase c;
  c.problem.mesh = mesh::generate_hertz(g);
  for (const BodySpec& body : hertz_a.bodies) c.problem.materials.push_back(fem::Material{body.E, body.nu});
  c.problem.discretization = contact::Discretization::Collocation;
  auto step = [&](double dx) {
    return hf::LoadStep{{{"top", dx, -0.5 * d.approach}, {"bottom", 0.0, 0.5 * d.approach}}, {}};
  };
  approach_then_slide(c, step, d.tangential, d.tangential_steps, d.coefficient);
  return c;
}

namespace {

// A step's loads at mu: its Dirichlet values, and its tractions (the case's when it has none).
hf::LoadStep load_step(const CaseSpec& step, const Mu& mu, const mesh::Mesh&) {
  return hf::LoadStep{dirichlet_at(step, mu), tractions_at(step, mu)};
}

// 3D: Dirichlet data only (case_problem.hpp, make_problem).
hf::LoadStep3 load_step(const CaseSpec& step, const Mu& mu, const mesh::Mesh3&) {
  require(step.tractions.empty(), step.context() + " is three-dimensional: its load steps are Dirichlet data only "
                                                   "(no [[load_steps.traction]] in 3D)");
  return hf::LoadStep3{dirichlet_at(step, mu), {}};
}

template <int Dim>
BasicFrictionalCase<Dim> file_case(const FrictionalCaseFile& file, const mesh::SimplexMesh<Dim>& reference, const Mu& mu) {
  file.spec.check_mu(mu);
  BasicFrictionalCase<Dim> c;
  c.problem = make_problem(file.spec, reference, mu, contact::Discretization::Collocation);
  for (const FrictionFileSpec::Step& s : file.friction.steps) {
    CaseSpec step = file.spec;  // the step's loads in place of the case's (its tractions when it has some)
    step.dirichlet = s.dirichlet;
    if (!s.tractions.empty()) step.tractions = s.tractions;
    c.path.push_back(load_step(step, mu, reference));
  }
  c.friction.law = hf::friction_law_from_string(file.friction.law);
  const int k = file.friction.coefficient_parameter;
  c.friction.coefficient = k >= 0 ? mu(k) : file.friction.coefficient;
  c.friction.threshold = file.friction.threshold;
  return c;
}

}  // namespace

FrictionalCase frictional_case(const FrictionalCaseFile& file, const mesh::Mesh& reference, const Mu& mu) {
  return file_case(file, reference, mu);
}

FrictionalCase3 frictional_case(const FrictionalCaseFile& file, const mesh::Mesh3& reference, const Mu& mu) {
  return file_case(file, reference, mu);
}

namespace {

// One body of block-on-block-3d: a box whose contact face and side faces are renamed.
mesh::Mesh3 named_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n, int nz, int body) {
  mesh::Mesh3 m = mesh::box(lo, hi, n, n, nz, body);
  const bool slave = body == mesh::kSlaveBody;
  mesh::rename_boundary(m, slave ? "bottom" : "top", slave ? mesh::kSlaveBoundary : mesh::kMasterBoundary);
  for (const char* side : {"left", "right", "front", "back"}) {
    mesh::rename_boundary(m, side, std::string(side) + (slave ? "1" : "2"));
  }
  return m;
}

}  // namespace

FrictionalCase3 cattaneo_3d_case(int level, const Cattaneo3dData& d) {
  require(level >= 0 && level <= 2, "cattaneo-3d: level must be in [0, 2] (got " + std::to_string(level) + ")");
  require(std::isfinite(d.approach) && d.approach > 0.0 && d.approach <= 0.1,
          "cattaneo-3d: the approach must be in (0, 0.1] (got " + number_text(d.approach) + ")");
  require(std::isfinite(d.tangential), "cattaneo-3d: the tangential displacement is not finite");
  require(std::isfinite(d.coefficient) && d.coefficient >= 0.0,
          "cattaneo-3d: the friction coefficient must be >= 0 (got " + number_text(d.coefficient) + ")");
  require(d.tangential_steps >= 1, "cattaneo-3d: tangential_steps must be >= 1 (got " + std::to_string(d.tangential_steps) + ")");
  const CaseSpec hertz_3d = builtin_case_spec("hertz-3d");
  mesh::Hertz3dGeometry g;
  g.fine_size = mesh::hertz_3d_fine_size_for_level(level);
  FrictionalCase3 c;
  c.problem.mesh = mesh::mirror(mesh::mirror(mesh::generate_hertz_3d(g), 0, "symmetry_x"), 1, "symmetry_y");
  for (const BodySpec& body : hertz_3d.bodies) c.problem.materials.push_back(fem::Material{body.E, body.nu});
  c.problem.discretization = contact::Discretization::Collocation;
  auto step = [&](double dx) {
    return hf::LoadStep3{{fem::DirichletCondition{"top", dx, 0.0, -d.approach},
                          fem::DirichletCondition{"bottom", 0.0, 0.0, 0.0}},
                         {}};
  };
  approach_then_slide(c, step, d.tangential, d.tangential_steps, d.coefficient);
  return c;
}

FrictionalCase3 block_on_block_3d_case(int level, const BlockOnBlock3dData& d) {
  require(level >= 0 && level <= 2, "block-on-block-3d: level must be in [0, 2] (got " + std::to_string(level) + ")");
  require(std::isfinite(d.approach) && d.approach > 0.0,
          "block-on-block-3d: the approach must be > 0 (got " + number_text(d.approach) + ")");
  require(d.tangential.allFinite(), "block-on-block-3d: the tangential displacement is not finite");
  require(std::isfinite(d.coefficient) && d.coefficient >= 0.0,
          "block-on-block-3d: the friction coefficient must be >= 0 (got " + number_text(d.coefficient) + ")");
  require(d.tangential_steps >= 1,
          "block-on-block-3d: tangential_steps must be >= 1 (got " + std::to_string(d.tangential_steps) + ")");
  const int k = 1 << level;
  FrictionalCase3 c;
  c.problem.mesh = mesh::merge(named_box({0.2, 0.2, 0.0}, {0.8, 0.8, 0.4}, 6 * k, 4 * k, mesh::kSlaveBody),
                               named_box({0.0, 0.0, -0.5}, {1.0, 1.0, 0.0}, 10 * k, 5 * k, mesh::kMasterBody));
  c.problem.materials = {fem::Material{10.0, 0.3}, fem::Material{10.0, 0.3}};
  c.problem.discretization = contact::Discretization::Collocation;
  auto step = [&](const Eigen::Vector2d& t) {
    return hf::LoadStep3{{fem::DirichletCondition{"top", t.x(), t.y(), -d.approach},
                          fem::DirichletCondition{"bottom", 0.0, 0.0, 0.0}},
                         {}};
  };
  approach_then_slide(c, step, d.tangential, d.tangential_steps, d.coefficient);
  return c;
}

}  // namespace contactrb::cases
