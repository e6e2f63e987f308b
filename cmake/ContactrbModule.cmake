# contactrb_module(<name> DEPS <public targets...> PRIVATE_DEPS <private targets...>)
# Defines the library contactrb_<name> from src/contactrb/<name>/*.cpp (an INTERFACE
# library when the folder holds headers only). Headers are included as
# "contactrb/<name>/<file>.hpp". The target is installed with its headers and exported as
# contactrb::<name> (export set contactrbTargets, CMakeLists.txt); contactrb::<name> is also
# its alias in the build tree.
function(contactrb_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/src/contactrb/${name}/*.cpp")
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
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/src/contactrb/${name}/"
          DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/contactrb/${name}"
          FILES_MATCHING PATTERN "*.hpp")
  set_property(GLOBAL APPEND PROPERTY CONTACTRB_MODULES ${name})
endfunction()

# contactrb_test(<module> DEPS <targets...>): one GoogleTest executable test_<module>
# from tests/<module>/*.cpp, registered with CTest (labels: the module name).
function(contactrb_test module)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
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
  gtest_discover_tests(test_${module} PROPERTIES LABELS ${module} DISCOVERY_TIMEOUT 60)
endfunction()
