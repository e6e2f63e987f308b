// theta_functions (theta.hpp): the theta functions of a case, from its CaseSpec. Apart from
// theta.cpp, which the online stage links (contactrb::parameters): a CaseSpec belongs to the
// offline side (contactrb::cases).
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/theta.hpp"

namespace contactrb::cases {

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
