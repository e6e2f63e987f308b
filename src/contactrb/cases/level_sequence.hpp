#pragma once
// Grid sequencing (nested iteration) on the built-in refinement levels (docs/solvers.md, "Grid
// sequencing"): the same case at the same mu is solved on coarser levels first, each from the
// previous one's solution transferred (hf/level_transfer.hpp), and the last one's transferred
// solution is the initial guess of the fine solve. The answer is the fine solve's, to its own
// tolerance: the coarse solves only choose where it starts.
#include <optional>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/hf/hf_solver.hpp"

namespace contactrb::cases {

// The coarse levels of a sequence towards `level`: level - count * step, ..., level - step,
// without the negative ones (count 0: none). Throws contactrb::Error for count < 0 or step < 1.
std::vector<int> sequence_levels(int level, int count, int step = 2);

// The number of coarse levels when none is asked for (`--sequence -1`, docs/solvers.md, "Grid
// sequencing"): kAutoSequence with the Newton method in 2D from level kAutoSequenceFromLevel on,
// kAutoSequence3d in 3D from kAutoSequence3dFromLevel on, 0 otherwise. Measured (docs/performance.md, "Grid sequencing from level 4"): with Newton, two
// coarse stages (levels L - 4, L - 2) cut hertz-a's time from level 5 on (level 5: -14 % at mu
// 0.3, -25 % at mu 0.45; level 7: -15 to -30 %) and break even on level 4 over the mu range (+17 %
// / +6 % / -13 % at mu 0.15 / 0.3 / 0.45), where they take the fine solve from 5 / 8 / 9 Newton
// iterations to 3 / 4 / 4. Kacanov: never automatic (its answer depends on the start to its
// tolerance eps_KA, docs/solvers.md "Warm start").
inline constexpr int kAutoSequence = 2;
inline constexpr int kAutoSequenceFromLevel = 4;
// In 3D, one coarse stage (level L - 2) from level 3 on. Measured (docs/performance.md, "HF
// scaling in 3D"; hertz-3d, Newton with the AMG linear solver that `auto` picks there): level 3
// 8.3 s against 11.9 s cold, level 4 98 s against 204 s; on level 2 (direct) it does not pay.
inline constexpr int kAutoSequence3d = 1;
inline constexpr int kAutoSequence3dFromLevel = 3;
int default_sequence(int dimension, hf::HFMethod method, int level);

// `requested` (>= 0: as given; -1: default_sequence). Throws contactrb::Error naming `option`
// for anything below -1.
int resolve_sequence(int requested, int dimension, hf::HFMethod method, int level,
                     const std::string& option = "--sequence");

struct SequenceStage {
  int level = 0;
  int dofs = 0;
  int iterations = 0;
  bool converged = false;
  double mesh_s = 0.0;      // wall time of the stage's mesh generation and problem
  double solve_s = 0.0;     // HFSolution::time_s (setup + iterations)
  double transfer_s = 0.0;  // transfer of its solution to the next level
};

struct SequenceStart {
  hf::HFInitialGuess guess;  // for the fine solver (empty: no coarse stage converged)
  std::vector<SequenceStage> stages;
  double time_s = 0.0;  // all of the stages, wall
};

// The reference meshes of the coarse levels (ascending) and the wall time of each one's
// generation. A caller that starts other threads before the coarse stages (the Newton solver's
// analysis beside them, hf::HFSetupOptions) generates them first: Gmsh's 3D Delaunay mesher
// gives another mesh when another thread allocates meanwhile (hertz-3d level 0: 2520, 2544 or
// 2562 DOFs from run to run), and the answer would then depend on the run.
template <int Dim>
struct CoarseMeshes {
  std::vector<int> levels;
  std::vector<mesh::SimplexMesh<Dim>> meshes;
  std::vector<double> mesh_s;
};
template <int Dim>
CoarseMeshes<Dim> coarse_meshes(const CaseSpec& spec, const std::vector<int>& levels);

// The coarse stages on `levels` (ascending, each below the fine solver's level) of the built-in
// or TOML case `spec` at mu, the HF settings `settings` on each, and the initial guess for
// `fine` (a solver of the same case at mu on the finer level). A stage that does not converge
// ends the chain: the guess is the last converged stage's (or none), and the stage says so.
// Dim = 2 or 3: one path, the transfer of the dimension (hf/level_transfer.hpp).
template <int Dim>
SequenceStart sequence_start(const CaseSpec& spec, const Mu& mu, const std::vector<int>& levels,
                             std::optional<contact::Discretization> constraint, const hf::HFSettings& settings,
                             const hf::BasicHFSolver<Dim>& fine);
// The same on meshes generated before (coarse_meshes).
template <int Dim>
SequenceStart sequence_start(const CaseSpec& spec, const Mu& mu, const CoarseMeshes<Dim>& coarse,
                             std::optional<contact::Discretization> constraint, const hf::HFSettings& settings,
                             const hf::BasicHFSolver<Dim>& fine);

}  // namespace contactrb::cases
