#pragma once
// --solver of the commands that solve HF snapshots (snapshots, offline, report): the HF method of
// offline::SnapshotRequest::settings (docs/solvers.md, "Which solver for snapshots"); --sequence of
// every command that solves HF (docs/solvers.md, "Grid sequencing").
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "contactrb/hf/hf_solver.hpp"

namespace contactrb::app {

// Adds --solver to `sub`, stored in `solver` (nullopt when not given); `prefix` opens its help
// ("With --case: ").
CLI::Option* add_snapshot_solver_option(CLI::App* sub, std::optional<std::string>& solver, const std::string& prefix = "");

// The method of --solver as given (nullopt: not given, the request's default stays). Throws
// contactrb::Error naming --solver and the accepted values for anything else.
std::optional<hf::HFMethod> snapshot_solver_option(const std::optional<std::string>& solver);

// Adds --sequence K to `sub`, stored in `sequence` (-1: automatic, cases::resolve_sequence), the
// grid sequencing of `solve` (docs/solvers.md, "Grid sequencing"); `prefix` opens its help, `what`
// names the solves it applies to.
CLI::Option* add_sequence_option(CLI::App* sub, int& sequence, const std::string& prefix = "",
                                 const std::string& what = "");

// Throws contactrb::Error naming --sequence for a value below -1 (the cheap check before any mesh).
void check_sequence_option(int sequence);

}  // namespace contactrb::app
