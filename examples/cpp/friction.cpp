// Frictional contact along a load path: the Cattaneo-Mindlin case (hertz-a's half-disks pressed
// together, then the upper flat edge moved sideways) with Coulomb friction f = 0.3
// (docs/solvers.md, "Friction"; docs/cases.md, "Frictional cases").
//
// Build (in the contactrb build tree, tests on):
//   cmake --build build --target example_friction
// Run:
//   ./build/examples/cpp/example_friction            # or: ctest --test-dir build -R example_friction
// Prints each load step (status, Newton iterations, forces, stick and slip nodes) and the ratio
// Q / (f P); exits 1 when a step does not converge or the library throws.
#include <cmath>
#include <cstdio>
#include <exception>

#include "contactrb/cases/frictional_cases.hpp"
#include "contactrb/hf/friction.hpp"

int main() {
  try {
    // Mesh level 2 (121 slave arc nodes); approach 0.13, tangential displacement 0.01 in two steps.
    const contactrb::cases::FrictionalCase c = contactrb::cases::cattaneo_case(2, {0.13, 0.01, 0.3, 2});
    const contactrb::hf::FrictionalSolution s = contactrb::hf::solve_load_path(c.problem, c.path, c.friction);
    for (std::size_t i = 0; i < s.steps.size(); ++i) {
      const contactrb::hf::FrictionStepReport& r = s.steps[i];
      std::printf("step %zu: %s in %d iterations, P %.5f, Q %.5f, %d stick, %d slip\n", i + 1,
                  contactrb::hf::to_string(r.status), r.iterations, r.normal_force, r.tangential_force(0), r.stick,
                  r.slip);
    }
    if (!s.converged) {  // non-convergence (and full sliding) is a status, never an exception
      std::fprintf(stderr, "example_friction: %s\n", s.message.c_str());
      return 1;
    }
    std::printf("Q / (f P) = %.4f\n", std::abs(s.tangential_force(0)) / (c.friction.coefficient * s.contact_force));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "example_friction: %s\n", e.what());
    return 1;
  }
  return 0;
}
