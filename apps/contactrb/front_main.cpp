// contactrb: the command-line entry point (docs/cli.md, "Two executables"). It links the online library
// only (Eigen, HDF5: contactrb::online), so that `contactrb online --model m.h5 --mu X` (and
// `contactrb sample`) costs a few milliseconds of process start instead of loading gmsh,
// OpenCASCADE, FLTK and the sparse solvers (docs/performance.md, "Online query"). Every
// other command, `online --out` (the HF mesh of the case), either under mpirun, --help,
// --version and any usage error are handed to the full executable contactrb-full (main.cpp) by
// execv with the same arguments, so that their output and exit codes are those of one program.
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "cli_main.hpp"
#include "commands.hpp"
#include "mpi_world.hpp"

#ifndef CONTACTRB_FULL_NAME
#define CONTACTRB_FULL_NAME "contactrb-full"
#endif
#ifndef CONTACTRB_FULL_FROM_BIN
#define CONTACTRB_FULL_FROM_BIN "../libexec/contactrb"
#endif

namespace {

// Whether this process answers the command itself: `online` or `sample`, and none of the
// arguments that need more than the online library or whose output the full program gives
// (help, version).
bool answers_itself(int argc, char** argv) {
  if (argc < 2) return false;
  const std::string_view command(argv[1]);
  if (command != "online" && command != "sample") return false;
  // Under mpirun the full program answers (this one is built without MPI, to start fast).
  if (contactrb::app::mpirun_processes() > 1) return false;
  for (int i = 2; i < argc; ++i) {
    const std::string_view a(argv[i]);
    if (a == "-h" || a == "--help" || a == "--version") return false;
    // online --out: the reconstructed fields on the HF mesh (sample's --out is its CSV).
    if (command == "online" && (a == "--out" || a.starts_with("--out="))) return false;
  }
  return true;
}

// contactrb-full next to this executable (the build tree), else in the installed libexec
// directory relative to it (CONTACTRB_FULL_FROM_BIN, from CMake's install directories).
std::filesystem::path full_executable() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path dir = ec ? std::filesystem::path(".") : self.parent_path();
  for (const std::filesystem::path& p : {dir / CONTACTRB_FULL_NAME, dir / CONTACTRB_FULL_FROM_BIN / CONTACTRB_FULL_NAME}) {
    if (::access(p.c_str(), X_OK) == 0) return p;
  }
  return dir / CONTACTRB_FULL_FROM_BIN / CONTACTRB_FULL_NAME;
}

[[noreturn]] void run_full(char** argv) {
  const std::filesystem::path full = full_executable();
  ::execv(full.c_str(), argv);  // argv[0] unchanged: the usage lines name the program as typed
  // A deployment error, not a bug: exit code 1 like any error the user can fix.
  std::cerr << "contactrb: error: cannot run " << full.string() << ": " << std::strerror(errno)
            << " (every command but online and sample runs contactrb-full, installed with contactrb in "
            << CONTACTRB_FULL_FROM_BIN << "/ next to bin/: reinstall contactrb)\n";
  std::exit(1);
}

}  // namespace

int main(int argc, char** argv) {
  if (!answers_itself(argc, argv)) run_full(argv);
  using namespace contactrb::app;
  return run_cli(
      argc, argv, [](CLI::App& app) { return std::vector<Command>{add_online_command(app, nullptr), add_sample_command(app)}; },
      [argv] { run_full(argv); });
}
