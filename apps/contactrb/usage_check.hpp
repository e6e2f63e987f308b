#pragma once
// Unknown subcommands and options, named with the nearest known name, before CLI11 parses:
// CLI11 reports `contactrb offlin --case hertz-b` as "arguments not expected: hertz-b --case
// offlin" and `--modle` as "--model is required".
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace contactrb::app {

// The nearest of `known` to `word` by edit distance, or "" when none is close (at most a third
// of the word's letters, and at least one, differ; a word that is a prefix of a known one counts).
std::string nearest_name(const std::string& word, const std::vector<std::string>& known);

// Throws CLI::ExtrasError naming an unknown subcommand (argv[1]) or an unknown long option of
// the given subcommand ("--name" or "--name=value"), with a suggestion. Values that follow an
// option are not options, so only arguments that start with "--" are checked.
void check_names(const CLI::App& app, int argc, char** argv);

}  // namespace contactrb::app
