#include "hf_solver_option.hpp"

#include "commands.hpp"

namespace contactrb::app {

CLI::Option* add_snapshot_solver_option(CLI::App* sub, std::optional<std::string>& solver, const std::string& prefix) {
  return sub->add_option("--solver", solver,
                         prefix + "HF solver of the snapshots: kacanov (the paper's) | newton (semi-smooth Newton); "
                                  "default: kacanov on 2D level 0, newton otherwise (docs/solvers.md)");
}

std::optional<hf::HFMethod> snapshot_solver_option(const std::optional<std::string>& solver) {
  if (!solver) return std::nullopt;
  return option_enum("--solver", *solver, hf::hf_method_from_string);
}

}  // namespace contactrb::app
