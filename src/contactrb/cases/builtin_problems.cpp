#include "contactrb/cases/builtin_problems.hpp"

#include <map>

#include "contactrb/cases/catalog.hpp"

namespace contactrb::cases {

const ParameterDomain& parameter_domain(const std::string& case_name) {
  static const std::map<std::string, ParameterDomain> domains = [] {
    std::map<std::string, ParameterDomain> d;
    for (const CaseInfo& c : builtin_cases()) {
      const ParameterSpec p = builtin_case_spec(c.name).parameters.front();
      d[c.name] = ParameterDomain{p.name, p.min, p.max, p.reference};
    }
    return d;
  }();
  find_case(case_name);
  return domains.at(case_name);
}

void check_parameter(const std::string& case_name, double mu) {
  builtin_case_spec(case_name).check_mu(Mu::Constant(1, mu));
}

hf::ContactProblem make_problem(const std::string& case_name, const Mu& mu, int level,
                                std::optional<contact::Discretization> constraint) {
  return make_problem(builtin_case_spec(case_name), mu, level, constraint);
}

hf::ContactProblem make_problem(const std::string& case_name, double mu, int level,
                                std::optional<contact::Discretization> constraint) {
  return make_problem(builtin_case_spec(case_name), Mu::Constant(1, mu), level, constraint);
}

}  // namespace contactrb::cases
