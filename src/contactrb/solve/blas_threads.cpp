#include "contactrb/solve/blas_threads.hpp"

// OpenBLAS's extensions, weak: null when the BLAS loaded is another one (reference BLAS, BLIS).
extern "C" {
void openblas_set_num_threads(int num_threads) __attribute__((weak));
int openblas_get_num_threads() __attribute__((weak));
}

namespace contactrb::solve {

bool blas_threads_settable() { return openblas_set_num_threads != nullptr && openblas_get_num_threads != nullptr; }

int blas_threads() { return blas_threads_settable() ? openblas_get_num_threads() : 1; }

ScopedBlasThreads::ScopedBlasThreads(int threads) {
  if (threads <= 0 || !blas_threads_settable()) return;
  const int current = openblas_get_num_threads();
  if (current == threads) return;
  previous_ = current;
  openblas_set_num_threads(threads);
}

ScopedBlasThreads::~ScopedBlasThreads() {
  if (previous_ > 0) openblas_set_num_threads(previous_);
}

}  // namespace contactrb::solve
