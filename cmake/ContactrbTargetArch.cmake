# contactrb_target_arch(): with CONTACTRB_MARCH set (e.g. `native`), compile every target of the
# project with -march=<value> when the compiler accepts it; sets CONTACTRB_ARCH_FLAG to that flag
# (empty otherwise). CMakeLists.txt then makes the flag part of contactrb_common's interface, so
# that whatever links contactrb (the Python module, an installed library's users) is compiled the
# same way: Eigen aligns its arrays to the widest vector the flags enable (16 bytes for SSE2, 32
# for AVX, 64 for AVX-512), and two objects compiled differently that exchange Eigen types
# corrupt memory. -ffp-contract=off keeps the compiler from fusing a*b+c in our own scalar code
# (its results stay those of the default build); Eigen's kernels use FMA explicitly. GCC 12
# reports -Warray-bounds in Eigen 3.4's AVX assignment loops on 2- and 3-vectors (a 256-bit
# unaligned load inside a loop that runs zero times for them): silenced in this build only.
include(CheckCXXCompilerFlag)

macro(contactrb_target_arch)
  set(CONTACTRB_ARCH_FLAG "")
  if(CONTACTRB_MARCH)
    check_cxx_compiler_flag("-march=${CONTACTRB_MARCH}" CONTACTRB_MARCH_ACCEPTED)
    if(NOT CONTACTRB_MARCH_ACCEPTED)
      message(FATAL_ERROR "contactrb: the compiler refuses -march=${CONTACTRB_MARCH} (CONTACTRB_MARCH)")
    endif()
    set(CONTACTRB_ARCH_FLAG "-march=${CONTACTRB_MARCH}")
    add_compile_options(${CONTACTRB_ARCH_FLAG} -ffp-contract=off)
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      add_compile_options(-Wno-array-bounds)
    endif()
    message(STATUS "contactrb: compiling with ${CONTACTRB_ARCH_FLAG}: binaries for this kind of CPU only")
  endif()
endmacro()
