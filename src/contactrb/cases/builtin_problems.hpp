#pragma once
// The paper's three cases by name (Section 6; DESIGN.md "The three paper cases"): thin
// wrappers over their CaseSpec (case_spec.hpp, builtin_case_spec) and make_problem
// (case_problem.hpp), the one code path shared with the TOML cases.
#include <optional>
#include <string>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/hf/contact_problem.hpp"

namespace contactrb::cases {

struct ParameterDomain {
  std::string name;
  double min = 0.0;
  double max = 0.0;
  double reference = 0.0;  // the value at which the reference mesh is Omega(mu)
};

// The first parameter's domain (the paper's cases have one).
const ParameterDomain& parameter_domain(const std::string& case_name);
// Throws contactrb::Error for a NaN or a value outside [min, max], naming the case,
// the parameter and the domain (one-parameter cases).
void check_parameter(const std::string& case_name, double mu);

// The HF problem of a built-in case at mu (mesh level `level`, 0 = the paper's mesh).
// `constraint` overrides the case's default discretization. The double overload is for the
// one-parameter cases.
hf::ContactProblem make_problem(const std::string& case_name, const Mu& mu, int level = 0,
                                std::optional<contact::Discretization> constraint = std::nullopt);
hf::ContactProblem make_problem(const std::string& case_name, double mu, int level = 0,
                                std::optional<contact::Discretization> constraint = std::nullopt);

}  // namespace contactrb::cases
