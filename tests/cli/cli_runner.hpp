#pragma once
// Runs the built contactrb executable (CONTACTRB_CLI) through the shell and captures its
// exit code, stdout and stderr separately.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace contactrb::test {

struct CliResult {
  int exit_code = -1;  // -1 when the process did not exit normally (a crash)
  std::string out;
  std::string err;
};

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q += c;
    }
  }
  return q + "'";
}

// Runs `command` (a shell command line, quoted as needed) in `working_dir` when it is not
// empty, with `env` ("NAME=value NAME2=value2") set for it.
inline CliResult run_shell(const std::string& command, const std::string& working_dir = "", const std::string& env = "") {
  static int counter = 0;
  const std::filesystem::path err_file = std::filesystem::temp_directory_path() /
                                         ("contactrb_cli_stderr_" + std::to_string(static_cast<long>(::getpid())) +
                                          "_" + std::to_string(counter++));
  const std::string cd = working_dir.empty() ? std::string() : "cd " + shell_quote(working_dir) + " && ";
  const std::string cmd = cd + (env.empty() ? "" : "env " + env + " ") + command + " 2>" + shell_quote(err_file.string());
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("popen failed for: " + cmd);
  CliResult r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err_file);
  std::stringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  std::filesystem::remove(err_file);
  return r;
}

// `args` is appended to the command line as is (quote paths with shell_quote); the command
// runs in `working_dir` when it is not empty, in the test's working directory otherwise;
// `env` ("NAME=value NAME2=value2", quoted as needed) is set for the command only.
inline CliResult run_cli(const std::string& args, const std::string& working_dir = "", const std::string& env = "") {
  return run_shell(shell_quote(CONTACTRB_CLI) + " " + args, working_dir, env);
}

// The environment of the mpirun tests: root may run mpirun (CI containers). In the sanitizer
// build LeakSanitizer is off for the MPI processes: OpenMPI's MPI_Init keeps ~120 KB in its
// unloaded plugins until exit (frames unsymbolized, so no suppression can match them; measured
// with ./scripts/test.sh --sanitize). Every other sanitizer check stays on, and the same code
// paths are leak-checked without MPI.
inline std::string mpirun_environment() {
  std::string env = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1";
#ifdef __SANITIZE_ADDRESS__
  env += " ASAN_OPTIONS=detect_leaks=0:abort_on_error=1";
#endif
  return env;
}

// The lines of `text`, without their '\n'.
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

// Value after "key: " on its own line of `text`, or "" when absent.
inline std::string field_value(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::string line;
  const std::string prefix = key + ": ";
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) return line.substr(prefix.size());
  }
  return "";
}

// A user error: exit code 1 and one "contactrb: error: " message on stderr that holds `words`.
inline void expect_user_error(const CliResult& r, const std::string& words) {
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(r.err.rfind("contactrb: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(words), std::string::npos) << r.err << "\n(expected: " << words << ")";
}

}  // namespace contactrb::test
