// The factorization of the Newton solver's A_00 alone (solve/selected_inverse.hpp) on a built-in
// case (2D or 3D, default hertz-a) at level L, for the orderings given (docs/performance.md, "Why
// the defaults are what they are", "Fill-reducing ordering"; "HF scaling in 3D"): wall seconds of
// the analysis (ordering + symbolic) and numeric factorization, wall and CPU seconds of compute(),
// of the inverse block on every free slave DOF (the first Newton iteration's block is a subset)
// and of one full solve; nnz(L); a residual. BLAS threads: OPENBLAS_NUM_THREADS.
// --analysis-only: the ordering and symbolic analysis alone, with CHOLMOD's count of nnz(L) and
// of the factorization's flops (where the numeric factorization would not fit).
//   bench_a00_factorization LEVEL REPEAT [auto|cholmod|node-metis ...] [--case NAME] [--analysis-only]
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/solve/selected_inverse.hpp"

using namespace contactrb;

namespace {

double cpu() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_utime.tv_sec + r.ru_stime.tv_sec) + 1e-6 * static_cast<double>(r.ru_utime.tv_usec + r.ru_stime.tv_usec);
}

double peak_rss_mb() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_maxrss) / 1024.0;
}

solve::FactorOrdering ordering_of(const std::string& name) {
  return name == "cholmod" ? solve::FactorOrdering::Cholmod
         : name == "node-metis" ? solve::FactorOrdering::NodeMetis
                                : solve::FactorOrdering::Auto;
}

mesh::Mesh reference_of(const cases::CaseSpec& spec, int level, std::integral_constant<int, 2>) {
  return cases::reference_mesh(spec, level);
}
mesh::Mesh3 reference_of(const cases::CaseSpec& spec, int level, std::integral_constant<int, 3>) {
  return cases::reference_mesh3(spec, level);
}

struct Run {
  std::string case_name = "hertz-a";
  int level = 5, repeat = 1;
  std::vector<std::string> orderings;
  bool analysis_only = false;
};

template <int Dim>
int run(const Run& run, const cases::CaseSpec& spec) {
  const cases::Mu mu = cases::Mu::Constant(1, spec.parameters.at(0).reference);
  const auto reference = reference_of(spec, run.level, std::integral_constant<int, Dim>{});
  const hf::BasicHFSolver<Dim> s(cases::make_problem(spec, reference, mu));
  const Eigen::SparseMatrix<double> A00 = s.dofs().restrict_matrix(s.stiffness());
  // contact DOFs (slave, free)
  std::vector<int> g2f(static_cast<std::size_t>(s.dofs().num_dofs()), -1);
  for (int i = 0; i < s.dofs().num_free(); ++i) g2f[static_cast<std::size_t>(s.dofs().free_dofs()[static_cast<std::size_t>(i)])] = i;
  std::vector<int> E;
  for (int node : s.pair().slave)
    for (int c = 0; c < Dim; ++c)
      if (g2f[static_cast<std::size_t>(Dim * node + c)] >= 0) E.push_back(g2f[static_cast<std::size_t>(Dim * node + c)]);
  std::printf("%s level %d: n %ld nnz %ld |E| %zu, peak RSS before the factorization %.0f MB\n", run.case_name.c_str(),
              run.level, static_cast<long>(A00.rows()), static_cast<long>(A00.nonZeros()), E.size(), peak_rss_mb());
  for (const std::string& ord : run.orderings) {
    for (int r = 0; r < run.repeat; ++r) {
      std::printf("%s: ", ord.c_str());
      if (run.analysis_only) {
        const double c0 = cpu();
        const solve::FactorAnalysis a = solve::FactorAnalysis::analyze(A00, ordering_of(ord));
        std::printf("analysis %.3f s (cpu %.3f) valid %d nnzL %.4e (%.2f GB as doubles) flops %.4e peak RSS %.0f MB\n",
                    a.seconds(), cpu() - c0, a.valid() ? 1 : 0, a.factor_nonzeros(), 8e-9 * a.factor_nonzeros(),
                    a.factor_flops(), peak_rss_mb());
        std::fflush(stdout);
        continue;
      }
      solve::SelectedInverse inv;
      const double c0 = cpu();
      const auto t0 = std::chrono::steady_clock::now();
      inv.compute(A00, ordering_of(ord));
      const double c1 = cpu();
      const auto t1 = std::chrono::steady_clock::now();
      const Eigen::MatrixXd G = inv.block(E);
      const double c2 = cpu();
      const auto t2 = std::chrono::steady_clock::now();
      const Eigen::VectorXd b = Eigen::VectorXd::Ones(A00.rows());
      const Eigen::VectorXd x = inv.solve(b);
      const double c3 = cpu();
      const auto t3 = std::chrono::steady_clock::now();
      auto d = [](auto from, auto to) { return std::chrono::duration<double>(to - from).count(); };
      std::printf("analysis %.3f numeric %.3f (wall %.3f cpu %.3f) block wall %.3f cpu %.3f solve wall %.3f cpu %.3f nnzL %ld G00 %.12e resid %.2e peak RSS %.0f MB\n",
                  inv.analyze_seconds(), inv.factorize_seconds(), d(t0, t1), c1 - c0, d(t1, t2), c2 - c1, d(t2, t3), c3 - c2,
                  inv.factor_nonzeros(), G(0, 0), (A00 * x - b).norm() / b.norm(), peak_rss_mb());
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Run r;
  std::vector<std::string> positional;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--case" && a + 1 < argc) r.case_name = argv[++a];
    else if (arg == "--analysis-only") r.analysis_only = true;
    else positional.push_back(arg);
  }
  try {
    if (!positional.empty()) r.level = std::stoi(positional[0]);
    if (positional.size() > 1) r.repeat = std::stoi(positional[1]);
    r.orderings.assign(positional.size() > 2 ? positional.begin() + 2 : positional.end(), positional.end());
    if (r.orderings.empty()) r.orderings.push_back("auto");
    const cases::CaseSpec spec = cases::builtin_case_spec(r.case_name);
    return cases::case_dimension(spec) == 3 ? run<3>(r, spec) : run<2>(r, spec);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_a00_factorization: %s\n", e.what());
    return 1;
  }
}
