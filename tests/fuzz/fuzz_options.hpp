#pragma once
// Options of the fuzz suite (docs/testing.md): from the command line of test_fuzz
// (--fuzz-cases N, --fuzz-seed S, --fuzz-case K, --fuzz-seconds T, --fuzz-timeout T,
// --fuzz-failures DIR) or, for ctest and scripts/test.sh, from the environment
// (CONTACTRB_FUZZ_CASES, CONTACTRB_FUZZ_SEED, CONTACTRB_FUZZ_SECONDS, CONTACTRB_FUZZ_TIMEOUT,
// CONTACTRB_FUZZ_FAILURES). The command line wins.
#include <cstdint>
#include <filesystem>
#include <optional>

namespace contactrb::fuzz {

struct Options {
  std::uint64_t seed = 20260323;               // fixed: the ctest run is the same every time
  std::optional<std::size_t> cases;            // per target; absent: the target's default
  std::optional<std::size_t> single_case;      // run this case index only (reproduction)
  double budget_s = 40.0;                      // per target: stop starting cases after this
  double timeout_s = 30.0;                     // per case: longer is a hang
  std::filesystem::path failures_dir = "fuzz-failures";
};

const Options& options();

}  // namespace contactrb::fuzz
