// `contactrb cases`: one line per built-in case (paper Section 6, the 3D cases and the frictional ones), with its dimension.
#include <iomanip>
#include <iostream>
#include <vector>

#include "commands.hpp"
#include "contactrb/cases/catalog.hpp"

namespace contactrb::app {

Command add_cases_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("cases", "List the built-in cases, one per line: name, dimension, summary");
  return {sub, [] {
            std::size_t width = 0;
            std::vector<cases::CaseInfo> all = cases::builtin_cases();
            for (const auto& c : cases::frictional_builtin_cases()) all.push_back(c);
            for (const auto& c : all) width = std::max(width, c.name.size());
            for (const auto& c : all) {
              std::cout << std::left << std::setw(static_cast<int>(width) + 2) << c.name << c.dimension << "D  "
                        << c.summary << "\n";
            }
            return 0;
          }};
}

}  // namespace contactrb::app
