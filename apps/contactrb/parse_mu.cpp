#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "contactrb/common/error.hpp"

#include <nlohmann/json.hpp>

namespace contactrb::app {

namespace {

// Shortest text that reads back as the same double (a message must not round 0.45 + 1 ulp
// onto 0.45).
std::string exact(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

// One number with optional surrounding blanks, nothing else; `what` names it in messages.
double parse_number(const std::string& raw, const std::string& what) {
  const auto first = raw.find_first_not_of(" \t\r");
  require(first != std::string::npos, what.empty() ? "empty line (expected one parameter value)"
                                                    : what + "the value is empty (expected a number)");
  const auto last = raw.find_last_not_of(" \t\r");
  const std::string text = raw.substr(first, last - first + 1);
  errno = 0;
  char* end = nullptr;
  const double mu = std::strtod(text.c_str(), &end);
  // The whole text: strtod stops at an embedded NUL byte, which would accept "0.3\0junk".
  require(end != text.c_str() && end == text.c_str() + text.size(), what + "'" + text + "' is not a number");
  require(!std::isnan(mu), what + "'" + text + "' is not a number (NaN)");
  require(!std::isinf(mu), what + "'" + text + "' is not finite");
  // strtod signals both ends of the range with ERANGE: an overflow (already refused as
  // infinite above) or an underflow, which returns 0 or a subnormal: '1e-400' would silently
  // become mu = 0.
  require(errno != ERANGE, what + "'" + text + "' is below the smallest normal double (2.2e-308): it would be read as " +
                               exact(mu) + "; write 0 if you mean 0");
  return mu;
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

std::string names_of(const std::vector<cases::ParameterSpec>& parameters) {
  std::string s;
  for (const cases::ParameterSpec& p : parameters) s += (s.empty() ? "" : ", ") + p.name;
  return s;
}

// Splits on ',' keeping empty items (",," is a missing value, not nothing); without a comma
// and with `blanks`, on runs of blanks.
std::vector<std::string> split(const std::string& text, bool blanks) {
  std::vector<std::string> items;
  if (blanks && text.find(',') == std::string::npos) {
    std::string current;
    for (char ch : text + " ") {
      if (ch == ' ' || ch == '\t' || ch == '\r') {
        if (!current.empty()) items.push_back(current);
        current.clear();
      } else {
        current += ch;
      }
    }
    return items;
  }
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i == text.size() || text[i] == ',') {
      items.push_back(text.substr(start, i - start));
      start = i + 1;
    }
  }
  return items;
}

// name=value pairs: every parameter exactly once.
cases::Mu parse_named(const std::vector<std::string>& items, const std::vector<cases::ParameterSpec>& parameters,
                      const std::string& what) {
  cases::Mu mu(static_cast<Eigen::Index>(parameters.size()));
  std::vector<bool> given(parameters.size(), false);
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    require(eq != std::string::npos, what + "'" + trim(item) + "' is not name=value (mix of named and positional values)");
    const std::string name = trim(item.substr(0, eq));
    const int k = cases::parameter_index(parameters, name);
    require(k >= 0, what + "unknown parameter '" + name + "' (parameters: " + names_of(parameters) + ")");
    require(!given[static_cast<std::size_t>(k)], what + "parameter '" + name + "' is given twice");
    given[static_cast<std::size_t>(k)] = true;
    mu(k) = parse_number(item.substr(eq + 1), what + name + ": ");
  }
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    require(given[k], what + "missing value for parameter '" + parameters[k].name + "' (parameters: " +
                          names_of(parameters) + ")");
  }
  return mu;
}

cases::Mu parse_point(const std::string& text, const std::vector<cases::ParameterSpec>& parameters,
                      const std::string& what, bool batch) {
  const std::size_t p = parameters.size();
  require(p >= 1, what + "the model has no parameter");
  const std::string t = trim(text);
  require(!t.empty(), batch ? what + "empty line (expected " + std::to_string(p) + " parameter value" +
                                  (p == 1 ? "" : "s: " + names_of(parameters)) + ")"
                            : what + "the value is empty (expected a number)");
  if (batch && t.front() == '{') {
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(t);
    } catch (const nlohmann::json::exception&) {
      throw Error(what + "not a valid JSON object");
    }
    require(j.is_object(), what + "not a JSON object");
    cases::Mu mu(static_cast<Eigen::Index>(p));
    std::vector<bool> given(p, false);
    for (const auto& [name, value] : j.items()) {
      const int k = cases::parameter_index(parameters, name);
      require(k >= 0, what + "unknown parameter '" + name + "' (parameters: " + names_of(parameters) + ")");
      require(value.is_number(), what + "the value of '" + name + "' is not a number");
      const double v = value.get<double>();
      require(std::isfinite(v), what + "the value of '" + name + "' is not finite");
      mu(k) = v;
      given[static_cast<std::size_t>(k)] = true;
    }
    for (std::size_t k = 0; k < p; ++k) {
      require(given[k], what + "missing value for parameter '" + parameters[k].name + "'");
    }
    return mu;
  }
  if (t.find('=') != std::string::npos) return parse_named(split(t, false), parameters, what);
  const std::vector<std::string> items = split(t, batch);
  require(items.size() == p, what + "expected " + std::to_string(p) + " value" + (p == 1 ? "" : "s") + " (" +
                                 names_of(parameters) + "), got " + std::to_string(items.size()) +
                                 (p > 1 ? " (or give name=value pairs)" : ""));
  cases::Mu mu(static_cast<Eigen::Index>(p));
  for (std::size_t k = 0; k < p; ++k) {
    mu(static_cast<Eigen::Index>(k)) =
        parse_number(items[k], p == 1 ? what : what + parameters[k].name + ": ");
  }
  return mu;
}

}  // namespace

double parse_mu_line(const std::string& line) { return parse_number(line, ""); }

double parse_mu_option(const std::string& text, const std::string& flag) { return parse_number(text, flag + ": "); }

cases::Mu parse_mu_line(const std::string& line, const std::vector<cases::ParameterSpec>& parameters) {
  if (parameters.size() == 1 && line.find_first_of("={") == std::string::npos) {
    return cases::Mu::Constant(1, parse_number(line, ""));  // the one-number form, its messages
  }
  return parse_point(line, parameters, "", true);
}

cases::Mu parse_mu_option(const std::string& text, const std::string& flag,
                          const std::vector<cases::ParameterSpec>& parameters) {
  if (parameters.size() == 1 && text.find('=') == std::string::npos) {
    return cases::Mu::Constant(1, parse_number(text, flag + ": "));
  }
  return parse_point(text, parameters, flag + ": ", false);
}

std::vector<double> parse_values_option(const std::vector<std::string>& items, const std::string& flag) {
  std::vector<double> values;
  for (std::size_t i = 0; i < items.size(); ++i) {
    values.push_back(parse_number(items[i], flag + " value " + std::to_string(i + 1) + ": "));
    // A repeated value adds a solve but no information, and a training set of one repeated
    // value gave a model that answered far from the HF solution with converged = true.
    if (i > 0 && !(values[i] > values[i - 1])) {
      throw Error(flag + ": the values must be strictly increasing, but value " + std::to_string(i + 1) + " (" +
                  exact(values[i]) + ") is not above value " + std::to_string(i) + " (" + exact(values[i - 1]) + ")");
    }
  }
  return values;
}

std::optional<std::vector<cases::Mu>> parse_values_points(const std::vector<std::string>& items, const std::string& flag,
                                                           const std::vector<cases::ParameterSpec>& parameters) {
  if (items.empty()) return std::nullopt;
  require(parameters.size() == 1, flag + " lists values of one parameter, but the case has " +
                                      std::to_string(parameters.size()) + " (" + names_of(parameters) +
                                      "): give the points as a named set of the case file ([sets]) and --set NAME");
  return cases::points_1d(parse_values_option(items, flag));
}

}  // namespace contactrb::app
