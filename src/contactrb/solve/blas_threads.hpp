#pragma once
// The thread count of the BLAS (OpenBLAS, the libblas.so.3 alternative of scripts/install-deps.sh)
// for a scope: the semi-smooth Newton solver raises it for its BLAS-3 parts on large problems (the
// supernodal factorization of A_00 and the selected-inverse block, solve/selected_inverse.hpp;
// docs/performance.md, "BLAS threads"). OpenBLAS's count is process-wide: never change it while other
// threads of the process call the BLAS (snapshot generation with --jobs > 1 leaves it alone).
namespace contactrb::solve {

// True when the BLAS loaded is OpenBLAS (openblas_set_num_threads is found at run time).
bool blas_threads_settable();
// The BLAS's current thread count (1 when it cannot be read).
int blas_threads();

// Sets the count to `threads` (> 0) on construction and restores the previous one on
// destruction; does nothing when threads <= 0, when it equals the current count, or when the
// BLAS is not OpenBLAS.
class ScopedBlasThreads {
 public:
  explicit ScopedBlasThreads(int threads);
  ~ScopedBlasThreads();
  ScopedBlasThreads(const ScopedBlasThreads&) = delete;
  ScopedBlasThreads& operator=(const ScopedBlasThreads&) = delete;

 private:
  int previous_ = 0;  // 0: nothing to restore
};

}  // namespace contactrb::solve
