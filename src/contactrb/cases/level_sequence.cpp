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
template <int Dim>
hf::HFInitialGuess transfer(const hf::BasicHFSolver<Dim>& from, const hf::BasicHFSolution<Dim>& solution,
                            const hf::BasicHFSolver<Dim>& to) {
  hf::HFInitialGuess guess;
  guess.u = hf::transfer_displacement(from.problem().mesh, solution.u, to.problem().mesh);
  guess.lambda = hf::transfer_pressure(from.problem().mesh, from.pair(), from.quadrature(), solution.lambda,
                                       to.problem().mesh, to.pair(), to.quadrature());
  return guess;
}
// The case's reference mesh of `level`.
template <int Dim>
mesh::SimplexMesh<Dim> reference_at_level(const CaseSpec& spec, int level) {
  if constexpr (Dim == 2) {
    return reference_mesh(spec, level);
  } else {
    return reference_mesh3(spec, level);
  }
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

int default_sequence(int dimension, hf::HFMethod method, int level) {
  if (method != hf::HFMethod::Newton) return 0;
  if (dimension == 3) return level >= kAutoSequence3dFromLevel ? kAutoSequence3d : 0;
  return level >= kAutoSequenceFromLevel ? kAutoSequence : 0;
}

int resolve_sequence(int requested, int dimension, hf::HFMethod method, int level, const std::string& option) {
  require(requested >= -1,
          option + " must be >= 0, or -1 for automatic (got " + std::to_string(requested) + ")");
  return requested < 0 ? default_sequence(dimension, method, level) : requested;
}

template <int Dim>
CoarseMeshes<Dim> coarse_meshes(const CaseSpec& spec, const std::vector<int>& levels) {
  for (std::size_t k = 1; k < levels.size(); ++k) {
    require(levels[k - 1] < levels[k], "grid sequencing: the coarse levels must ascend");
  }
  CoarseMeshes<Dim> coarse;
  coarse.levels = levels;
  for (int level : levels) {
    const auto t = Clock::now();
    coarse.meshes.push_back(reference_at_level<Dim>(spec, level));
    coarse.mesh_s.push_back(seconds_since(t));
  }
  return coarse;
}

template <int Dim>
SequenceStart sequence_start(const CaseSpec& spec, const Mu& mu, const std::vector<int>& levels,
                             std::optional<contact::Discretization> constraint, const hf::HFSettings& settings,
                             const hf::BasicHFSolver<Dim>& fine) {
  const auto t0 = Clock::now();
  SequenceStart start = sequence_start(spec, mu, coarse_meshes<Dim>(spec, levels), constraint, settings, fine);
  start.time_s = seconds_since(t0);
  return start;
}

template <int Dim>
SequenceStart sequence_start(const CaseSpec& spec, const Mu& mu, const CoarseMeshes<Dim>& coarse,
                             std::optional<contact::Discretization> constraint, const hf::HFSettings& settings,
                             const hf::BasicHFSolver<Dim>& fine) {
  const auto t0 = Clock::now();
  SequenceStart start;
  require(coarse.meshes.size() == coarse.levels.size() && coarse.mesh_s.size() == coarse.levels.size(),
          "grid sequencing: one coarse mesh per level");
  double meshes_s = 0.0;
  std::optional<hf::BasicHFSolver<Dim>> previous;
  hf::BasicHFSolution<Dim> previous_solution;
  for (std::size_t k = 0; k < coarse.levels.size(); ++k) {
    const int level = coarse.levels[k];
    SequenceStage stage;
    stage.level = level;
    auto t = Clock::now();
    spec.check_mu(mu);
    hf::BasicHFSolver<Dim> solver(make_problem(spec, coarse.meshes[k], mu, constraint));
    stage.dofs = solver.problem().mesh.num_dofs();
    // The mesh's generation and the problem; setup_time_s is in solve_s.
    stage.mesh_s = coarse.mesh_s[k] + seconds_since(t) - solver.setup_time_s();
    meshes_s += coarse.mesh_s[k];
    require(stage.dofs < fine.problem().mesh.num_dofs(),
            "grid sequencing: level " + std::to_string(level) + " is not coarser than the fine mesh");
    hf::HFInitialGuess guess;
    if (previous) {
      t = Clock::now();
      guess = transfer(*previous, previous_solution, solver);
      start.stages.back().transfer_s = seconds_since(t);
    }
    hf::BasicHFSolution<Dim> solution = solver.solve(settings, guess);
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
  start.time_s = meshes_s + seconds_since(t0);
  return start;
}

template CoarseMeshes<2> coarse_meshes(const CaseSpec&, const std::vector<int>&);
template CoarseMeshes<3> coarse_meshes(const CaseSpec&, const std::vector<int>&);
template SequenceStart sequence_start(const CaseSpec&, const Mu&, const CoarseMeshes<2>&,
                                      std::optional<contact::Discretization>, const hf::HFSettings&,
                                      const hf::BasicHFSolver<2>&);
template SequenceStart sequence_start(const CaseSpec&, const Mu&, const CoarseMeshes<3>&,
                                      std::optional<contact::Discretization>, const hf::HFSettings&,
                                      const hf::BasicHFSolver<3>&);
template SequenceStart sequence_start(const CaseSpec&, const Mu&, const std::vector<int>&,
                                      std::optional<contact::Discretization>, const hf::HFSettings&,
                                      const hf::BasicHFSolver<2>&);
template SequenceStart sequence_start(const CaseSpec&, const Mu&, const std::vector<int>&,
                                      std::optional<contact::Discretization>, const hf::HFSettings&,
                                      const hf::BasicHFSolver<3>&);

}  // namespace contactrb::cases
