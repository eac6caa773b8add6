# SPDX-License-Identifier: MIT
# The "static" backend's sources in sadr::fluid_backends (included by ../CMakeLists.txt; its schema
# entry static_schema.cpp goes into sadr::fluid_schema by convention, ../backends.cmake).
target_sources(sadr_fluid_backends PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/static_backend.cpp)
