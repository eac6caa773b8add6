// SPDX-License-Identifier: MIT
// (private) The mesh readers behind read_mesh (mesh_io.hpp), one per library.
#pragma once

#include <string>

#include "sadr/geometry/mesh_io.hpp"

namespace sadr::geometry {

/// A Wavefront .obj file through assimp (mesh_io_obj.cpp); same errors as read_mesh.
MeshFile read_obj(const std::string& path, int dimension);

}  // namespace sadr::geometry
