#pragma once
// The contactrb command line (docs/cli.md), shared by the two executables:
// `contactrb` (front_main.cpp: answers `online` itself with the online library only, hands every
// other command to the full executable) and `contactrb-full` (main.cpp: every command).
// Exit codes: 0 success, 1 an error the user can fix (one line on stderr), CLI11's own
// non-zero codes for usage errors, 2 an internal error (a bug: please report it).
#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

#include "commands.hpp"

namespace contactrb::app {

// Parses argv with the subcommands add_commands registers and runs the one given.
// on_parse_error (if set) is called on any CLI11 parse outcome other than success (usage error,
// --help, --version) before anything is printed; it may replace the process (front_main.cpp).
int run_cli(int argc, char** argv, const std::function<std::vector<Command>(CLI::App&)>& add_commands,
            const std::function<void()>& on_parse_error = {});

}  // namespace contactrb::app
