// Projection of the slave nodes on the deformed master polyline against the contact surface size.
//
// Hertz-like configuration: the master is the upper unit half circle (outer arc of a half
// annulus, n nodes); the n slave nodes are placed by the displacement on the lower half of
// the unit circle centred at (0, 2.1) (gap 0.1 at the centre, about 1.2 at the sides), so
// the search sees near and far nodes. Counters: slave nodes per second.
//
// 3D (BM_Project3*, argument: slave squares across, n x n): the master is the cap of the unit
// sphere over [-0.7, 0.7]^2 (a box of (n - 1)^2 x 1 cubes mapped radially: non-matching), the
// (n + 1)^2 slave nodes of the top face of an n^2 x 1 box are placed by the displacement on the
// lower cap of the unit sphere centred at (0, 0, 2.1), again near and far nodes.
//
// BM_Lac3Rows (same 3D setup, slave nodes near the master: the lower cap touches the master
// cap at the centre, so every slave triangle has master triangles below it): the rows of the
// exactly integrated 3D LAC, constraint_rows from the projection (not timed) to K and g.
//
//   bench_contact --benchmark_filter=Project
//   bench_contact --benchmark_filter=Lac3
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/mesh/structured.hpp"

namespace {

using namespace contactrb;

struct Setup {
  mesh::Mesh mesh;
  contact::ContactPair pair;
  Eigen::VectorXd w;
};

Setup hertz_like(int n) {
  mesh::Mesh slave = mesh::rectangle(-1.0, 2.0, 1.0, 2.5, n - 1, 1, mesh::kSlaveBody);
  mesh::Mesh master = mesh::rectangle(0.0, 0.0, 1.0, 1.0, n - 1, 1, mesh::kMasterBody);
  for (auto& p : master.nodes) {  // half annulus r in [0.5, 1], theta = pi (1 - x)
    const double r = 0.5 + 0.5 * p.y(), t = std::numbers::pi * (1.0 - p.x());
    p = Eigen::Vector2d(r * std::cos(t), r * std::sin(t));
  }
  for (const char* g : {"right", "top", "left"}) mesh::rename_boundary(slave, g, std::string("s_") + g);
  for (const char* g : {"right", "bottom", "left"}) mesh::rename_boundary(master, g, std::string("m_") + g);
  mesh::rename_boundary(slave, "bottom", mesh::kSlaveBoundary);
  mesh::rename_boundary(master, "top", mesh::kMasterBoundary);
  Setup s;
  s.mesh = mesh::merge(slave, master);
  s.pair = contact::make_contact_pair(s.mesh);
  s.w = Eigen::VectorXd::Zero(s.mesh.num_dofs());
  for (std::size_t i = 0; i < s.pair.slave.size(); ++i) {
    const int v = s.pair.slave[i];
    const double t = std::numbers::pi * (1.0 + static_cast<double>(i) / static_cast<double>(n - 1));
    const Eigen::Vector2d target(std::cos(t), 2.1 + std::sin(t));
    s.w.segment<2>(2 * v) = target - s.mesh.nodes[static_cast<std::size_t>(v)];
  }
  return s;
}

void run(benchmark::State& state, contact::SearchMethod method) {
  const int n = static_cast<int>(state.range(0));
  const Setup s = hertz_like(n);
  contact::ProjectionOptions options;
  options.search = method;
  for (auto _ : state) {
    contact::PointwiseContact pc = contact::project_slave_nodes(s.mesh, s.pair, s.w, options);
    benchmark::DoNotOptimize(pc.g.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.SetComplexityN(n);
}

struct Setup3 {
  mesh::Mesh3 mesh;
  contact::ContactPair3 pair;
  Eigen::VectorXd w;
};

// (x, y) in [-0.7, 0.7]^2 -> centre + z_sign * unit(x, y, z_sign): a cap of the unit sphere.
Eigen::Vector3d on_sphere(double x, double y, const Eigen::Vector3d& centre, double z_sign) {
  return centre + Eigen::Vector3d(x, y, z_sign).normalized();
}

Setup3 sphere_caps(int n, double centre_height = 2.1) {
  const Eigen::Vector3d lo(-0.7, -0.7, 0.0), hi(0.7, 0.7, 1.0);
  mesh::Mesh3 slave = mesh::box(lo, hi, n, n, 1, mesh::kSlaveBody);
  mesh::Mesh3 master = mesh::box(lo, hi, n - 1, n - 1, 1, mesh::kMasterBody);
  for (auto& p : master.nodes) p = (0.5 + 0.5 * p.z()) * on_sphere(p.x(), p.y(), Eigen::Vector3d::Zero(), 1.0);
  for (const char* g : {"front", "back", "left", "right", "top"}) mesh::rename_boundary(slave, g, std::string("s_") + g);
  for (const char* g : {"front", "back", "left", "right", "bottom"}) mesh::rename_boundary(master, g, std::string("m_") + g);
  mesh::rename_boundary(slave, "bottom", mesh::kSlaveBoundary);
  mesh::rename_boundary(master, "top", mesh::kMasterBoundary);
  Setup3 s;
  s.mesh = mesh::merge(slave, master);
  s.pair = contact::make_contact_pair(s.mesh);
  s.w = Eigen::VectorXd::Zero(s.mesh.num_dofs());
  for (const int v : s.pair.slave) {
    const Eigen::Vector3d& X = s.mesh.nodes[static_cast<std::size_t>(v)];
    s.w.segment<3>(3 * v) = on_sphere(X.x(), X.y(), Eigen::Vector3d(0.0, 0.0, centre_height), -1.0) - X;
  }
  return s;
}

void run3(benchmark::State& state, contact::SearchMethod method) {
  const Setup3 s = sphere_caps(static_cast<int>(state.range(0)));
  contact::ProjectionOptions options;
  options.search = method;
  for (auto _ : state) {
    contact::PointwiseContact3 pc = contact::project_slave_nodes(s.mesh, s.pair, s.w, options);
    benchmark::DoNotOptimize(pc.g.data());
  }
  const auto S = static_cast<std::int64_t>(s.pair.slave.size());
  state.SetItemsProcessed(state.iterations() * S);
  state.SetComplexityN(S);
  state.counters["slave_nodes"] = static_cast<double>(S);
  state.counters["master_triangles"] = static_cast<double>(s.pair.master_faces.size());
}

// The two caps touch at the centre (gap 0) and open to about 0.7 at the corners.
void BM_Lac3Rows(benchmark::State& state) {
  const Setup3 s = sphere_caps(static_cast<int>(state.range(0)), 2.0);
  const contact::ContactQuadrature q = contact::make_quadrature(s.mesh, s.pair, contact::Discretization::LAC);
  const contact::PointwiseContact3 pc = contact::project_slave_nodes(s.mesh, s.pair, s.w);
  for (auto _ : state) {
    contact::ConstraintRows rows = contact::constraint_rows(s.mesh, s.pair, q, pc, s.w);
    benchmark::DoNotOptimize(rows.g.data());
  }
  const auto S = static_cast<std::int64_t>(s.pair.slave.size());
  state.SetItemsProcessed(state.iterations() * S);
  state.SetComplexityN(S);
  state.counters["slave_nodes"] = static_cast<double>(S);
  state.counters["master_triangles"] = static_cast<double>(s.pair.master_faces.size());
}

void BM_Project3Tree(benchmark::State& state) { run3(state, contact::SearchMethod::Tree); }
void BM_Project3AllPairs(benchmark::State& state) { run3(state, contact::SearchMethod::AllPairs); }

void BM_ProjectAutomatic(benchmark::State& state) { run(state, contact::SearchMethod::Automatic); }
void BM_ProjectTree(benchmark::State& state) { run(state, contact::SearchMethod::Tree); }
void BM_ProjectAllPairs(benchmark::State& state) { run(state, contact::SearchMethod::AllPairs); }

}  // namespace

BENCHMARK(BM_ProjectAutomatic)->RangeMultiplier(10)->Range(100, 100000)->Unit(benchmark::kMicrosecond)->Complexity();
BENCHMARK(BM_ProjectTree)->RangeMultiplier(10)->Range(100, 100000)->Unit(benchmark::kMicrosecond)->Complexity(benchmark::oNLogN);
BENCHMARK(BM_ProjectAllPairs)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMicrosecond)->Complexity(benchmark::oNSquared);

// 1e3, 1e4 and 1e5 slave nodes ((n + 1)^2 for n = 31, 99, 315).
BENCHMARK(BM_Project3Tree)->Arg(31)->Arg(99)->Arg(315)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNLogN);
BENCHMARK(BM_Lac3Rows)->Arg(31)->Arg(99)->Arg(315)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNLogN);
BENCHMARK(BM_Project3AllPairs)->Arg(31)->Arg(99)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNSquared);

BENCHMARK_MAIN();
