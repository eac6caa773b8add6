# SPDX-License-Identifier: MIT
# The "tdpd" backend's sources in sadr::fluid_backends (included by ../CMakeLists.txt; its schema
# entry tdpd_schema.cpp goes into sadr::fluid_schema by convention, ../backends.cmake).
target_sources(sadr_fluid_backends PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/tdpd_backend.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tdpd_cells.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tdpd_pair_block.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tdpd_parameters.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tdpd_rates.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tdpd_walls.cpp)
# The SIMD pair block: no FMA contraction (its avx512f / avx2 / default clones give the same bits)
# and no errno from sqrt (else the loop does not vectorise).
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/tdpd_pair_block.cpp PROPERTIES
  COMPILE_OPTIONS "-ffp-contract=off;-fno-math-errno")
