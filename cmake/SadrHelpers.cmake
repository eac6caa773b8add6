# SPDX-License-Identifier: MIT
# Helper functions shared by every sadr CMakeLists.

# sadr_set_warnings(target): -Wall -Wextra (+ -Werror with SADR_WERROR).
function(sadr_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local
    $<$<BOOL:${SADR_WERROR}>:-Werror>)
endfunction()

# sadr_unity_build(target BATCH n): with SADR_UNITY_BUILD, compile the target's sources as unity
# sources of n files each, so that the headers they share (CLI11, nlohmann/json, protobuf, yaml-cpp)
# are parsed once per batch. Only for code off the time-stepping path (CLI, scenes, wire, outputs);
# the numerical kernels (fluid_core, fluid_backends, ssa_core) stay one object per file.
# A source with SKIP_UNITY_BUILD_INCLUSION stays on its own.
function(sadr_unity_build target)
  cmake_parse_arguments(U "" "BATCH" "" ${ARGN})
  if(SADR_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${U_BATCH})
  endif()
endfunction()

# sadr_add_gtest(NAME name SOURCES a.cpp ... LIBS lib ... LABELS unit ... [TIMEOUT s])
# One GoogleTest executable; every TEST in it becomes a ctest test with LABELS.
# Tests run with the source tree's tests/data and tests/data/refs reachable via
# the environment variables SADR_TEST_DATA and SADR_REFS.
function(sadr_add_gtest)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  target_include_directories(${T_NAME} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
  target_compile_definitions(${T_NAME} PRIVATE
    SADR_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SADR_BINARY_DIR="${PROJECT_BINARY_DIR}")
  sadr_set_warnings(${T_NAME})
  gtest_discover_tests(${T_NAME}
    DISCOVERY_TIMEOUT 60
    PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT}
      ENVIRONMENT "SADR_REFS=${SADR_REFS_DIR}")
endfunction()
