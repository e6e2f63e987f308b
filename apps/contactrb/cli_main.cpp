// The command-line driver both executables share (cli_main.hpp).
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_main.hpp"
#include "commands.hpp"
#include "mpi_world.hpp"
#include "usage_check.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/printable.hpp"
#include "contactrb/common/version.hpp"
#include "contactrb/online/online_many.hpp"

namespace {

// CLI11 reads an empty value ('') of a numeric option as 0, and strtod reads '1e-400' as 0:
// `--eps-pod ''` would silently become eps_pod = 0. Every numeric option of every
// subcommand refuses both as a usage error. (--mu and --values are read as text and parsed
// by parse_mu_option, which gives `contactrb: error:` messages.)
std::string empty_or_underflow(std::string& text) {
  if (text.find_first_not_of(" \t") == std::string::npos) return "the value is empty (expected a number)";
  errno = 0;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (end != text.c_str() && errno == ERANGE && std::abs(x) < 1.0) {
    return "'" + text + "' is below the smallest normal double (2.2e-308) and would be read as 0";
  }
  return "";
}

void refuse_empty_numbers(CLI::App& app, const CLI::Validator& check) {
  for (CLI::Option* o : app.get_options()) {
    const std::string type = o->get_type_name();
    if (type.find("FLOAT") != std::string::npos || type.find("INT") != std::string::npos) o->check(check);
  }
  // Option groups are nameless subcommands: recurse into them as well.
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) refuse_empty_numbers(*sub, check);
}

// --jobs above the hardware threads runs no faster and reserves a solver, a buffer and a thread
// per job (a batch with --jobs 1000000 reserved 7 GB before its first line): every command's
// --jobs is capped at the hardware threads, with a note. 0 (every thread) and values the
// command refuses (negative, not a number) pass through to its own check.
void cap_jobs(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    if (CLI::Option* jobs = sub->get_option_no_throw("--jobs")) {
      jobs->transform(CLI::Validator(
          [name = sub->get_name()](std::string& text) {
            char* end = nullptr;
            errno = 0;
            const long long requested = std::strtoll(text.c_str(), &end, 10);
            const long long threads = contactrb::online::hardware_jobs();
            if (end != text.c_str() && *end == '\0' && errno == 0 && requested > threads) {
              std::cerr << "contactrb: note: " << name << " --jobs " << requested << " is above the " << threads
                        << " hardware threads of this machine: using " << threads << "\n";
              text = std::to_string(threads);
            }
            return std::string();
          },
          "", "jobs cap"));
    }
    cap_jobs(*sub);
  }
}

}  // namespace

namespace contactrb::app {

int run_cli(int argc, char** argv, const std::function<std::vector<Command>(CLI::App&)>& add_commands,
            const std::function<void()>& on_parse_error) {
  CLI::App app{"contactrb: reduced-basis models of parametrized elastic frictionless contact"};
  app.set_version_flag("--version", std::string("contactrb ") + contactrb::kVersion);
  app.require_subcommand(0, 1);
  const std::vector<Command> commands = add_commands(app);
  refuse_empty_numbers(app, CLI::Validator(empty_or_underflow, "", "number"));
  cap_jobs(app);
  try {
    check_names(app, argc, argv);
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (on_parse_error) on_parse_error();
    // CLI11 quotes the offending argument: escaped like our own messages (help text and
    // --version go to stdout untouched).
    std::ostringstream err;
    const int code = app.exit(e, std::cout, err);
    std::cerr << contactrb::printable(err.str());
    return code;
  }
  try {
    for (const auto& command : commands) {
      if (!command.subcommand->parsed()) continue;
      // Under mpirun only the commands that split their work (docs/parallel.md): any other would
      // run whole in every process, each writing the same files.
      const std::string name = command.subcommand->get_name();
      const bool greedy = name == "offline" && command.subcommand->count("--greedy") > 0;
      if (contactrb::app::mpirun_processes() > 1 && name != "snapshots" && name != "online" && name != "sample" &&
          !greedy) {
        throw contactrb::Error("`contactrb " + name + "` does not run under mpirun with several processes (each would do "
                    "the whole run); mpirun runs snapshots, online --batch, sample and offline --greedy");
      }
      return command.run();
    }
    std::cout << app.help();
    return 0;
  } catch (const contactrb::Error& e) {
    // Messages quote the user's input (paths, lines): escaped so that a control character
    // cannot act on the terminal.
    std::cerr << "contactrb: error: " << contactrb::printable(e.what()) << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "contactrb: internal error: " << contactrb::printable(e.what()) << "\n";
    return 2;
  } catch (...) {
    std::cerr << "contactrb: internal error: unknown exception\n";
    return 2;
  }
}

}  // namespace contactrb::app
