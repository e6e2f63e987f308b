#include "contactrb/cases/theta.hpp"

#include <cmath>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/common/error.hpp"

namespace contactrb::cases {

double ThetaMonomial::operator()(const Eigen::VectorXd& mu) const {
  double x = coefficient;
  for (const ThetaFactor& f : factors) {
    const double r = mu(f.parameter) / f.scale;
    double y = 1.0;
    for (int i = 0; i < std::abs(f.power); ++i) y *= r;
    x *= f.power < 0 ? 1.0 / y : y;
  }
  return x;
}

Eigen::VectorXd evaluate(const std::vector<ThetaMonomial>& thetas, const Eigen::VectorXd& mu) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(thetas.size()));
  for (std::size_t j = 0; j < thetas.size(); ++j) v(static_cast<Eigen::Index>(j)) = thetas[j](mu);
  return v;
}

void check_thetas(const AffineThetas& thetas, int num_parameters, const std::string& what) {
  for (const auto* list : {&thetas.a, &thetas.f, &thetas.lift}) {
    for (const ThetaMonomial& t : *list) {
      require(std::isfinite(t.coefficient) && t.coefficient != 0.0, what + ": a theta coefficient is zero or not finite");
      for (const ThetaFactor& f : t.factors) {
        require(f.parameter >= 0 && f.parameter < num_parameters,
                what + ": a theta factor names parameter " + std::to_string(f.parameter) + " of " +
                    std::to_string(num_parameters));
        require(std::isfinite(f.scale) && f.scale != 0.0, what + ": a theta factor has a zero or non-finite scale");
        require(std::abs(f.power) <= 8, what + ": a theta factor has power " + std::to_string(f.power));
      }
    }
  }
}

AffineThetas theta_functions(const CaseSpec& spec) {
  AffineThetas t;
  const auto scaling = [&](int body, int power, ThetaMonomial& m) {
    const int k = spec.parameter_of_body(ParameterKind::BodyScaling, body);
    if (k >= 0) m.factors.push_back({k, spec.parameters[static_cast<std::size_t>(k)].reference, power});
  };
  // Stiffness: one term unless some body's E is a parameter.
  const int E0 = spec.parameter_of_body(ParameterKind::YoungModulus, 0);
  const int E1 = spec.parameter_of_body(ParameterKind::YoungModulus, 1);
  if (E0 < 0 && E1 < 0) {
    t.a = {ThetaMonomial{}};
  } else {
    for (int E : {E0, E1}) {
      ThetaMonomial m;
      if (E >= 0) m.factors.push_back({E, 1.0, 1});
      t.a.push_back(m);
    }
  }
  // Body loads: |det M_i(mu)| = s_i^2 (paper (48)), times the body-force parameter.
  for (int body = 0; body < 2; ++body) {
    if (spec.bodies[static_cast<std::size_t>(body)].load.isZero(0.0)) continue;
    ThetaMonomial m;
    scaling(body, 2, m);
    const int k = spec.parameter_of_body(ParameterKind::BodyForce, body);
    if (k >= 0) m.factors.push_back({k, 1.0, 1});
    t.f.push_back(m);
  }
  // Tractions: the edge length scales by s_i; the normal of a uniform scaling does not turn.
  for (const TractionSpec& tr : spec.tractions) {
    ThetaMonomial m;
    if (tr.body >= 0) scaling(tr.body, 1, m);
    if (tr.parameter >= 0) m.factors.push_back({tr.parameter, 1.0, 1});
    t.f.push_back(m);
  }
  if (!spec.dirichlet.empty()) {
    t.lift.push_back(ThetaMonomial{});
    for (int k : dirichlet_parameters(spec)) t.lift.push_back(ThetaMonomial{1.0, {{k, 1.0, 1}}});
  }
  return t;
}

}  // namespace contactrb::cases
