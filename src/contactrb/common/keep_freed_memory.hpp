#pragma once
// Freed memory stays in the process. glibc returns freed blocks above 32 MB (mmap) and a free
// heap top above the trim threshold to the OS, and every later use of such memory page-faults
// again (costly in this VM). Kept in the process, the 1 GB factor of A_00 at 1.2e6 DOFs
// (allocated inside CHOLMOD) reuses the memory freed by the mesh generation and the assembly:
// hertz-a level 7, 0.97M -> 0.65M page faults, numeric factorization 9.8 -> 5.8 s, peak resident
// memory +3 % (docs/performance.md, "Why the defaults are what they are", "Kept freed memory"). Process-wide, so called by programs
// (contactrb-full, bench_hf_scaling), never by the library.
#include <malloc.h>

namespace contactrb {

inline void keep_freed_memory() {
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

}  // namespace contactrb
