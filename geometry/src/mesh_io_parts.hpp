// SPDX-License-Identifier: MIT
// (private) The mesh readers behind read_mesh (mesh_io.hpp), one per library.
#pragma once

#include <string>

#include "sadr/geometry/mesh_io.hpp"

namespace sadr::geometry {

/// A Wavefront .obj file through assimp (mesh_io_obj.cpp); same errors as read_mesh.
MeshFile read_obj(const std::string& path, int dimension);

/// Throws InvalidArgument naming the file, the facet (and in ASCII the line) when a vertex of
/// the STL file `path` (binary or ASCII) is not finite; gmsh would drop that facet silently.
void check_stl_vertices(const std::string& path);

}  // namespace sadr::geometry
