#include "contactrb/cases/parameter.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <system_error>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::cases {

namespace {

// The shortest text that reads back to the same double: a value just outside the domain must
// not print as its bound ("0.45 is outside [0.15, 0.45]" for 0.4500000001).
std::string exact_text(double v) {
  std::array<char, 32> buf{};
  const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  if (ec != std::errc()) return number_text(v);
  return std::string(buf.data(), end);
}

}  // namespace

const char* to_string(ParameterKind kind) {
  switch (kind) {
    case ParameterKind::DirichletScale:
      return "dirichlet-scale";
    case ParameterKind::BodyScaling:
      return "body-scaling";
    case ParameterKind::YoungModulus:
      return "young-modulus";
    case ParameterKind::Traction:
      return "traction";
    case ParameterKind::BodyForce:
      return "body-force";
    case ParameterKind::FrictionCoefficient:
      return "friction-coefficient";
  }
  return "unknown";
}

ParameterKind parameter_kind_from_string(const std::string& name) {
  using enum ParameterKind;
  return enum_from_string(name, "parameter kind",
                          std::array{DirichletScale, BodyScaling, YoungModulus, Traction, BodyForce, FrictionCoefficient});
}

bool has_body(ParameterKind kind) {
  return kind == ParameterKind::BodyScaling || kind == ParameterKind::YoungModulus || kind == ParameterKind::BodyForce;
}

double ParameterSpec::scale(double value) const {
  return kind == ParameterKind::BodyScaling ? value / reference : 1.0;
}

void ParameterSpec::check(double value, const std::string& context) const {
  if (!std::isfinite(value) || value < min || value > max) {
    std::ostringstream os;
    os << "parameter mu = " << exact_text(value) << " (" << name << ") is outside the domain [" << exact_text(min)
       << ", " << exact_text(max) << "] of " << context;
    throw Error(os.str());
  }
}

void check_parameter_spec(const ParameterSpec& p, const std::string& context) {
  const std::string where = " (" + context + ")";
  require(!p.name.empty(), "a parameter has no name" + where);
  for (char ch : p.name) {
    const auto u = static_cast<unsigned char>(ch);
    require(ch != ',' && ch != '=' && ch != '"' && u >= 0x20 && u != 0x7f,
            "parameter name '" + p.name + "' holds a ',', '=', '\"' or control character (names are used in "
            "--mu name=value)" + where);
  }
  const std::string which = "parameter '" + p.name + "'";
  require(std::isfinite(p.min) && std::isfinite(p.max) && p.min <= p.max,
          which + ": domain [" + exact_text(p.min) + ", " + exact_text(p.max) + "] is not an interval" + where);
  // The data a parameter multiplies (case_spec.cpp) are capped at this magnitude too.
  constexpr double kMaxParameterMagnitude = 1e50;
  require(std::abs(p.min) <= kMaxParameterMagnitude && std::abs(p.max) <= kMaxParameterMagnitude,
          which + ": domain [" + exact_text(p.min) + ", " + exact_text(p.max) +
              "] reaches above 1e50 in magnitude (products with the case's data would overflow double precision: "
              "change the units)" + where);
  require(std::isfinite(p.reference) && p.reference >= p.min && p.reference <= p.max,
          which + ": reference value " + exact_text(p.reference) + " is outside the domain" + where);
  if (has_body(p.kind)) {
    require(p.body == 0 || p.body == 1,
            which + ": the body must be 0 (slave) or 1 (master), got " + std::to_string(p.body) + where);
  }
  if (p.kind == ParameterKind::BodyScaling) {
    require(p.min > 0.0, which + ": body-scaling needs a positive domain (the scale mu / reference must be > 0)" + where);
    require(p.center.allFinite(), which + ": scaling center is not finite" + where);
  }
  if (p.kind == ParameterKind::YoungModulus) {
    require(p.min > 0.0, which + ": young-modulus needs a positive domain (E > 0)" + where);
  }
}

void check_parameter_list(const std::vector<ParameterSpec>& parameters, const std::string& context) {
  require(!parameters.empty(), "the case has no parameter (" + context + ")");
  std::set<std::string> names;
  std::map<std::pair<ParameterKind, int>, std::string> per_body;
  for (const ParameterSpec& p : parameters) {
    check_parameter_spec(p, context);
    require(names.insert(p.name).second, "parameter '" + p.name + "' is defined twice (" + context + ")");
    if (has_body(p.kind)) {
      const auto [it, fresh] = per_body.emplace(std::make_pair(p.kind, p.body), p.name);
      require(fresh, "parameters '" + it->second + "' and '" + p.name + "' are both of kind " + to_string(p.kind) +
                         " on the " + (p.body == 0 ? "slave" : "master") + " body (one per body) (" + context + ")");
    }
  }
}

void check_mu(const std::vector<ParameterSpec>& parameters, const Mu& mu, const std::string& context) {
  if (mu.size() != static_cast<Eigen::Index>(parameters.size())) {
    std::string names;
    for (const ParameterSpec& p : parameters) names += (names.empty() ? "" : ", ") + p.name;
    throw Error("a parameter point of " + context + " needs " + std::to_string(parameters.size()) + " value" +
                (parameters.size() == 1 ? "" : "s") + " (" + names + "), got " + std::to_string(mu.size()));
  }
  for (std::size_t k = 0; k < parameters.size(); ++k) parameters[k].check(mu(static_cast<Eigen::Index>(k)), context);
}

void check_points(const std::vector<ParameterSpec>& parameters, const std::vector<Mu>& points,
                  const std::string& context) {
  require(!points.empty(), context + " has no point");
  for (const Mu& mu : points) check_mu(parameters, mu, context);
  if (parameters.size() == 1) {
    check_increasing(values_1d(points), context);
    return;
  }
  std::map<std::vector<double>, std::size_t> seen;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::vector<double> key(points[i].data(), points[i].data() + points[i].size());
    const auto [it, fresh] = seen.emplace(key, i);
    if (!fresh) {  // the message only on failure: every problem of a case checks its sets' points
      throw Error(context + ": points " + std::to_string(it->second + 1) + " and " + std::to_string(i + 1) +
                  " are the same, " + mu_values_text(points[i]));
    }
  }
}

Mu reference_mu(const std::vector<ParameterSpec>& parameters) {
  Mu mu(static_cast<Eigen::Index>(parameters.size()));
  for (std::size_t k = 0; k < parameters.size(); ++k) mu(static_cast<Eigen::Index>(k)) = parameters[k].reference;
  return mu;
}

int parameter_index(const std::vector<ParameterSpec>& parameters, const std::string& name) {
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    if (parameters[k].name == name) return static_cast<int>(k);
  }
  return -1;
}

std::string mu_text(const std::vector<ParameterSpec>& parameters, const Mu& mu) {
  std::string s;
  for (Eigen::Index k = 0; k < mu.size(); ++k) {
    if (k > 0) s += ", ";
    if (k < static_cast<Eigen::Index>(parameters.size())) s += parameters[static_cast<std::size_t>(k)].name + " = ";
    s += exact_text(mu(k));
  }
  return s;
}

std::string mu_short_text(const Mu& mu) {
  if (mu.size() == 1) return number_text(mu(0));
  std::string s = "(";
  for (Eigen::Index k = 0; k < mu.size(); ++k) s += (k > 0 ? ", " : "") + number_text(mu(k));
  return s + ")";
}

std::string mu_values_text(const Mu& mu) {
  if (mu.size() == 1) return exact_text(mu(0));
  std::string s = "(";
  for (Eigen::Index k = 0; k < mu.size(); ++k) s += (k > 0 ? ", " : "") + exact_text(mu(k));
  return s + ")";
}

void check_increasing(const std::vector<double>& values, const std::string& context) {
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (!(values[i] > values[i - 1])) {
      throw Error("the values of " + context + " must be strictly increasing, but value " + std::to_string(i + 1) +
                  " (" + exact_text(values[i]) + ") is not above value " + std::to_string(i) + " (" +
                  exact_text(values[i - 1]) + ")");
    }
  }
}

std::vector<double> arithmetic_set(double start, double step, int count) {
  require(count >= 0, "a parameter set needs count >= 0 (got " + std::to_string(count) + ")");
  std::vector<double> v;
  v.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) v.push_back(start + i * step);
  return v;
}

std::vector<double> midpoints(const std::vector<double>& values) {
  std::vector<double> m;
  for (std::size_t i = 1; i < values.size(); ++i) m.push_back(0.5 * (values[i - 1] + values[i]));
  return m;
}

std::vector<Mu> points_1d(const std::vector<double>& values) {
  std::vector<Mu> points;
  points.reserve(values.size());
  for (double v : values) points.push_back(Mu::Constant(1, v));
  return points;
}

std::vector<double> values_1d(const std::vector<Mu>& points) {
  std::vector<double> values;
  values.reserve(points.size());
  for (const Mu& mu : points) {
    require(mu.size() == 1, "a one-parameter set was expected, got a point of " + std::to_string(mu.size()) +
                                " values");
    values.push_back(mu(0));
  }
  return values;
}

}  // namespace contactrb::cases
