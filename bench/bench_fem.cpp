// FEM assembly and sparse Cholesky factorization against the number of DOFs, on the
// structured unit square mesh::rectangle (n x n cells, 2 (n + 1)^2 DOFs), bottom edge clamped;
// the assembly also on the Hertz meshes and on the unit cube (tetrahedra).
// Figures: docs/performance.md, "FEM assembly and factorization".
#include <benchmark/benchmark.h>

#include "contactrb/fem/cholesky.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb;

namespace {

// Cells per side for about 1e3, 1e4, 1e5, 1e6 DOFs.
constexpr int kSides[] = {22, 70, 223, 706};

mesh::Mesh square(int n) { return mesh::rectangle(0.0, 0.0, 1.0, 1.0, n, n); }
const std::vector<fem::Material> kMaterial = {fem::Material{15.0, 0.35}};

void add_sizes(benchmark::internal::Benchmark* b) {
  for (int n : kSides) b->Arg(n);
  b->Unit(benchmark::kMillisecond);
}

void set_counters(benchmark::State& state, const mesh::Mesh& m) {
  state.counters["dofs"] = m.num_dofs();
  state.counters["triangles"] = m.num_triangles();
}

void BM_AssembleStiffness(benchmark::State& state) {
  const mesh::Mesh m = square(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    fem::SparseMatrix K = fem::stiffness(m, kMaterial);
    benchmark::DoNotOptimize(K.valuePtr());
  }
  set_counters(state, m);
}
BENCHMARK(BM_AssembleStiffness)->Apply(add_sizes);

// The stiffness of the Hertz meshes (two bodies, unstructured) at mesh levels 0, 3, 5.
void BM_AssembleHertz(benchmark::State& state) {
  mesh::HertzGeometry geometry;
  geometry.slave_arc_nodes = mesh::hertz_arc_nodes_for_level(static_cast<int>(state.range(0)));
  const mesh::Mesh m = mesh::generate_hertz(geometry);
  const std::vector<fem::Material> materials(2, fem::Material{15.0, 0.35});
  for (auto _ : state) {
    fem::SparseMatrix K = fem::stiffness(m, materials);
    benchmark::DoNotOptimize(K.valuePtr());
  }
  set_counters(state, m);
}
BENCHMARK(BM_AssembleHertz)->Arg(0)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);

// 3D: the stiffness of the unit cube mesh::box, n^3 cells of six tetrahedra each,
// 3 (n + 1)^3 DOFs: n = 31 and 68 for about 1e5 and 1e6 DOFs.
void BM_AssembleStiffness3d(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const mesh::Mesh3 m = mesh::box({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, n, n, n);
  Eigen::Index nnz = 0;
  for (auto _ : state) {
    fem::SparseMatrix K = fem::stiffness(m, kMaterial);
    nnz = K.nonZeros();
    benchmark::DoNotOptimize(K.valuePtr());
  }
  state.counters["dofs"] = m.num_dofs();
  state.counters["tetrahedra"] = m.num_tetrahedra();
  state.counters["nnz_per_dof"] = static_cast<double>(nnz) / m.num_dofs();
}
BENCHMARK(BM_AssembleStiffness3d)->Arg(31)->Arg(68)->Unit(benchmark::kMillisecond);

void BM_AssembleH1(benchmark::State& state) {
  const mesh::Mesh m = square(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    fem::SparseMatrix H = fem::h1_product(m);
    benchmark::DoNotOptimize(H.valuePtr());
  }
  set_counters(state, m);
}
BENCHMARK(BM_AssembleH1)->Apply(add_sizes);

void BM_RestrictDirichlet(benchmark::State& state) {
  const mesh::Mesh m = square(static_cast<int>(state.range(0)));
  const fem::SparseMatrix K = fem::stiffness(m, kMaterial);
  const fem::DofMap dofs(m, {{"bottom", 0.0, 0.0}});
  for (auto _ : state) {
    fem::SparseMatrix A = dofs.restrict_matrix(K);
    benchmark::DoNotOptimize(A.valuePtr());
  }
  set_counters(state, m);
}
BENCHMARK(BM_RestrictDirichlet)->Apply(add_sizes);

void factorize(benchmark::State& state, fem::CholeskyBackend backend) {
  const mesh::Mesh m = square(static_cast<int>(state.range(0)));
  const fem::DofMap dofs(m, {{"bottom", 0.0, 0.0}});
  const fem::SparseMatrix A = dofs.restrict_matrix(fem::stiffness(m, kMaterial));
  for (auto _ : state) {
    fem::SparseCholesky chol(backend);
    if (chol.compute(A) != fem::FactorStatus::Success) state.SkipWithError("factorization failed");
    benchmark::DoNotOptimize(&chol);
  }
  set_counters(state, m);
}
void BM_FactorizeCholmod(benchmark::State& state) { factorize(state, fem::CholeskyBackend::Cholmod); }
void BM_FactorizeEigen(benchmark::State& state) { factorize(state, fem::CholeskyBackend::EigenSimplicial); }
BENCHMARK(BM_FactorizeCholmod)->Apply(add_sizes);
BENCHMARK(BM_FactorizeEigen)->Apply(add_sizes);

void back_solve(benchmark::State& state, fem::CholeskyBackend backend) {
  const mesh::Mesh m = square(static_cast<int>(state.range(0)));
  const fem::DofMap dofs(m, {{"bottom", 0.0, 0.0}});
  const fem::SparseMatrix A = dofs.restrict_matrix(fem::stiffness(m, kMaterial));
  fem::SparseCholesky chol(backend);
  if (chol.compute(A) != fem::FactorStatus::Success) state.SkipWithError("factorization failed");
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  for (auto _ : state) {
    Eigen::VectorXd x = chol.solve(b);
    benchmark::DoNotOptimize(x.data());
  }
  set_counters(state, m);
}
void BM_SolveCholmod(benchmark::State& state) { back_solve(state, fem::CholeskyBackend::Cholmod); }
void BM_SolveEigen(benchmark::State& state) { back_solve(state, fem::CholeskyBackend::EigenSimplicial); }
BENCHMARK(BM_SolveCholmod)->Apply(add_sizes);
BENCHMARK(BM_SolveEigen)->Apply(add_sizes);

// The whole HF linear setup with the default backend: assemble, eliminate, factorize.
void BM_AssembleAndFactorize(benchmark::State& state) {
  const mesh::Mesh m = square(static_cast<int>(state.range(0)));
  const fem::DofMap dofs(m, {{"bottom", 0.0, 0.0}});
  for (auto _ : state) {
    fem::SparseCholesky chol;
    if (chol.compute(dofs.restrict_matrix(fem::stiffness(m, kMaterial))) != fem::FactorStatus::Success) {
      state.SkipWithError("factorization failed");
    }
    benchmark::DoNotOptimize(&chol);
  }
  set_counters(state, m);
}
BENCHMARK(BM_AssembleAndFactorize)->Apply(add_sizes);

}  // namespace

BENCHMARK_MAIN();
