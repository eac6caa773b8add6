# SPDX-License-Identifier: MIT
# Helper functions shared by every sadr CMakeLists.

# sadr_set_warnings(target): -Wall -Wextra (+ -Werror with SADR_WERROR).
function(sadr_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local
    $<$<BOOL:${SADR_WERROR}>:-Werror>)
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
