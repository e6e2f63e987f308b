#pragma once
// Running a plotting script of scripts/ (matplotlib) from a command: found next to the
// installed binary (<prefix>/share/contactrb), in $CONTACTRB_SCRIPTS, or in the source tree;
// run with $CONTACTRB_PYTHON, else /usr/bin/python3, without a shell.
#include <string>
#include <vector>

namespace contactrb::app {

// Exit code of the scripts when matplotlib / numpy cannot be imported.
inline constexpr int kPlotMissingModules = 2;

// The path of scripts/`name`; throws contactrb::Error listing the places tried (`hint`: what
// the user can do instead, e.g. "use --no-plot").
std::string find_script(const std::string& name, const std::string& hint);

// Runs the script with `args` (its stdout to /dev/null when `quiet`) and returns nothing; throws
// contactrb::Error saying what failed (no interpreter, no matplotlib, the script's exit code),
// followed by `what_is_there`.
void run_python_script(const std::string& script, const std::vector<std::string>& args, const std::string& what_is_there,
                       bool quiet = false);

}  // namespace contactrb::app
