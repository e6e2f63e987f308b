# The installed package, used as a user would (docs/cpp-api.md, "Using contactrb from CMake"):
# install the build to a fresh prefix, configure and build tests/install/consumer against it with
# find_package(contactrb), and check that its online energy is the CLI's.
#   cmake -DBUILD_DIR=... -DCONSUMER_SOURCE_DIR=... -DWORK_DIR=... -DCLI=... -DGENERATOR=...
#         -DCXX_COMPILER=... -DC_COMPILER=... [-DCOMPILER_LAUNCHER=...] [-DBUILD_TYPE=...]
#         [-DSANITIZE_FLAGS=...] -DCASE=... -DMU=... -P run_install_test.cmake
foreach(var BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR CLI GENERATOR CXX_COMPILER C_COMPILER CASE MU)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_install_test.cmake: -D${var}=... is required")
  endif()
endforeach()

# Runs the command; stops the test with its output when it fails. OUTPUT_VARIABLE <var>: its stdout.
function(run step)
  cmake_parse_arguments(ARG "" "OUTPUT_VARIABLE" "COMMAND" ${ARGN})
  execute_process(COMMAND ${ARG_COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${step} failed (${rc}):\n  ${ARG_COMMAND}\n${out}\n${err}")
  endif()
  if(ARG_OUTPUT_VARIABLE)
    set(${ARG_OUTPUT_VARIABLE} "${out}" PARENT_SCOPE)
  endif()
endfunction()

set(prefix "${WORK_DIR}/prefix")
set(consumer_build "${WORK_DIR}/consumer-build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

run("install" COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")

set(configure_args -S "${CONSUMER_SOURCE_DIR}" -B "${consumer_build}" -G "${GENERATOR}"
    "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_C_COMPILER=${C_COMPILER}"
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(COMPILER_LAUNCHER)
  list(APPEND configure_args "-DCMAKE_CXX_COMPILER_LAUNCHER=${COMPILER_LAUNCHER}")
endif()
if(BUILD_TYPE)
  list(APPEND configure_args "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}")
endif()
if(SANITIZE_FLAGS)  # the static libraries were built with the sanitizers: so is their user
  list(APPEND configure_args "-DCMAKE_CXX_FLAGS=${SANITIZE_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${SANITIZE_FLAGS}")
endif()
run("consumer configure" COMMAND "${CMAKE_COMMAND}" ${configure_args})
# The package came from the prefix, not from the build tree.
file(STRINGS "${consumer_build}/CMakeCache.txt" found_dir REGEX "^contactrb_DIR:")
string(REGEX REPLACE "^contactrb_DIR:[A-Z]+=" "" found_dir "${found_dir}")
file(REAL_PATH "${found_dir}" found_dir)
file(REAL_PATH "${prefix}" real_prefix)
string(FIND "${found_dir}" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "find_package(contactrb) found '${found_dir}', not the installed package under '${prefix}'")
endif()
# find_package(contactrb COMPONENTS online) looked for none of the offline side's libraries.
file(STRINGS "${consumer_build}/CMakeCache.txt" offline_side REGEX "^(tomlplusplus_DIR|LAPACK_[A-Za-z_]*|GMSH_LIBRARY|UMFPACK_LIBRARY|CHOLMOD_LIBRARY):")
if(offline_side)
  message(FATAL_ERROR "find_package(contactrb COMPONENTS online) looked for the offline side: ${offline_side}")
endif()
run("consumer build" COMMAND "${CMAKE_COMMAND}" --build "${consumer_build}")
# Without COMPONENTS: every module and its dependencies are found.
run("consumer configure, all modules"
    COMMAND "${CMAKE_COMMAND}" ${configure_args} -B "${consumer_build}-all" -DCONSUMER_ALL_MODULES=ON)

# The installed executables: bin/contactrb answers `online` itself and hands `offline` to
# libexec/contactrb/contactrb-full (apps/contactrb/CMakeLists.txt).
set(installed_cli "${prefix}/bin/contactrb")
set(model "${WORK_DIR}/model.h5")
run("installed contactrb offline" COMMAND "${installed_cli}" offline --case "${CASE}" --out "${model}")
run("installed contactrb online" COMMAND "${installed_cli}" online --model "${model}" --mu "${MU}"
    OUTPUT_VARIABLE cli_json)
run("build-tree contactrb online" COMMAND "${CLI}" online --model "${model}" --mu "${MU}" OUTPUT_VARIABLE build_json)
foreach(key energy contact_force u_hat lambda_hat)  # time_s differs
  string(JSON installed_value GET "${cli_json}" ${key})
  string(JSON build_value GET "${build_json}" ${key})
  if(NOT installed_value STREQUAL build_value)
    message(FATAL_ERROR "${key}: the installed contactrb answered ${installed_value}, the build tree's ${build_value}")
  endif()
endforeach()
string(JSON cli_energy GET "${cli_json}" energy)
run("consumer" COMMAND "${consumer_build}/consumer" "${model}" "${MU}" "${cli_energy}" OUTPUT_VARIABLE consumer_out)
message(STATUS "consumer: ${consumer_out}")

# A row-cone model (`offline --dual rows`) answered with the reduced Newton: the installed CLI, the
# build tree's and the consumer agree.
set(rows_model "${WORK_DIR}/rows/model.h5")
file(MAKE_DIRECTORY "${WORK_DIR}/rows")
run("installed contactrb offline --dual rows" COMMAND "${installed_cli}" offline --case "${CASE}" --dual rows --out "${rows_model}")
run("installed contactrb online --iteration newton"
    COMMAND "${installed_cli}" online --model "${rows_model}" --mu "${MU}" --iteration newton OUTPUT_VARIABLE rows_json)
run("build-tree contactrb online --iteration newton"
    COMMAND "${CLI}" online --model "${rows_model}" --mu "${MU}" --iteration newton OUTPUT_VARIABLE rows_build_json)
foreach(key energy contact_force u_hat lambda_hat iterations)
  string(JSON installed_value GET "${rows_json}" ${key})
  string(JSON build_value GET "${rows_build_json}" ${key})
  if(NOT installed_value STREQUAL build_value)
    message(FATAL_ERROR "row cone, ${key}: the installed contactrb answered ${installed_value}, the build tree's ${build_value}")
  endif()
endforeach()
string(JSON rows_energy GET "${rows_json}" energy)
run("consumer, row cone and Newton" COMMAND "${consumer_build}/consumer" "${rows_model}" "${MU}" "${rows_energy}" newton
    OUTPUT_VARIABLE consumer_out)
message(STATUS "consumer (row cone, newton): ${consumer_out}")

# The installed Python module (docs/python.md, "Install"), when it was built (-DPYTHON=... and
# -DPYTHON_DIR=<its directory under the prefix>): imported from the prefix, not from the build
# tree, its online energy is the CLI's, to the last digit.
if(PYTHON AND PYTHON_DIR)
  set(check [=[
import sys
import contactrb
prefix, model, mu, energy = sys.argv[1:5]
if not contactrb.__file__.startswith(prefix):
    sys.exit(f"contactrb imported from {contactrb.__file__}, not from the prefix {prefix}")
iteration = sys.argv[5] if len(sys.argv) > 5 else "automatic"
r = contactrb.Model.load(model).solve(float(mu), iteration=iteration)
if r.energy != float(energy):
    sys.exit(f"installed module: energy {r.energy!r}, the CLI's {energy} ({iteration})")
print(f"python: energy {r.energy!r} = the CLI's ({iteration})")
]=])
  run("installed python module"
      COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${prefix}/${PYTHON_DIR}" "${PYTHON}" -c "${check}"
              "${prefix}/${PYTHON_DIR}" "${model}" "${MU}" "${cli_energy}"
      OUTPUT_VARIABLE python_out)
  message(STATUS "${python_out}")
  run("installed python module, row cone and Newton"
      COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${prefix}/${PYTHON_DIR}" "${PYTHON}" -c "${check}"
              "${prefix}/${PYTHON_DIR}" "${rows_model}" "${MU}" "${rows_energy}" newton
      OUTPUT_VARIABLE python_out)
  message(STATUS "${python_out}")
endif()
