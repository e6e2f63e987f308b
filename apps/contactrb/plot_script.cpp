#include "plot_script.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "contactrb/common/error.hpp"

namespace contactrb::app {

namespace fs = std::filesystem;

std::string find_script(const std::string& name, const std::string& hint) {
  if (const char* env = std::getenv("CONTACTRB_SCRIPTS"); env != nullptr && *env != '\0') {
    const fs::path p = fs::path(env) / name;
    require(fs::is_regular_file(p), "CONTACTRB_SCRIPTS is set to '" + std::string(env) + "', which has no " + name);
    return p.string();
  }
  std::vector<fs::path> tried;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    tried.push_back(exe.parent_path().parent_path() / "share" / "contactrb" / name);
    // Installed, the commands that plot run as <prefix>/libexec/contactrb/contactrb-full
    // (apps/contactrb/CMakeLists.txt).
    tried.push_back(exe.parent_path().parent_path().parent_path() / "share" / "contactrb" / name);
  }
#ifdef CONTACTRB_SCRIPTS_DIR
  tried.push_back(fs::path(CONTACTRB_SCRIPTS_DIR) / name);
#endif
  std::string list;
  for (const fs::path& p : tried) {
    if (fs::is_regular_file(p)) return p.string();
    list += (list.empty() ? "" : ", ") + p.string();
  }
  throw Error("cannot find the plotting script " + name + " (tried " + list +
              "); set CONTACTRB_SCRIPTS to the directory that holds it, or " + hint);
}

void run_python_script(const std::string& script, const std::vector<std::string>& args, const std::string& what_is_there,
                       bool quiet) {
  const char* py_env = std::getenv("CONTACTRB_PYTHON");
  const std::string python = (py_env != nullptr && *py_env != '\0') ? py_env : "/usr/bin/python3";
  std::cout.flush();
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  require(pid >= 0, std::string("cannot start the plotting script: fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    if (quiet) {
      if (FILE* null = std::freopen("/dev/null", "w", stdout); null == nullptr) ::_exit(127);
    }
    std::vector<std::string> all{python, script};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(python.c_str(), argv.data());
    ::_exit(127);  // exec failed: no interpreter
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    require(errno == EINTR, std::string("waiting for the plotting script failed: ") + std::strerror(errno));
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  require(code != 127, "cannot run the Python interpreter '" + python + "' for the figure (set CONTACTRB_PYTHON); " +
                           what_is_there);
  require(code != kPlotMissingModules, "the figure needs matplotlib and numpy for " + python +
                                           " (Debian: apt-get install python3-matplotlib python3-numpy); " + what_is_there);
  require(code == 0, "the plotting script " + script + " failed (exit code " + std::to_string(code) + "); " + what_is_there);
}

}  // namespace contactrb::app
