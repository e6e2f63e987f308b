#include "contactrb/solve/amg_preconditioner.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"

#ifdef CONTACTRB_HAVE_HYPRE
#include <mpi.h>
#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_parcsr_ls.h>
#include <_hypre_parcsr_ls.h>
#include <_hypre_parcsr_mv.h>

#include <mutex>
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif
#endif

namespace contactrb::solve {

const char* to_string(AmgStatus status) {
  switch (status) {
    case AmgStatus::Success: return "success";
    case AmgStatus::Unavailable: return "unavailable (this build has no hypre: libhypre-dev)";
    case AmgStatus::SetupFailed: return "setup failed";
    case AmgStatus::InvalidInput: return "invalid input";
  }
  return "unknown";
}

AmgStatus amg_status_from_string(const std::string& name) {
  return enum_from_string(name, "AMG status",
                          std::array{AmgStatus::Success, AmgStatus::Unavailable, AmgStatus::SetupFailed,
                                     AmgStatus::InvalidInput});
}

const char* to_string(AmgSmoother smoother) {
  switch (smoother) {
    case AmgSmoother::ForwardBackward: return "forward-backward";
    case AmgSmoother::Symmetric: return "symmetric";
  }
  return "unknown";
}

AmgSmoother amg_smoother_from_string(const std::string& name) {
  return enum_from_string(name, "AMG smoother", std::array{AmgSmoother::ForwardBackward, AmgSmoother::Symmetric});
}

bool amg_available() {
#ifdef CONTACTRB_HAVE_HYPRE
  return true;
#else
  return false;
#endif
}

namespace {

bool valid_input(const Eigen::SparseMatrix<double>& A, const std::vector<int>& component, int components) {
  if (A.rows() != A.cols() || A.rows() == 0) return false;
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k) {
    if (!std::isfinite(A.valuePtr()[k])) return false;
  }
  if (component.empty()) return true;
  if (static_cast<Eigen::Index>(component.size()) != A.rows() || components < 1) return false;
  for (int c : component) {
    if (c < 0 || c >= components) return false;
  }
  return true;
}

}  // namespace

#ifdef CONTACTRB_HAVE_HYPRE

namespace {

// hypre is built with MPI on Debian: it needs MPI initialised, also in a sequential run. A
// process that did not initialise MPI itself (contactrb solve, the tests) gets a singleton MPI
// here, finalized at exit; under mpirun the executable has initialised it already and each rank
// builds its own hierarchy on MPI_COMM_SELF.
void ensure_hypre() {
  static std::once_flag once;
  std::call_once(once, [] {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) {
      int provided = 0;
      {
#if defined(__SANITIZE_ADDRESS__)
        // OpenMPI's singleton start keeps what it allocates (in plugins it unloads) until exit:
        // not this program's leaks, and not attributable by LeakSanitizer.
        __lsan::ScopedDisabler third_party;
#endif
        MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
      }
      std::atexit([] {
#if defined(__SANITIZE_ADDRESS__)
        __lsan::ScopedDisabler third_party;
#endif
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (!finalized) MPI_Finalize();
      });
    }
    HYPRE_Init();
  });
}

HYPRE_ParVector make_vector(HYPRE_IJVector& ij, int n) {
  HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, n - 1, &ij);
  HYPRE_IJVectorSetObjectType(ij, HYPRE_PARCSR);
  HYPRE_IJVectorInitialize(ij);
  HYPRE_IJVectorAssemble(ij);
  void* object = nullptr;
  HYPRE_IJVectorGetObject(ij, &object);
  return static_cast<HYPRE_ParVector>(object);
}

double* vector_data(HYPRE_ParVector v) {
  return hypre_VectorData(hypre_ParVectorLocalVector(reinterpret_cast<hypre_ParVector*>(v)));
}

}  // namespace

struct AmgPreconditioner::Impl {
  AmgStatus status = AmgStatus::SetupFailed;
  int n = 0;
  HYPRE_IJMatrix ij_matrix = nullptr;
  HYPRE_ParCSRMatrix matrix = nullptr;
  HYPRE_IJVector ij_b = nullptr, ij_x = nullptr;
  HYPRE_ParVector b = nullptr, x = nullptr;
  HYPRE_Solver solver = nullptr;
  double setup_seconds = 0.0;
  int levels = 0;

  ~Impl() { release(); }
  void release() {
    if (solver) HYPRE_BoomerAMGDestroy(solver);
    if (ij_matrix) HYPRE_IJMatrixDestroy(ij_matrix);
    if (ij_b) HYPRE_IJVectorDestroy(ij_b);
    if (ij_x) HYPRE_IJVectorDestroy(ij_x);
    solver = nullptr;
    ij_matrix = nullptr;
    ij_b = ij_x = nullptr;
    matrix = nullptr;
    b = x = nullptr;
  }

  // A in hypre's IJ interface, row by row (CSR).
  void set_matrix(const Eigen::SparseMatrix<double>& A) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = A;
    HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, n - 1, 0, n - 1, &ij_matrix);
    HYPRE_IJMatrixSetObjectType(ij_matrix, HYPRE_PARCSR);
    std::vector<HYPRE_Int> sizes(static_cast<std::size_t>(n));
    std::vector<HYPRE_BigInt> row_index(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const auto entries = rows.outerIndexPtr()[i + 1] - rows.outerIndexPtr()[i];
      sizes[static_cast<std::size_t>(i)] = static_cast<HYPRE_Int>(entries);
      row_index[static_cast<std::size_t>(i)] = i;
    }
    HYPRE_IJMatrixSetRowSizes(ij_matrix, sizes.data());
    HYPRE_IJMatrixInitialize(ij_matrix);
    std::vector<HYPRE_BigInt> cols(rows.innerIndexPtr(), rows.innerIndexPtr() + rows.nonZeros());
    HYPRE_IJMatrixSetValues(ij_matrix, n, sizes.data(), row_index.data(), cols.data(), rows.valuePtr());
    HYPRE_IJMatrixAssemble(ij_matrix);
    void* object = nullptr;
    HYPRE_IJMatrixGetObject(ij_matrix, &object);
    matrix = static_cast<HYPRE_ParCSRMatrix>(object);
  }

  void set_options(const std::vector<int>& component, int components, const AmgSettings& s) {
    HYPRE_BoomerAMGCreate(&solver);
    HYPRE_BoomerAMGSetPrintLevel(solver, 0);
    HYPRE_BoomerAMGSetCoarsenType(solver, 10);  // HMIS
    HYPRE_BoomerAMGSetInterpType(solver, 6);    // extended+i
    HYPRE_BoomerAMGSetPMaxElmts(solver, s.max_interpolation_entries);
    HYPRE_BoomerAMGSetStrongThreshold(solver, s.strong_threshold);
    HYPRE_BoomerAMGSetAggNumLevels(solver, s.aggressive_levels);
    HYPRE_BoomerAMGSetRelaxType(solver, 8);  // l1 symmetric Gauss-Seidel; Gaussian elimination on the coarsest level
    if (s.smoother == AmgSmoother::ForwardBackward) {
      HYPRE_BoomerAMGSetCycleRelaxType(solver, 13, 1);  // l1 Gauss-Seidel forward, down the cycle
      HYPRE_BoomerAMGSetCycleRelaxType(solver, 14, 2);  // backward, up the cycle
    }
    HYPRE_BoomerAMGSetNumSweeps(solver, 1);
    HYPRE_BoomerAMGSetMaxIter(solver, 1);  // one V-cycle per application
    HYPRE_BoomerAMGSetTol(solver, 0.0);
    if (!component.empty() && components > 1) {
      HYPRE_BoomerAMGSetNumFunctions(solver, components);
      // hypre takes the array and frees it with the solver (host memory: malloc / free).
      auto* dof_func = static_cast<HYPRE_Int*>(std::malloc(sizeof(HYPRE_Int) * component.size()));
      for (std::size_t i = 0; i < component.size(); ++i) dof_func[i] = component[i];
      HYPRE_BoomerAMGSetDofFunc(solver, dof_func);
    }
  }
};

AmgPreconditioner::AmgPreconditioner() : impl_(std::make_unique<Impl>()) {}

AmgStatus AmgPreconditioner::compute(const Eigen::SparseMatrix<double>& A, const std::vector<int>& component,
                                     int components, const AmgSettings& settings) {
  Impl& m = *impl_;
  m.release();
  if (!valid_input(A, component, components)) return m.status = AmgStatus::InvalidInput;
  ensure_hypre();
  const auto t0 = std::chrono::steady_clock::now();
  m.n = static_cast<int>(A.rows());
  m.set_matrix(A);
  m.b = make_vector(m.ij_b, m.n);
  m.x = make_vector(m.ij_x, m.n);
  m.set_options(component, components, settings);
  HYPRE_ClearAllErrors();
  HYPRE_BoomerAMGSetup(m.solver, m.matrix, m.b, m.x);
  if (HYPRE_GetError() != 0) {
    HYPRE_ClearAllErrors();
    m.release();
    return m.status = AmgStatus::SetupFailed;
  }
  m.levels = hypre_ParAMGDataNumLevels(reinterpret_cast<hypre_ParAMGData*>(m.solver));
  m.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return m.status = AmgStatus::Success;
}

Eigen::VectorXd AmgPreconditioner::apply(const Eigen::VectorXd& r) const {
  const Impl& m = *impl_;
  require(m.status == AmgStatus::Success,
          std::string("AMG: apply() without a hierarchy (status ") + to_string(m.status) + ")");
  require(r.size() == m.n, "AMG: apply() to a vector of " + std::to_string(r.size()) + " entries for a matrix of " +
                               std::to_string(m.n) + " rows");
  Eigen::Map<Eigen::VectorXd>(vector_data(m.b), m.n) = r;
  Eigen::Map<Eigen::VectorXd> x(vector_data(m.x), m.n);
  x.setZero();
  HYPRE_BoomerAMGSolve(m.solver, m.matrix, m.b, m.x);
  HYPRE_ClearAllErrors();  // "did not converge" in one cycle is the intent
  return x;
}

#else  // no hypre

struct AmgPreconditioner::Impl {
  AmgStatus status = AmgStatus::Unavailable;
  double setup_seconds = 0.0;
  int levels = 0;
};

AmgPreconditioner::AmgPreconditioner() : impl_(std::make_unique<Impl>()) {}

AmgStatus AmgPreconditioner::compute(const Eigen::SparseMatrix<double>& A, const std::vector<int>& component,
                                     int components, const AmgSettings&) {
  impl_->status = valid_input(A, component, components) ? AmgStatus::Unavailable : AmgStatus::InvalidInput;
  return impl_->status;
}

Eigen::VectorXd AmgPreconditioner::apply(const Eigen::VectorXd&) const {
  throw Error(std::string("AMG: apply() without a hierarchy (status ") + to_string(impl_->status) + ")");
}

#endif

AmgPreconditioner::~AmgPreconditioner() = default;
AmgPreconditioner::AmgPreconditioner(AmgPreconditioner&&) noexcept = default;
AmgPreconditioner& AmgPreconditioner::operator=(AmgPreconditioner&&) noexcept = default;
AmgStatus AmgPreconditioner::status() const { return impl_->status; }
double AmgPreconditioner::setup_seconds() const { return impl_->setup_seconds; }
int AmgPreconditioner::levels() const { return impl_->levels; }

}  // namespace contactrb::solve
