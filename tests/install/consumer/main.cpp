// Loads a reduced model file, answers one query online and prints the energy (full precision).
//   consumer <model.h5> <mu> [expected_energy [iteration]]
// With expected_energy (the CLI's, tests/install/run_install_test.cmake): exit 1 unless the two
// agree to round-off (relative kRelativeTolerance). iteration: the reduced iteration, as
// `contactrb online --iteration` (default: automatic).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/online/online_solver.hpp"

namespace {
// Same library, same model, same mu: only the decimal round trip of the CLI's JSON differs.
constexpr double kRelativeTolerance = 1e-12;
}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 5) {
    std::fprintf(stderr, "usage: consumer <model.h5> <mu> [expected_energy [iteration]]\n");
    return 2;
  }
  try {
    const contactrb::model::ReducedModel model = contactrb::io::read_reduced_model_file(argv[1]);
    contactrb::online::OnlineSolver solver(model);
    contactrb::online::OnlineSettings settings;
    if (argc == 5) settings.iteration = contactrb::online::online_iteration_from_string(argv[4]);
    const contactrb::online::OnlineSolution solution = solver.solve(std::stod(argv[2]), settings);
    if (!solution.converged()) {
      std::fprintf(stderr, "consumer: not converged: %s\n", solution.message.c_str());
      return 1;
    }
    std::printf("energy %.17g (N %d, R %d, %d iterations)\n", solution.energy, solver.N(), solver.R(),
                solution.iterations);
    if (argc >= 4) {
      const double expected = std::stod(argv[3]);
      const double difference = std::abs(solution.energy - expected);
      if (!(difference <= kRelativeTolerance * std::max(1.0, std::abs(expected)))) {
        std::fprintf(stderr, "consumer: energy %.17g differs from the expected %.17g by %.3g\n", solution.energy,
                     expected, difference);
        return 1;
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
  return 0;
}
