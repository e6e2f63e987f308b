#include "contactrb/cases/parameter.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>
#include <set>
#include <sstream>

#include "contactrb/common/error.hpp"

namespace contactrb::cases {

namespace {

// The shortest text that reads back to the same double: a value just outside the domain must
// not print as its bound ("0.45 is outside [0.15, 0.45]" for 0.4500000001).
std::string exact_text(double v) {
  std::array<char, 32> buf{};
  const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  if (ec != std::errc()) return std::to_string(v);
  return std::string(buf.data(), end);
}

}  // namespace

const char* to_string(ParameterKind kind) {
  switch (kind) {
    case ParameterKind::DirichletScale:
      return "dirichlet-scale";
    case ParameterKind::BodyScaling:
      return "body-scaling";
  }
  return "unknown";
}

ParameterKind parameter_kind_from_string(const std::string& name) {
  if (name == "dirichlet-scale") return ParameterKind::DirichletScale;
  if (name == "body-scaling") return ParameterKind::BodyScaling;
  throw Error("unknown parameter kind '" + name + "' (expected dirichlet-scale or body-scaling)");
}

double ParameterSpec::scale(double mu) const {
  return kind == ParameterKind::BodyScaling ? mu / reference : 1.0;
}

bool ParameterSpec::has_set(const std::string& set_name) const {
  for (const ParameterSet& s : sets) {
    if (s.name == set_name) return true;
  }
  return false;
}

const std::vector<double>& ParameterSpec::set(const std::string& set_name) const {
  for (const ParameterSet& s : sets) {
    if (s.name == set_name) return s.values;
  }
  std::ostringstream os;
  os << "parameter '" << name << "' has no set '" << set_name << "' (sets:";
  for (const ParameterSet& s : sets) os << " " << s.name;
  os << ")";
  throw Error(os.str());
}

void ParameterSpec::check(double mu, const std::string& context) const {
  if (!std::isfinite(mu) || mu < min || mu > max) {
    std::ostringstream os;
    os << "parameter mu = " << exact_text(mu) << " (" << name << ") is outside the domain [" << exact_text(min) << ", "
       << exact_text(max) << "] of "
       << context;
    throw Error(os.str());
  }
}

void check_parameter_spec(const ParameterSpec& p, const std::string& context) {
  const std::string where = " (" + context + ")";
  require(!p.name.empty(), "the parameter has no name" + where);
  require(std::isfinite(p.min) && std::isfinite(p.max) && p.min <= p.max,
          "parameter domain [" + std::to_string(p.min) + ", " + std::to_string(p.max) + "] is not an interval" + where);
  require(std::isfinite(p.reference) && p.reference >= p.min && p.reference <= p.max,
          "parameter reference value " + std::to_string(p.reference) + " is outside the domain" + where);
  if (p.kind == ParameterKind::BodyScaling) {
    require(p.min > 0.0, "body-scaling needs a positive domain (the scale mu / reference must be > 0)" + where);
    require(p.body == 0 || p.body == 1, "scaled body must be 0 (slave) or 1 (master), got " +
                                            std::to_string(p.body) + where);
    require(p.center.allFinite(), "scaling center is not finite" + where);
  }
  std::set<std::string> names;
  for (const ParameterSet& s : p.sets) {
    require(!s.name.empty(), "a parameter set has no name" + where);
    require(names.insert(s.name).second, "parameter set '" + s.name + "' is defined twice" + where);
    for (double mu : s.values) p.check(mu, "parameter set '" + s.name + "'" + where);
    check_increasing(s.values, "parameter set '" + s.name + "'" + where);
  }
}

void check_increasing(const std::vector<double>& values, const std::string& context) {
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (!(values[i] > values[i - 1])) {
      const auto text = [](double x) {  // shortest round-trip digits
        char buf[32];
        return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
      };
      throw Error("the values of " + context + " must be strictly increasing, but value " + std::to_string(i + 1) +
                  " (" + text(values[i]) + ") is not above value " + std::to_string(i) + " (" + text(values[i - 1]) +
                  ")");
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

}  // namespace contactrb::cases
