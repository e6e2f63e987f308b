#include "hf_solver_option.hpp"

#include "commands.hpp"
#include "contactrb/common/error.hpp"

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

CLI::Option* add_sequence_option(CLI::App* sub, int& sequence, const std::string& prefix, const std::string& what) {
  return sub
      ->add_option("--sequence", sequence,
                   prefix + "Grid sequencing" + what +
                       ": solve first on K coarser levels (level - 2K, ..., level - 2; those below 0 skipped) and "
                       "start from the last one's solution; -1: 2 with the newton solver on level >= 4 in 2D, 1 on "
                       "level >= 3 in 3D, 0 otherwise (docs/solvers.md)")
      ->capture_default_str();
}

void check_sequence_option(int sequence) {
  require(sequence >= -1, "--sequence must be >= 0, or -1 for automatic (got " + std::to_string(sequence) + ")");
}

}  // namespace contactrb::app
