// main() of test_fuzz: GoogleTest's, after taking the --fuzz-* options out of argv.
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "fuzz_options.hpp"

namespace contactrb::fuzz {

namespace {

Options& mutable_options() {
  static Options o;
  return o;
}

// A whole non-negative number, or exit with a usage message: a typo must not silently run
// the default suite.
std::uint64_t parse_count(const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  unsigned long long v = 0;
  try {
    v = std::stoull(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || text[0] == '-') {
    std::cerr << "test_fuzz: " << flag << " needs a whole number >= 0, got '" << text << "'\n";
    std::exit(2);
  }
  return v;
}

double parse_seconds(const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !(v > 0.0)) {
    std::cerr << "test_fuzz: " << flag << " needs a number of seconds > 0, got '" << text << "'\n";
    std::exit(2);
  }
  return v;
}

void apply(Options& o, const std::string& flag, const std::string& value) {
  if (flag == "--fuzz-cases") {
    o.cases = parse_count(flag, value);
    o.budget_s = 1e9;  // an explicit count runs whole unless --fuzz-seconds says otherwise
  } else if (flag == "--fuzz-seed") {
    o.seed = parse_count(flag, value);
  } else if (flag == "--fuzz-case") {
    o.single_case = parse_count(flag, value);
  } else if (flag == "--fuzz-seconds") {
    o.budget_s = parse_seconds(flag, value);
  } else if (flag == "--fuzz-timeout") {
    o.timeout_s = parse_seconds(flag, value);
  } else if (flag == "--fuzz-failures") {
    o.failures_dir = value;
  } else {
    std::cerr << "test_fuzz: unknown option " << flag
              << " (--fuzz-cases, --fuzz-seed, --fuzz-case, --fuzz-seconds, --fuzz-timeout, --fuzz-failures)\n";
    std::exit(2);
  }
}

}  // namespace

const Options& options() { return mutable_options(); }

}  // namespace contactrb::fuzz

int main(int argc, char** argv) {
  using contactrb::fuzz::apply;
  contactrb::fuzz::Options& o = contactrb::fuzz::mutable_options();
  // The environment first (ctest, scripts/test.sh), then the command line.
  const std::vector<std::pair<const char*, const char*>> env{{"CONTACTRB_FUZZ_CASES", "--fuzz-cases"},
                                                             {"CONTACTRB_FUZZ_SEED", "--fuzz-seed"},
                                                             {"CONTACTRB_FUZZ_SECONDS", "--fuzz-seconds"},
                                                             {"CONTACTRB_FUZZ_TIMEOUT", "--fuzz-timeout"},
                                                             {"CONTACTRB_FUZZ_FAILURES", "--fuzz-failures"}};
  for (const auto& [variable, flag] : env) {
    if (const char* v = std::getenv(variable); v != nullptr && *v != '\0') apply(o, flag, v);
  }
  ::testing::InitGoogleTest(&argc, argv);  // removes its own --gtest_* flags
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--fuzz-", 0) != 0) continue;
    const std::size_t eq = a.find('=');
    if (eq != std::string::npos) {
      apply(o, a.substr(0, eq), a.substr(eq + 1));
    } else if (i + 1 < argc) {
      apply(o, a, argv[++i]);
    } else {
      std::cerr << "test_fuzz: " << a << " needs a value\n";
      return 2;
    }
  }
  return RUN_ALL_TESTS();
}
