// SPDX-License-Identifier: MIT
// Wavefront OBJ files through assimp's C API (Debian libassimp5), loaded with dlopen at the first
// OBJ read, like gmsh (gmsh_dl.cpp): a program that reads no OBJ file does not load it. The
// headers give the types only; nothing here links libassimp. Polygons are triangulated by
// assimp; each named object or group (`o` / `g`) is also a surface by its name.
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <mutex>
#include <string>

#include "dl_library.hpp"
#include "mesh_io_parts.hpp"
#include "sadr/common/status.hpp"

namespace sadr::geometry {
namespace {

DlLibrary& assimp() {
  static DlLibrary lib({"libassimp.so.5", "libassimp.so"},
                       "the assimp library (libassimp.so.5; Debian: libassimp5)",
                       "reading an .obj file");
  return lib;
}

#define SADR_ASSIMP(fn) assimp().symbol<decltype(fn)>(#fn)

std::mutex& assimp_mutex() {
  static std::mutex m;
  return m;
}

/// Appends the triangles of `mesh` to `out` (its vertices appended too); a face that is not a
/// triangle after triangulation (a point or a line) is skipped and counted.
void append(const aiMesh& mesh, SurfaceMesh& out, std::size_t& skipped) {
  const int base = static_cast<int>(out.vertices.size());
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
    const aiVector3D& p = mesh.mVertices[v];
    out.vertices.push_back({p.x, p.y, p.z});
  }
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) {
      ++skipped;
      continue;
    }
    out.triangles.push_back({base + static_cast<int>(face.mIndices[0]),
                             base + static_cast<int>(face.mIndices[1]),
                             base + static_cast<int>(face.mIndices[2])});
  }
}

}  // namespace

MeshFile read_obj(const std::string& path, int dimension) {
  if (dimension != 3) {
    throw InvalidArgument(path +
                          ": an .obj file holds a 3D surface; a 2D scene takes a gmsh .msh file");
  }
  std::lock_guard lock(assimp_mutex());
  // assimp reads OBJ vertices as single precision (ai_real is float in Debian's build).
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices;
  const aiScene* scene = SADR_ASSIMP(aiImportFile)(path.c_str(), flags);
  if (!scene) {
    throw InvalidArgument(path + ": assimp cannot read it: " + SADR_ASSIMP(aiGetErrorString)());
  }
  struct Release {
    const aiScene* s;
    ~Release() { SADR_ASSIMP(aiReleaseImport)(s); }
  } release{scene};
  MeshFile out;
  out.path = path;
  out.dimension = 3;
  out.boundary.dimension = 3;
  out.boundary.source = path;
  std::size_t skipped = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    append(mesh, out.boundary, skipped);
    const std::string name(mesh.mName.data, mesh.mName.length);
    if (name.empty() || name == "defaultobject") continue;
    SurfaceMesh& group = out.surfaces[name];
    out.group_dimensions[name] = 2;
    group.dimension = 3;
    group.source = path + " (group " + name + ")";
    std::size_t ignored = 0;
    append(mesh, group, ignored);
  }
  if (out.boundary.triangles.empty()) {
    throw InvalidArgument(
        path + ": empty mesh: no face of 3 or more vertices" +
        (skipped > 0 ? " (" + std::to_string(skipped) + " points or lines)" : std::string()) +
        "; allowed: a surface of triangles or polygons");
  }
  validate(out.boundary);
  for (auto& [name, group] : out.surfaces) {
    if (group.triangles.empty()) continue;
    validate(group);
  }
  return out;
}

}  // namespace sadr::geometry
