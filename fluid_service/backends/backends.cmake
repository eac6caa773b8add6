# SPDX-License-Identifier: MIT
# The fluid backends that ship with sadr: the one list. A new backend is its folder
# fluid_service/backends/NAME/ (NAME_backend.{hpp,cpp}, NAME_schema.cpp, backend.cmake) plus its
# name here. Both fluid_service/schema/CMakeLists.txt and fluid_service/backends/CMakeLists.txt
# include this file and generate their tables from the list, by convention:
# - sadr::fluid_schema compiles backends/NAME/NAME_schema.cpp and lists
#   `schema::Backend NAME_backend()` (schema/src/backend_list.cpp.in -> backends()),
# - sadr::fluid_backends includes backends/NAME/backend.cmake (its sources) and calls
#   `void register_NAME_backend(BackendRegistry&)`, defined in the backend's folder
#   (registry.cpp.in -> register_builtin_backends()).
# The list is sorted here, so `sadr backends`, the registry and docs/scene-format.md's tables are
# in alphabetical order whatever the order written.
set(SADR_FLUID_BACKENDS prescribed sdpd static tdpd)

list(SORT SADR_FLUID_BACKENDS)
set(SADR_FLUID_BACKENDS_DIR ${CMAKE_CURRENT_LIST_DIR})
foreach(b IN LISTS SADR_FLUID_BACKENDS)
  if(NOT b MATCHES "^[a-z][a-z0-9_]*$")
    message(FATAL_ERROR "fluid backend '${b}': names are lower-case C++ identifiers")
  endif()
  foreach(f backend.cmake ${b}_schema.cpp)
    if(NOT EXISTS ${SADR_FLUID_BACKENDS_DIR}/${b}/${f})
      message(FATAL_ERROR "fluid backend '${b}' (backends.cmake) has no ${b}/${f}")
    endif()
  endforeach()
endforeach()

# sadr_fluid_backend_table(var format): `format` once per backend (in the list's order), @b@
# replaced by its name, one line each; for the generated tables.
function(sadr_fluid_backend_table var format)
  set(s "")
  foreach(b IN LISTS SADR_FLUID_BACKENDS)
    string(REPLACE "@b@" "${b}" line "${format}")
    string(APPEND s "${line}\n")
  endforeach()
  set(${var} "${s}" PARENT_SCOPE)
endfunction()
