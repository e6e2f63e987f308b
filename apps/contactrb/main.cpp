// contactrb-full: every subcommand (the mesh generation, the HF solver, the offline stage, the
// study). `contactrb` runs it for everything but a plain `online` (front_main.cpp); it can be
// run directly too.
#include <vector>

#include "cli_main.hpp"
#include "contactrb/common/keep_freed_memory.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
  contactrb::keep_freed_memory();  // the HF solver's factor reuses freed memory (the header says why)
  using namespace contactrb::app;
  return run_cli(argc, argv, [](CLI::App& app) {
    return std::vector<Command>{
        add_cases_command(app),     add_mesh_command(app),   add_solve_command(app),
        add_snapshots_command(app), add_merge_command(app),    add_offline_command(app),
        add_online_command(app, online_field_hooks()),         add_sample_command(app),
        add_evaluate_command(app),  add_report_command(app),   add_demo_command(app),
    };
  });
}
