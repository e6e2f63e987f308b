# contactrb_find_native_libraries(<found_var> <missing_var>)
# The libraries that ship no CMake package on Debian, found by hand and wrapped in IMPORTED
# targets: gmsh::gmsh (mesh/), contactrb_deps::umfpack (solve/), when libcholmod is found,
# contactrb_deps::cholmod (fem/ and solve/; the callers require it: the Newton steps need it) and,
# when libHYPRE and MPI are found, contactrb_deps::hypre (solve/, optional).
# Used by the build (CMakeLists.txt) and by the installed contactrbConfig.cmake, so a consumer
# links the private dependencies of the static libraries through the same targets.
# Sets <found_var> to TRUE when the required ones were found, else FALSE with <missing_var> the
# list of what is missing. Targets that already exist are left alone.
function(contactrb_find_native_libraries found_var missing_var)
  set(missing "")

  find_library(GMSH_LIBRARY gmsh)
  find_path(GMSH_INCLUDE_DIR gmsh.h)
  if(GMSH_LIBRARY AND GMSH_INCLUDE_DIR)
    if(NOT TARGET gmsh::gmsh)
      add_library(gmsh::gmsh UNKNOWN IMPORTED)
      set_target_properties(gmsh::gmsh PROPERTIES IMPORTED_LOCATION "${GMSH_LIBRARY}"
                                                 INTERFACE_INCLUDE_DIRECTORIES "${GMSH_INCLUDE_DIR}")
    endif()
  else()
    list(APPEND missing "gmsh (GMSH_LIBRARY, GMSH_INCLUDE_DIR)")
  endif()

  # UMFPACK (SuiteSparse, Debian libsuitesparse-dev): the sparse LU of the semi-smooth Newton
  # systems (solve/sparse_lu.hpp).
  find_library(UMFPACK_LIBRARY umfpack)
  find_path(UMFPACK_INCLUDE_DIR umfpack.h PATH_SUFFIXES suitesparse)
  if(UMFPACK_LIBRARY AND UMFPACK_INCLUDE_DIR)
    if(NOT TARGET contactrb_deps::umfpack)
      add_library(contactrb_deps::umfpack UNKNOWN IMPORTED)
      set_target_properties(contactrb_deps::umfpack PROPERTIES IMPORTED_LOCATION "${UMFPACK_LIBRARY}"
                                                              INTERFACE_INCLUDE_DIRECTORIES "${UMFPACK_INCLUDE_DIR}")
    endif()
  else()
    list(APPEND missing "UMFPACK (UMFPACK_LIBRARY, UMFPACK_INCLUDE_DIR)")
  endif()

  # CHOLMOD is optional; the caller decides whether its absence is an error
  # (contactrbConfig.cmake: when the installed fem/ was built with it).
  find_library(CHOLMOD_LIBRARY cholmod)
  find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
  if(CHOLMOD_LIBRARY AND CHOLMOD_INCLUDE_DIR AND NOT TARGET contactrb_deps::cholmod)
    add_library(contactrb_deps::cholmod UNKNOWN IMPORTED)
    set_target_properties(contactrb_deps::cholmod PROPERTIES IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
                                                            INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}")
  endif()

  # hypre (Debian libhypre-dev, built with MPI) is optional, like CHOLMOD: BoomerAMG, the
  # preconditioner of the AMG Krylov solve of the Newton systems (solve/amg_preconditioner.hpp).
  # Its headers include mpi.h: the MPI C library comes with it (without the C++ bindings).
  find_library(HYPRE_LIBRARY HYPRE)
  find_path(HYPRE_INCLUDE_DIR HYPRE.h PATH_SUFFIXES hypre)
  if(HYPRE_LIBRARY AND HYPRE_INCLUDE_DIR AND NOT TARGET contactrb_deps::hypre)
    find_package(MPI COMPONENTS C QUIET)
    if(MPI_C_FOUND)
      add_library(contactrb_deps::hypre UNKNOWN IMPORTED)
      set_target_properties(contactrb_deps::hypre PROPERTIES IMPORTED_LOCATION "${HYPRE_LIBRARY}"
                                                            INTERFACE_INCLUDE_DIRECTORIES "${HYPRE_INCLUDE_DIR}"
                                                            INTERFACE_LINK_LIBRARIES MPI::MPI_C
                                                            INTERFACE_COMPILE_DEFINITIONS "OMPI_SKIP_MPICXX=1;MPICH_SKIP_MPICXX=1")
    endif()
  endif()

  if(missing)
    set(${found_var} FALSE PARENT_SCOPE)
  else()
    set(${found_var} TRUE PARENT_SCOPE)
  endif()
  set(${missing_var} "${missing}" PARENT_SCOPE)
endfunction()
