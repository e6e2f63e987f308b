#include "contactrb/cases/affine_assembly.hpp"

#include <string>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/traction.hpp"

namespace contactrb::cases {

namespace {

// Lift of the parts a of every Dirichlet value (parameter -1), or of the parts b of the values
// that depend on parameter k (0 elsewhere); the constrained DOFs are the same.
Eigen::VectorXd part_lift(const CaseSpec& spec, const mesh::Mesh& reference, int k) {
  const auto part = [k](const AffineValue& v) { return k < 0 ? v.a : (v.parameter == k ? v.b : 0.0); };
  std::vector<fem::DirichletCondition> conditions;
  for (const DirichletSpec& d : spec.dirichlet) {
    fem::DirichletCondition c;
    c.group = d.group;
    if (d.ux) c.ux = part(*d.ux);
    if (d.uy) c.uy = part(*d.uy);
    conditions.push_back(std::move(c));
  }
  return fem::DofMap(reference, conditions).lift();
}

void check_size(std::size_t terms, Eigen::Index theta) {
  require(static_cast<Eigen::Index>(terms) == theta, "affine combination: " + std::to_string(terms) +
                                                         " terms but " + std::to_string(theta) + " theta values");
}

}  // namespace

AffineTerms assemble_affine_terms(const CaseSpec& spec, const mesh::Mesh& reference) {
  check_case_spec(spec);
  check_tractions(spec, reference);
  AffineTerms t;
  // The order of theta_functions (theta.hpp).
  const bool E_param = spec.parameter_of_body(ParameterKind::YoungModulus, 0) >= 0 ||
                       spec.parameter_of_body(ParameterKind::YoungModulus, 1) >= 0;
  const std::vector<fem::Material> nominal = materials(spec, reference_mu(spec.parameters));
  if (!E_param) {
    t.A.push_back(fem::stiffness(reference, nominal));
  } else {
    for (int body = 0; body < 2; ++body) {
      fem::Material m = nominal[static_cast<std::size_t>(body)];
      if (spec.parameter_of_body(ParameterKind::YoungModulus, body) >= 0) m.E = 1.0;  // theta = E
      t.A.push_back(fem::stiffness_body(reference, body, m));
    }
  }
  for (int body = 0; body < 2; ++body) {
    const Eigen::Vector2d& load = spec.bodies[static_cast<std::size_t>(body)].load;
    if (!load.isZero(0.0)) t.f.push_back(fem::body_load(reference, body, load));
  }
  for (const TractionSpec& tr : spec.tractions) {
    t.f.push_back(fem::traction_load(reference, {tr.group, tr.is_pressure, tr.vector, tr.pressure}));
  }
  if (!spec.dirichlet.empty()) {
    t.lift.push_back(part_lift(spec, reference, -1));
    for (int k : dirichlet_parameters(spec)) t.lift.push_back(part_lift(spec, reference, k));
  }
  return t;
}

fem::SparseMatrix combine(const std::vector<fem::SparseMatrix>& terms, const Eigen::VectorXd& theta) {
  check_size(terms.size(), theta.size());
  if (terms.empty()) return {};
  fem::SparseMatrix sum = theta(0) * terms[0];
  for (std::size_t j = 1; j < terms.size(); ++j) sum += theta(static_cast<Eigen::Index>(j)) * terms[j];
  return sum;
}

Eigen::VectorXd combine(const std::vector<Eigen::VectorXd>& terms, const Eigen::VectorXd& theta, Eigen::Index size) {
  check_size(terms.size(), theta.size());
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(size);
  for (std::size_t j = 0; j < terms.size(); ++j) {
    require(terms[j].size() == size, "affine combination: term of size " + std::to_string(terms[j].size()) +
                                         ", expected " + std::to_string(size));
    sum += theta(static_cast<Eigen::Index>(j)) * terms[j];
  }
  return sum;
}

}  // namespace contactrb::cases
