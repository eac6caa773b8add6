// SPDX-License-Identifier: MIT
/// \file mesh_io.hpp
/// Mesh files through gmsh's API (Debian libgmsh-dev 4.8): gmsh .msh (v2 and v4, 2D and 3D) and
/// STL (ASCII and binary). Physical groups of a .msh are available by name: a group of dimension
/// d - 1 as a surface (its triangles in 3D, segments in 2D), a group of dimension d as a region
/// (the outward boundary of its tetrahedra in 3D, or of its triangles and quadrangles in 2D, so
/// that a region is a closed surface the winding number can test).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "sadr/geometry/mesh.hpp"

namespace sadr::geometry {

class MeshFile {
 public:
  std::string path;
  int dimension = 3;
  /// The whole mesh's boundary: the boundary of every volume element (3D) or surface element
  /// (2D) when there are any, else every triangle (3D; an STL) or segment (2D).
  SurfaceMesh boundary;

  /// Triangles (3D) / segments (2D) of the physical group `name` of dimension d - 1; throws
  /// InvalidArgument naming the file and listing the groups there are.
  [[nodiscard]] const SurfaceMesh& surface(const std::string& name) const;
  /// Closed boundary of the volume (3D) / surface (2D) elements of the physical group `name`.
  [[nodiscard]] const SurfaceMesh& region(const std::string& name) const;
  [[nodiscard]] std::vector<std::string> surface_names() const;
  [[nodiscard]] std::vector<std::string> region_names() const;

  std::map<std::string, SurfaceMesh> surfaces;  ///< by physical name (unnamed: "#<tag>")
  std::map<std::string, SurfaceMesh> regions;
  /// Every physical group's dimension by name, those of other dimensions (points, lines in 3D)
  /// included; OBJ groups are surfaces (2).
  std::map<std::string, int> group_dimensions;
};

/// Reads `path` (.msh or .stl, by extension, case-insensitive) as a mesh of `dimension` 2 or 3.
/// Throws InvalidArgument naming the file: missing or unreadable, unsupported extension, gmsh's
/// own parse error, unsupported element type (with its element tag), empty mesh, non-finite
/// vertices. Thread-safe (gmsh's global state is behind a mutex).
MeshFile read_mesh(const std::string& path, int dimension);

}  // namespace sadr::geometry
