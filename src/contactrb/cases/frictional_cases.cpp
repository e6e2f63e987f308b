#include "contactrb/cases/frictional_cases.hpp"

#include <cmath>
#include <string>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"
#include "contactrb/mesh/geometries.hpp"

namespace contactrb::cases {

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
  c.path.push_back(step(0.0));
  for (int i = 1; i <= d.tangential_steps; ++i) c.path.push_back(step(d.tangential * i / d.tangential_steps));
  c.problem.dirichlet = c.path.front().dirichlet;
  c.friction.law = hf::FrictionLaw::Coulomb;
  c.friction.coefficient = d.coefficient;
  return c;
}

FrictionalCase frictional_case(const FrictionalCaseFile& file, const mesh::Mesh& reference, const Mu& mu) {
  file.spec.check_mu(mu);
  FrictionalCase c;
  c.problem = make_problem(file.spec, reference, mu, contact::Discretization::Collocation);
  for (const FrictionFileSpec::Step& s : file.friction.steps) {
    CaseSpec step = file.spec;  // the step's loads in place of the case's (its tractions when it has some)
    step.dirichlet = s.dirichlet;
    if (!s.tractions.empty()) step.tractions = s.tractions;
    c.path.push_back(hf::LoadStep{dirichlet_at(step, mu), tractions_at(step, mu)});
  }
  c.friction.law = hf::friction_law_from_string(file.friction.law);
  const int k = file.friction.coefficient_parameter;
  c.friction.coefficient = k >= 0 ? mu(k) : file.friction.coefficient;
  c.friction.threshold = file.friction.threshold;
  return c;
}

}  // namespace contactrb::cases
