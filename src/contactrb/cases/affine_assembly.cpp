#include "contactrb/cases/affine_assembly.hpp"

#include <string>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/fem/dirichlet.hpp"

namespace contactrb::cases {

namespace {

// Lift of the part a (or b) of every Dirichlet value; the constrained DOFs are the same.
Eigen::VectorXd part_lift(const CaseSpec& spec, const mesh::Mesh& reference, bool slope) {
  std::vector<fem::DirichletCondition> conditions;
  for (const DirichletSpec& d : spec.dirichlet) {
    fem::DirichletCondition c;
    c.group = d.group;
    if (d.ux) c.ux = slope ? d.ux->b : d.ux->a;
    if (d.uy) c.uy = slope ? d.uy->b : d.uy->a;
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
  AffineTerms t;
  t.A.push_back(fem::stiffness(reference, materials(spec)));
  for (int body = 0; body < 2; ++body) {
    const Eigen::Vector2d& load = spec.bodies[static_cast<std::size_t>(body)].load;
    if (!load.isZero(0.0)) t.f.push_back(fem::body_load(reference, body, load));
  }
  if (!spec.dirichlet.empty()) {
    t.lift.push_back(part_lift(spec, reference, false));
    if (has_affine_dirichlet(spec)) t.lift.push_back(part_lift(spec, reference, true));
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
