#include "contactrb/cases/builtin_problems.hpp"

#include <cmath>
#include <map>
#include <sstream>

#include "contactrb/cases/catalog.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/mesh/geometries.hpp"

namespace contactrb::cases {

namespace {
// Paper Section 6.2: E = 15, nu = 0.35 for both half-disks.
const fem::Material kHertzMaterial{15.0, 0.35};
// Ring-on-block (Section 6.3): the ring is 15 times stiffer than the block (docs/cases.md).
const fem::Material kRingMaterial{15.0, 0.3};
const fem::Material kBlockMaterial{1.0, 0.3};
constexpr double kRingPush = 0.1;  // downward displacement of the ring's end faces

// Uniform scaling by s of one body about a fixed point p: x -> s (x - p) + p.
void scale_body(mesh::Mesh& m, int body, double s, const Eigen::Vector2d& p) {
  mesh::map_body(m, body, s * Eigen::Matrix2d::Identity(), (1.0 - s) * p);
}
}  // namespace

const ParameterDomain& parameter_domain(const std::string& case_name) {
  static const std::map<std::string, ParameterDomain> domains{
      {"hertz-a", {"imposed displacement", 0.15, 0.45, 0.3}},
      {"hertz-b", {"lower radius R2", 0.9, 1.12, 1.0}},
      {"ring-block", {"ring radius R1", 0.95, 1.15, 1.0}},
  };
  find_case(case_name);
  return domains.at(case_name);
}

void check_parameter(const std::string& case_name, double mu) {
  const ParameterDomain& d = parameter_domain(case_name);
  if (!std::isfinite(mu) || mu < d.min || mu > d.max) {
    std::ostringstream os;
    os << "parameter mu = " << mu << " (" << d.name << ") is outside the domain [" << d.min << ", "
       << d.max << "] of case '" << case_name << "'";
    throw Error(os.str());
  }
}

hf::ContactProblem make_problem(const std::string& case_name, double mu, int level,
                                std::optional<contact::Discretization> constraint) {
  check_parameter(case_name, mu);
  hf::ContactProblem p;
  p.mesh = reference_mesh(case_name, level);
  if (case_name == "hertz-a") {
    p.materials = {kHertzMaterial, kHertzMaterial};
    p.dirichlet = {{"top", 0.0, -0.5 * mu}, {"bottom", 0.0, 0.5 * mu}};
    p.discretization = contact::Discretization::Collocation;
  } else if (case_name == "hertz-b") {
    // R2 = mu: body 2 scaled about the top of its arc (0, -gap/2), keeping the gap 0.1.
    const mesh::HertzGeometry g;
    scale_body(p.mesh, mesh::kMasterBody, mu / g.R2, Eigen::Vector2d(0.0, -0.5 * g.gap));
    p.materials = {kHertzMaterial, kHertzMaterial};
    p.dirichlet = {{"top", 0.0, -0.2}, {"bottom", 0.0, 0.2}};
    p.discretization = contact::Discretization::Collocation;
  } else {
    // R1 = mu: the ring scaled about its lowest point (0, gap).
    const mesh::RingBlockGeometry g;
    scale_body(p.mesh, mesh::kSlaveBody, mu / g.R_out, Eigen::Vector2d(0.0, g.gap));
    p.materials = {kRingMaterial, kBlockMaterial};
    p.dirichlet = {{"ring_ends", 0.0, -kRingPush}, {"block_bottom", 0.0, 0.0}};
    p.discretization = contact::Discretization::LAC;
  }
  if (constraint) p.discretization = *constraint;
  return p;
}

}  // namespace contactrb::cases
