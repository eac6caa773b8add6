# SPDX-License-Identifier: MIT
# The "sdpd" backend's sources in sadr::fluid_backends (included by ../CMakeLists.txt; its schema
# entry sdpd_schema.cpp goes into sadr::fluid_schema by convention, ../backends.cmake).
target_sources(sadr_fluid_backends PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_adami_walls.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_backend.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_body_forces.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_fused_step.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_gather.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_half_path.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_integrator.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_limits.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_moving_bodies.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_open_boundary.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_pair_block.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_restart.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sdpd_transport_velocity.cpp)
# The SIMD pair terms must be bit-identical in SIMD lanes and scalar remainders (momentum to
# round-off): no FMA contraction in that file; sqrt without errno so the loop vectorises.
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/sdpd_pair_block.cpp
  PROPERTIES COMPILE_OPTIONS "-ffp-contract=off;-fno-math-errno")
