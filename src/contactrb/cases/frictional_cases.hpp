#pragma once
// Frictional cases: a contact problem, its load path and its friction law (hf/friction.hpp;
// docs/cases.md, "Frictional cases"): the built-in cattaneo (catalog.hpp,
// frictional_builtin_cases), cattaneo-3d (the same), case files with friction keys (2D and 3D), and
// block-on-block-3d, built from C++.
// Reduced models are frictionless.
#include <Eigen/Core>
#include <vector>

#include "contactrb/cases/case_toml.hpp"
#include "contactrb/cases/parameter.hpp"
#include "contactrb/hf/contact_problem.hpp"
#include "contactrb/hf/friction.hpp"

namespace contactrb::cases {

template <int Dim>
struct BasicFrictionalCase {
  hf::BasicContactProblem<Dim> problem;      // the mesh, materials and constraint rows
  std::vector<hf::BasicLoadStep<Dim>> path;  // in order
  hf::FrictionSettings friction;
};
using FrictionalCase = BasicFrictionalCase<2>;
using FrictionalCase3 = BasicFrictionalCase<3>;

// cattaneo: hertz-a's half-disks (R = 1, gap 0.1, E = 15, nu = 0.35 for both: the normal and
// tangential problems decouple), the flat edges brought together by `approach` (top
// (0, -approach/2), bottom (0, approach/2)), then the upper edge moved by `tangential` along x in
// `tangential_steps` equal steps; Coulomb friction with `coefficient`.
struct CattaneoData {
  double approach = 0.13;    // > gap 0.1: a/R about 0.1 at 0.13
  double tangential = 0.01;  // Q / (f P) about 0.6 at f = 0.3
  double coefficient = 0.3;
  int tangential_steps = 1;
};
// level: the hertz-a mesh level (slave arc nodes mesh::hertz_arc_nodes_for_level). Throws
// contactrb::Error for an approach that does not close the gap or exceeds hertz-a's domain (0.45),
// a negative or non-finite coefficient or displacement, tangential_steps < 1, level < 0.
FrictionalCase cattaneo_case(int level, const CattaneoData& data = {});

// A frictional case file (case_toml.hpp, frictional_case_from_toml_file) at mu on `reference`
// (reference_mesh): the problem of make_problem, one load step per [[load_steps]] with its
// Dirichlet values and tractions at mu (a step without tractions: the case's [[traction]]), the
// friction law of [friction]. Throws contactrb::Error
// for mu outside the case's domain.
FrictionalCase frictional_case(const FrictionalCaseFile& file, const mesh::Mesh& reference, const Mu& mu);
// The same for a 3D case file (reference_mesh3): Dirichlet data only, so a step with tractions
// is refused (contactrb::Error).
FrictionalCase3 frictional_case(const FrictionalCaseFile& file, const mesh::Mesh3& reference, const Mu& mu);

// cattaneo-3d: hertz-3d's hemisphere on a block (R = 1, E and nu of hertz-3d for both: the normal
// and tangential problems decouple) as a full model (the quarter mesh of mesh::generate_hertz_3d
// mirrored about x = 0 and y = 0, mesh::mirror: a symmetry plane would hold the tangential
// multipliers of the nodes on it by its rollers alone), the block's bottom clamped, the hemisphere's flat top pressed down by `approach`, then moved by
// `tangential` along x in `tangential_steps` equal steps; Coulomb friction with `coefficient`.
struct Cattaneo3dData {
  double approach = 0.02;     // hertz-3d's reference: a about 0.14
  double tangential = 0.0035;  // Q / (f P) about 0.5 at f = 0.3
  double coefficient = 0.3;
  int tangential_steps = 1;
};
// level: hertz-3d's (mesh::hertz_3d_fine_size_for_level), at most 2. Throws contactrb::Error as
// block_on_block_3d_case.
FrictionalCase3 cattaneo_3d_case(int level, const Cattaneo3dData& data = {});

// block-on-block-3d: a slave box [0.2, 0.8]^2 x [0, 0.4] (6 2^level cells across, 4 2^level high)
// on a master box [0, 1]^2 x [-0.5, 0] (10 2^level across, 5 2^level high): non-matching
// interfaces in contact at rest, E = 10, nu = 0.3 for both, collocation rows. The master's bottom
// is clamped; the slave's top is pressed down by `approach`, then moved by `tangential` (x, y) in
// `tangential_steps` equal steps; Coulomb friction with `coefficient`. Both meshes are symmetric
// about the plane x = y (mesh::box cuts every cube around its main diagonal), so a tangential
// displacement along (1, 1) is a load symmetric about that plane. Groups: "slave", "master",
// "top" (slave top), "bottom" (master bottom), the sides "left1" ... "back1" (slave) and
// "left2" ... "back2" (master).
struct BlockOnBlock3dData {
  double approach = 0.004;                          // a compressive strain of 1 % in the slave
  Eigen::Vector2d tangential{0.0005, 0.0};
  double coefficient = 0.3;
  int tangential_steps = 1;
};
// Throws contactrb::Error for level outside [0, 2], a non-positive or non-finite approach, a
// non-finite tangential displacement, a negative coefficient or tangential_steps < 1.
FrictionalCase3 block_on_block_3d_case(int level, const BlockOnBlock3dData& data = {});

}  // namespace contactrb::cases
