#pragma once
// The mpirun tests of contactrb (tests/cli/test_snapshot_mpi.cpp, test_greedy_mpi.cpp):
// `contactrb ARGS` on K ranks, and the skip of a build without MPI (CONTACTRB_MPIEXEC empty).
#include <gtest/gtest.h>

#include <string>

#include "cli/cli_runner.hpp"

namespace contactrb::test {

// --oversubscribe: more ranks than cores; `timeout` turns a hang into exit code 124; the
// environment lets root run mpirun (mpirun_environment, cli_runner.hpp); `env`: more variables
// ("NAME=value ...").
inline CliResult mpirun(int ranks, const std::string& args, const std::string& env = "") {
  const std::string command = "timeout 300 " + shell_quote(CONTACTRB_MPIEXEC) + " --oversubscribe -np " +
                              std::to_string(ranks) + " " + shell_quote(CONTACTRB_CLI) + " " + args;
  return run_shell(command, "", mpirun_environment() + (env.empty() ? "" : " " + env));
}

// Occurrences of `word` in `text` (lines printed once by rank 0, not once per rank).
inline int count(const std::string& text, const std::string& word) {
  int n = 0;
  for (auto p = text.find(word); p != std::string::npos; p = text.find(word, p + 1)) ++n;
  return n;
}

}  // namespace contactrb::test

#define SKIP_WITHOUT_MPI()                                                                     \
  if (std::string(CONTACTRB_MPIEXEC).empty()) {                                               \
    GTEST_SKIP() << "this build has no MPI (CONTACTRB_WITH_MPI off or no MPI C library found)"; \
  }
