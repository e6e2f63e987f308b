# contactrb_module(<name> [FOLDER <folder>] [SOURCES <stems...>] DEPS <public targets...>
#                  PRIVATE_DEPS <private targets...>)
# Defines the library contactrb_<name> from src/contactrb/<folder>/*.cpp (<folder> defaults to
# <name>; an INTERFACE library when there is no source). SOURCES <stems> makes a part of a
# folder its own library (e.g. the light parts of mesh/, solve/, cases/ that the online stage
# links: CMakeLists.txt): only <stem>.cpp of the folder; such parts are declared before the
# folder's own module, which then takes the remaining sources. Headers are included as
# "contactrb/<folder>/<file>.hpp" and installed with the folder's own module. The target is
# installed and exported as contactrb::<name> (export set contactrbTargets, CMakeLists.txt);
# contactrb::<name> is also its alias in the build tree.
function(contactrb_module name)
  cmake_parse_arguments(ARG "" "FOLDER" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  set(folder ${name})
  if(ARG_FOLDER)
    set(folder ${ARG_FOLDER})
  endif()
  set(dir "${PROJECT_SOURCE_DIR}/src/contactrb/${folder}")
  get_property(claimed GLOBAL PROPERTY CONTACTRB_CLAIMED_${folder})
  if(ARG_SOURCES)
    set(sources "")
    foreach(stem IN LISTS ARG_SOURCES)
      if(NOT EXISTS "${dir}/${stem}.cpp")
        message(FATAL_ERROR "contactrb_module(${name}): no ${folder}/${stem}.cpp")
      endif()
      list(APPEND sources "${dir}/${stem}.cpp")
    endforeach()
    set_property(GLOBAL APPEND PROPERTY CONTACTRB_CLAIMED_${folder} ${sources})
  else()
    file(GLOB sources CONFIGURE_DEPENDS "${dir}/*.cpp")
    if(claimed)
      list(REMOVE_ITEM sources ${claimed})
    endif()
  endif()
  set(target contactrb_${name})
  set(include_dirs "$<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src>" "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
  if(sources)
    add_library(${target} STATIC ${sources})
    target_include_directories(${target} PUBLIC ${include_dirs})
    target_link_libraries(${target} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${include_dirs})
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  add_library(contactrb::${name} ALIAS ${target})
  install(TARGETS ${target} EXPORT contactrbTargets
          ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
          LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}")
  if(NOT ARG_SOURCES)
    install(DIRECTORY "${dir}/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/contactrb/${folder}"
            FILES_MATCHING PATTERN "*.hpp")
  endif()
  set_property(GLOBAL APPEND PROPERTY CONTACTRB_MODULES ${name})
endfunction()

# contactrb_check_link_closure(<target> FORBIDDEN <targets...>): a configure-time error when
# <target> links, directly or through any target it links (PUBLIC, PRIVATE or INTERFACE, static
# libraries' $<LINK_ONLY:...> included), one of the FORBIDDEN targets. Enforces that the online
# library stays light (CMakeLists.txt; the runtime check is the ctest online_link_closure).
function(contactrb_check_link_closure target)
  cmake_parse_arguments(ARG "" "" "FORBIDDEN" ${ARGN})
  set(seen "")
  set(queue ${target})
  while(queue)
    list(POP_FRONT queue t)
    if(t IN_LIST seen)
      continue()
    endif()
    list(APPEND seen ${t})
    if(NOT TARGET ${t})
      continue()
    endif()
    get_target_property(aliased ${t} ALIASED_TARGET)
    if(aliased)
      list(APPEND queue ${aliased})
      continue()
    endif()
    set(deps "")
    foreach(prop LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
      get_target_property(v ${t} ${prop})
      if(v)
        list(APPEND deps ${v})
      endif()
    endforeach()
    foreach(d IN LISTS deps)
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" d "${d}")
      if(d MATCHES "^\\$<")
        continue()  # other generator expressions: none of ours
      endif()
      list(APPEND queue ${d})
    endforeach()
  endwhile()
  foreach(f IN LISTS ARG_FORBIDDEN)
    if(f IN_LIST seen)
      message(FATAL_ERROR "contactrb: ${target} must not link ${f} (the online library is Eigen + HDF5 only; "
                          "docs/rb.md, \"Layout\")")
    endif()
  endforeach()
endfunction()

# contactrb_label_slow(<test list> <label>): the tests of a gtest_discover_tests TEST_LIST get the
# labels <label> and `slow`. gtest_discover_tests passes one label only (it splits a list value),
# so both are set by a CTest include file read after the discovered tests (TEST_INCLUDE_FILES
# are read in order).
function(contactrb_label_slow test_list label)
  set(include_file "${CMAKE_CURRENT_BINARY_DIR}/${test_list}_labels.cmake")
  file(WRITE "${include_file}" "foreach(t IN LISTS ${test_list})\n"
                               "  set_tests_properties(\"\${t}\" PROPERTIES LABELS \"${label};slow\")\n"
                               "endforeach()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${include_file}")
endfunction()

# contactrb_test(<module> DEPS <targets...> [SLOW <patterns...>]): one GoogleTest executable
# test_<module> from tests/<module>/*.cpp, registered with CTest (labels: the module name). The
# tests matched by a SLOW pattern (--gtest_filter syntax: Suite.Test, Suite.*) get the label
# `slow` too (tests/CMakeLists.txt).
function(contactrb_test module)
  cmake_parse_arguments(ARG "" "" "DEPS;SLOW" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${module}/*.cpp")
  if(NOT sources)
    return()
  endif()
  add_executable(test_${module} ${sources})
  target_link_libraries(test_${module} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main Threads::Threads)
  target_include_directories(test_${module} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
  target_compile_definitions(test_${module} PRIVATE
    CONTACTRB_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    CONTACTRB_CLI="$<TARGET_FILE:contactrb>")
  if(ARG_SLOW)
    list(JOIN ARG_SLOW ":" slow)
    gtest_discover_tests(test_${module} TEST_FILTER "-${slow}" PROPERTIES LABELS ${module} DISCOVERY_TIMEOUT 60)
    gtest_discover_tests(test_${module} TEST_FILTER "${slow}" TEST_LIST test_${module}_slow
                         PROPERTIES LABELS ${module} DISCOVERY_TIMEOUT 60)
    contactrb_label_slow(test_${module}_slow ${module})
  else()
    gtest_discover_tests(test_${module} PROPERTIES LABELS ${module} DISCOVERY_TIMEOUT 60)
  endif()
endfunction()
