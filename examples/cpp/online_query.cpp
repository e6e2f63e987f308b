// Load a reduced model file and answer one parameter value online (paper Algorithm 1), with
// the a posteriori estimate of the energy-norm error (docs/cpp-api.md). Only the online library
// is needed (contactrb::online: Eigen and HDF5; no mesh generation, FE assembly or sparse solver).
//
// Build (in the contactrb build tree, tests on):
//   cmake --build build --target example_online_query
// Run, on a model of hertz-b (examples/cpp/build_model.cpp or `contactrb offline --case hertz-b`):
//   ./build/examples/cpp/example_online_query out/hertz-b-model.h5 1.01
//   (same answer as: contactrb online --model out/hertz-b-model.h5 --mu 1.01)
// Exits 1 when the file cannot be read, mu is outside the model's domain, or the solve does not
// converge.
#include <cstdio>
#include <exception>
#include <string>

#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/online/online_solver.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: example_online_query MODEL.h5 MU\n");
    return 1;
  }
  try {
    const contactrb::model::ReducedModel model = contactrb::io::read_reduced_model_file(argv[1]);
    contactrb::online::OnlineSolver solver(model);  // the model's largest N, R, Mk, Mg
    const contactrb::online::OnlineSolution s = solver.solve(std::stod(argv[2]));
    if (!s.converged()) {  // non-convergence is a status; s.message says why
      std::fprintf(stderr, "example_online_query: not converged: %s\n", s.message.c_str());
      return 1;
    }
    std::printf("mu = %s: N %d, R %d, %d iterations\n", argv[2], solver.N(), solver.R(), s.iterations);
    std::printf("energy %.17g, contact force %.17g\n", s.energy, s.contact_force);
    if (s.estimate.available) std::printf("error estimate |u_hf - u_rb|_A <= %.3g\n", s.estimate.energy);
  } catch (const std::exception& e) {  // contactrb::Error: the message the CLI prints
    std::fprintf(stderr, "example_online_query: %s\n", e.what());
    return 1;
  }
  return 0;
}
