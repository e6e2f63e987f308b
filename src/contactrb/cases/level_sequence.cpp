#include "contactrb/cases/level_sequence.hpp"

#include <chrono>
#include <string>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/hf/level_transfer.hpp"

namespace contactrb::cases {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The solution of `from` as an initial guess of `to` (same case, same mu, another mesh).
hf::HFInitialGuess transfer(const hf::HFSolver& from, const hf::HFSolution& solution, const hf::HFSolver& to) {
  hf::HFInitialGuess guess;
  guess.u = hf::transfer_displacement(from.problem().mesh, solution.u, to.problem().mesh);
  guess.lambda = hf::transfer_pressure(from.problem().mesh, from.pair(), from.quadrature(), solution.lambda,
                                       to.problem().mesh, to.pair(), to.quadrature());
  return guess;
}
}  // namespace

std::vector<int> sequence_levels(int level, int count, int step) {
  require(count >= 0, "grid sequencing: the number of coarse levels must be >= 0 (got " + std::to_string(count) + ")");
  require(step >= 1, "grid sequencing: the level step must be >= 1 (got " + std::to_string(step) + ")");
  std::vector<int> levels;
  for (int k = count; k >= 1; --k) {
    const int l = level - k * step;
    if (l >= 0) levels.push_back(l);
  }
  return levels;
}

SequenceStart sequence_start(const CaseSpec& spec, const Mu& mu, const std::vector<int>& levels,
                             std::optional<contact::Discretization> constraint, const hf::HFSettings& settings,
                             const hf::HFSolver& fine) {
  const auto t0 = Clock::now();
  SequenceStart start;
  for (std::size_t k = 1; k < levels.size(); ++k) {
    require(levels[k - 1] < levels[k], "grid sequencing: the coarse levels must ascend");
  }
  std::optional<hf::HFSolver> previous;
  hf::HFSolution previous_solution;
  for (int level : levels) {
    SequenceStage stage;
    stage.level = level;
    auto t = Clock::now();
    hf::HFSolver solver(make_problem(spec, mu, level, constraint));
    stage.dofs = solver.problem().mesh.num_dofs();
    stage.mesh_s = seconds_since(t) - solver.setup_time_s();  // setup_time_s is in solve_s
    require(stage.dofs < fine.problem().mesh.num_dofs(),
            "grid sequencing: level " + std::to_string(level) + " is not coarser than the fine mesh");
    hf::HFInitialGuess guess;
    if (previous) {
      t = Clock::now();
      guess = transfer(*previous, previous_solution, solver);
      start.stages.back().transfer_s = seconds_since(t);
    }
    hf::HFSolution solution = solver.solve(settings, guess);
    stage.iterations = solution.iterations;
    stage.converged = solution.converged;
    stage.solve_s = solution.time_s;
    start.stages.push_back(stage);
    if (!solution.converged) break;  // the chain ends: the last converged stage's guess (below)
    previous.emplace(std::move(solver));
    previous_solution = std::move(solution);
  }
  if (previous) {
    const auto t = Clock::now();
    start.guess = transfer(*previous, previous_solution, fine);
    // The stage whose solution was transferred (the last converged one).
    for (auto it = start.stages.rbegin(); it != start.stages.rend(); ++it) {
      if (it->converged) {
        it->transfer_s = seconds_since(t);
        break;
      }
    }
  }
  start.time_s = seconds_since(t0);
  return start;
}

}  // namespace contactrb::cases
