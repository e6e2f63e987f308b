// The factorization of the Newton solver's A_00 alone (solve/selected_inverse.hpp) on hertz-a
// level L, for the orderings given (docs/performance.md, "Why the defaults are what they are", "Fill-reducing ordering"): wall seconds of the
// analysis (ordering + symbolic) and numeric factorization, wall and CPU seconds of compute(), of
// the inverse block on every free slave DOF (the first Newton iteration's block is a subset) and
// of one full solve; nnz(L); a residual. BLAS threads: OPENBLAS_NUM_THREADS.
//   bench_a00_factorization LEVEL REPEAT [auto|cholmod|node-metis ...]
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/solve/selected_inverse.hpp"

using namespace contactrb;
static double cpu() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_utime.tv_sec + r.ru_stime.tv_sec) + 1e-6 * static_cast<double>(r.ru_utime.tv_usec + r.ru_stime.tv_usec);
}
int main(int argc, char** argv) {
  const int level = argc > 1 ? std::stoi(argv[1]) : 5;
  const int repeat = argc > 2 ? std::stoi(argv[2]) : 1;
  std::vector<std::string> ords;
  for (int a = 3; a < argc; ++a) ords.push_back(argv[a]);
  if (ords.empty()) ords.push_back("auto");
  const hf::HFSolver s(cases::make_problem("hertz-a", 0.3, level));
  const Eigen::SparseMatrix<double> A00 = s.dofs().restrict_matrix(s.stiffness());
  // contact DOFs (slave + master, free)
  std::vector<int> g2f(static_cast<std::size_t>(s.dofs().num_dofs()), -1);
  for (int i = 0; i < s.dofs().num_free(); ++i) g2f[static_cast<std::size_t>(s.dofs().free_dofs()[static_cast<std::size_t>(i)])] = i;
  std::vector<int> E;
  for (int node : s.pair().slave)
    for (int c = 0; c < 2; ++c)
      if (g2f[static_cast<std::size_t>(2 * node + c)] >= 0) E.push_back(g2f[static_cast<std::size_t>(2 * node + c)]);
  std::printf("n %ld nnz %ld |E| %zu\n", static_cast<long>(A00.rows()), static_cast<long>(A00.nonZeros()), E.size());
  for (const std::string& ord : ords)
  for (int r = 0; r < repeat; ++r) {
    const solve::FactorOrdering ordering = ord == "cholmod" ? solve::FactorOrdering::Cholmod : ord == "node-metis" ? solve::FactorOrdering::NodeMetis : solve::FactorOrdering::Auto;
    std::printf("%s: ", ord.c_str());
    solve::SelectedInverse inv;
    double c0 = cpu();
    auto t0 = std::chrono::steady_clock::now();
    inv.compute(A00, ordering);
    double c1 = cpu();
    auto t1 = std::chrono::steady_clock::now();
    const Eigen::MatrixXd G = inv.block(E);
    double c2 = cpu();
    auto t2 = std::chrono::steady_clock::now();
    Eigen::VectorXd b = Eigen::VectorXd::Ones(A00.rows());
    const Eigen::VectorXd x = inv.solve(b);
    double c3 = cpu();
    auto t3 = std::chrono::steady_clock::now();
    auto d = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    std::printf("analysis %.3f numeric %.3f (wall %.3f cpu %.3f) block wall %.3f cpu %.3f solve wall %.3f cpu %.3f nnzL %ld G00 %.12e resid %.2e\n",
                inv.analyze_seconds(), inv.factorize_seconds(), d(t0, t1), c1 - c0, d(t1, t2), c2 - c1, d(t2, t3), c3 - c2,
                inv.factor_nonzeros(), G(0, 0), (A00 * x - b).norm() / b.norm());
    std::fflush(stdout);
  }
}
