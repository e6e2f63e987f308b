#include "contactrb/cases/theta.hpp"

#include <cmath>

#include "contactrb/cases/case_spec.hpp"

namespace contactrb::cases {

double ThetaMonomial::operator()(double mu) const {
  double x = 1.0;
  const double r = mu / scale;
  for (int i = 0; i < std::abs(power); ++i) x *= r;
  return coefficient * (power < 0 ? 1.0 / x : x);
}

Eigen::VectorXd evaluate(const std::vector<ThetaMonomial>& thetas, double mu) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(thetas.size()));
  for (std::size_t j = 0; j < thetas.size(); ++j) v(static_cast<Eigen::Index>(j)) = thetas[j](mu);
  return v;
}

AffineThetas theta_functions(const CaseSpec& spec) {
  AffineThetas t;
  const ThetaMonomial one{1.0, 1.0, 0};
  t.a = {one};
  const ParameterSpec& p = spec.parameter;
  for (int body = 0; body < 2; ++body) {
    if (spec.bodies[static_cast<std::size_t>(body)].load.isZero(0.0)) continue;
    const bool scaled = p.kind == ParameterKind::BodyScaling && p.body == body;
    t.f.push_back(scaled ? ThetaMonomial{1.0, p.reference, 2} : one);
  }
  if (!spec.dirichlet.empty()) {
    t.lift.push_back(one);
    if (has_affine_dirichlet(spec)) t.lift.push_back(ThetaMonomial{1.0, 1.0, 1});
  }
  return t;
}

}  // namespace contactrb::cases
