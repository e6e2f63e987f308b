// contactrb-full: every subcommand (the mesh generation, the HF solver, the offline stage, the
// study). `contactrb` runs it for everything but a plain `online` (front_main.cpp); it can be
// run directly too.
#include <malloc.h>

#include <vector>

#include "cli_main.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
  // Freed memory stays in the process: glibc returns blocks above 32 MB and a large free heap top
  // to the OS, and every reuse page-faults again; the HF solver's 1 GB factor at 1.2e6 DOFs
  // (allocated inside CHOLMOD) then reuses the memory of the mesh generation and the assembly
  // (hertz-a level 7: 0.97M -> 0.65M page faults, docs/benchmarks.md "Page faults"). Process-wide:
  // set here, not in the library (peak resident memory +3 % at level 7).
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
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
