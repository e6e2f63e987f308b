// One high-fidelity contact solve of a built-in case: hertz-a (two half-disks pressed together
// by an imposed displacement) at mu = 0.3, with the paper's Kacanov method (docs/cpp-api.md).
//
// Build (in the contactrb build tree, tests on):
//   cmake --build build --target example_hf_solve
// Run:
//   ./build/examples/cpp/example_hf_solve            # or: ctest --test-dir build -R example_hf_solve
// Prints the case, the iteration count, the energy and the contact force; exits 1 when the
// solver does not converge or the library throws (a bad case name, mu outside the domain).
#include <cstdio>
#include <exception>

#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/hf/hf_solver.hpp"

int main() {
  try {
    const double mu = 0.3;  // the imposed displacement delta, in [0.15, 0.45]
    // Mesh level 0 (the paper's mesh) and the case's own constraint kind (collocation).
    contactrb::hf::HFSolver solver(contactrb::cases::make_problem("hertz-a", mu));
    const contactrb::hf::HFSolution solution = solver.solve();  // default HFSettings: Kacanov
    if (!solution.converged) {  // non-convergence is a status, never an exception
      std::fprintf(stderr, "example_hf_solve: not converged: %s\n", solution.message.c_str());
      return 1;
    }
    std::printf("hertz-a, mu = %g: %zu DOFs, %zu constraint rows\n", mu, static_cast<std::size_t>(solution.u.size()),
                static_cast<std::size_t>(solution.lambda.size()));
    std::printf("converged in %d iterations\n", solution.iterations);
    std::printf("energy %.6g, contact force %.6g, active constraints %d\n", solution.energy,
                solution.contact_force, solution.active_constraints);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "example_hf_solve: %s\n", e.what());
    return 1;
  }
  return 0;
}
