#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

#include "commands.hpp"
#include "contactrb/common/error.hpp"

namespace contactrb::app {

double parse_mu_line(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  require(first != std::string::npos, "empty line (expected one parameter value)");
  const auto last = line.find_last_not_of(" \t\r");
  const std::string text = line.substr(first, last - first + 1);
  errno = 0;
  char* end = nullptr;
  const double mu = std::strtod(text.c_str(), &end);
  require(end != text.c_str() && *end == '\0' && errno != ERANGE, "'" + text + "' is not a number");
  require(!std::isnan(mu), "'" + text + "' is not a number (NaN)");
  return mu;
}

}  // namespace contactrb::app
