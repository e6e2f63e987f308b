# Finds the Python interpreter and headers and pybind11 for the Python module (python/,
# docs/python.md); without them the module is skipped with a message (CONTACTRB_PYTHON_FOUND OFF).
# The interpreter: Python3_EXECUTABLE when given; otherwise the first python3 (on PATH, then
# /usr/bin/python3) that imports numpy, so that a python3 without numpy earlier on PATH (pyenv) is
# passed over for Debian's.
set(CONTACTRB_PYTHON_FOUND OFF)
if(CONTACTRB_SANITIZE)
  # An ASan-instrumented extension cannot be loaded by an uninstrumented python3 (the ASan runtime
  # must come first in the process).
  message(STATUS "contactrb: Python module skipped in the sanitizer build")
  return()
endif()
if(NOT Python3_EXECUTABLE)
  find_program(_contactrb_path_python3 NAMES python3 NO_CACHE)
  foreach(candidate IN ITEMS "${_contactrb_path_python3}" /usr/bin/python3)
    if(candidate AND EXISTS "${candidate}")
      execute_process(COMMAND "${candidate}" -c "import numpy" RESULT_VARIABLE _rc OUTPUT_QUIET ERROR_QUIET)
      if(_rc EQUAL 0)
        set(Python3_EXECUTABLE "${candidate}" CACHE FILEPATH "Python interpreter of the contactrb module")
        break()
      endif()
    endif()
  endforeach()
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module)
if(Python3_FOUND)
  find_package(pybind11 CONFIG QUIET)
endif()
if(NOT Python3_FOUND OR NOT pybind11_FOUND)
  message(STATUS "contactrb: Python module skipped (needs python3-dev, pybind11-dev: scripts/install-deps.sh)")
  return()
endif()
set(CONTACTRB_PYTHON_FOUND ON)
# Under the prefix: lib/python3.X/dist-packages for a Debian interpreter (its site directory is
# named dist-packages, and /usr/local/lib/python3.X/dist-packages is on its path), else
# lib/python3.X/site-packages.
if(Python3_SITEARCH MATCHES "dist-packages")
  set(_site dist-packages)
else()
  set(_site site-packages)
endif()
set(CONTACTRB_PYTHON_INSTALL_DIR "lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/${_site}"
    CACHE STRING "Install directory of the Python package contactrb, relative to the prefix")
message(STATUS "contactrb: Python module for ${Python3_EXECUTABLE} (${Python3_VERSION}), installed to "
               "<prefix>/${CONTACTRB_PYTHON_INSTALL_DIR}")
add_subdirectory(python)
