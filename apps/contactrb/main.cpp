// contactrb command line: subcommands grow issue by issue (docs/user-guide.md).
// Exit codes: 0 success, 1 an error the user can fix (one line on stderr), CLI11's own
// non-zero codes for usage errors, 2 an internal error (a bug: please report it).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <sstream>
#include <vector>

#include "commands.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/printable.hpp"
#include "contactrb/common/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"contactrb: reduced-basis models of parametrized elastic frictionless contact"};
  app.set_version_flag("--version", std::string("contactrb ") + contactrb::kVersion);
  app.require_subcommand(0, 1);
  const std::vector<contactrb::app::Command> commands{
      contactrb::app::add_cases_command(app),
      contactrb::app::add_mesh_command(app),
      contactrb::app::add_solve_command(app),
      contactrb::app::add_snapshots_command(app),
      contactrb::app::add_offline_command(app),
      contactrb::app::add_online_command(app),
      contactrb::app::add_evaluate_command(app),
      contactrb::app::add_report_command(app),
      contactrb::app::add_demo_command(app),
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 quotes the offending argument: escaped like our own messages (help text and
    // --version go to stdout untouched).
    std::ostringstream err;
    const int code = app.exit(e, std::cout, err);
    std::cerr << contactrb::printable(err.str());
    return code;
  }
  try {
    for (const auto& command : commands) {
      if (command.subcommand->parsed()) return command.run();
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
