// contactrb command line: subcommands grow issue by issue (docs/user-guide.md).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "contactrb/common/error.hpp"
#include "contactrb/common/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"contactrb: reduced-basis models of parametrized elastic frictionless contact"};
  app.set_version_flag("--version", std::string("contactrb ") + contactrb::kVersion);
  app.require_subcommand(0, 1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (app.get_subcommands().empty()) {
      std::cout << app.help();
      return 0;
    }
  } catch (const contactrb::Error& e) {
    std::cerr << "contactrb: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "contactrb: internal error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
