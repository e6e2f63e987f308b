// Frictional contact (docs/solvers.md, "Friction"): Coulomb's cone, the frictionless and tied
// limits, Cattaneo-Mindlin, the load path, full sliding.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "contactrb/hf/friction.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "hf_test_meshes.hpp"

using namespace contactrb;

namespace {
const fem::Material kMat{15.0, 0.35};

hf::ContactProblem hertz(int arc_nodes) {
  mesh::HertzGeometry g;
  g.slave_arc_nodes = arc_nodes;
  hf::ContactProblem p;
  p.mesh = mesh::generate_hertz(g);
  p.materials = {kMat, kMat};
  return p;
}

// The upper flat edge moved by (dx, -delta/2), the lower one by (0, delta/2).
hf::LoadStep hertz_step(double delta, double dx) {
  return hf::LoadStep{{{"top", dx, -0.5 * delta}, {"bottom", 0.0, 0.5 * delta}}, {}};
}

// Normal approach delta, then the tangential displacement dx of the upper edge in `steps` steps.
std::vector<hf::LoadStep> normal_then_tangential(double delta, double dx, int steps) {
  std::vector<hf::LoadStep> path{hertz_step(delta, 0.0)};
  for (int i = 1; i <= steps; ++i) path.push_back(hertz_step(delta, dx * i / steps));
  return path;
}

hf::FrictionSettings coulomb(double f) {
  hf::FrictionSettings s;
  s.law = hf::FrictionLaw::Coulomb;
  s.coefficient = f;
  return s;
}

void print_steps(const hf::FrictionalSolution& s) {
  for (std::size_t i = 0; i < s.steps.size(); ++i) {
    const hf::FrictionStepReport& r = s.steps[i];
    std::printf("[ report ] step %zu: %s, %d iterations, P %.6g, Q %.6g, stick %d slip %d open %d, %.3f s\n", i + 1,
                hf::to_string(r.status), r.iterations, r.normal_force,
                r.tangential_force.size() > 0 ? r.tangential_force(0) : 0.0, r.stick, r.slip, r.open, r.time_s);
  }
}
}  // namespace

TEST(Friction, Explore) {
  const hf::ContactProblem p = hertz(481);
  const hf::FrictionalSolution s = hf::solve_load_path(p, normal_then_tangential(0.13, 0.01, 1), coulomb(0.3));
  print_steps(s);
  for (std::size_t i = 0; i < s.steps.size(); ++i) {
    for (double r : s.steps[i].residuals) std::printf("%.2e ", r);
    std::printf("\n");
  }
  EXPECT_TRUE(s.converged) << s.message;
}
