# SPDX-License-Identifier: MIT
# The "prescribed" backend's sources in sadr::fluid_backends (included by ../CMakeLists.txt; its
# schema entry prescribed_schema.cpp goes into sadr::fluid_schema by convention, ../backends.cmake).
target_sources(sadr_fluid_backends PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/prescribed_backend.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prescribed_grid.cpp)
