#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "commands.hpp"
#include "contactrb/common/error.hpp"

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
  require(end != text.c_str() && *end == '\0', what + "'" + text + "' is not a number");
  require(!std::isnan(mu), what + "'" + text + "' is not a number (NaN)");
  require(!std::isinf(mu), what + "'" + text + "' is not finite");
  // strtod signals both ends of the range with ERANGE: an overflow (already refused as
  // infinite above) or an underflow, which returns 0 or a subnormal: '1e-400' would silently
  // become mu = 0.
  require(errno != ERANGE, what + "'" + text + "' is below the smallest normal double (2.2e-308): it would be read as " +
                               exact(mu) + "; write 0 if you mean 0");
  return mu;
}

}  // namespace

double parse_mu_line(const std::string& line) { return parse_number(line, ""); }

double parse_mu_option(const std::string& text, const std::string& flag) { return parse_number(text, flag + ": "); }

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

}  // namespace contactrb::app
