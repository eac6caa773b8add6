// SPDX-License-Identifier: MIT
// Bad mesh input, table-tested: each refused with InvalidArgument naming the file (and the
// element or group) and what was expected.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "mesh_builders.hpp"
#include "sadr/common/status.hpp"
#include "sadr/geometry/mesh_io.hpp"

namespace sadr::geometry {
namespace {

struct BadCase {
  const char* file;     ///< written into the temp dir unless content is null
  const char* content;  ///< null: do not create it
  int dimension;
  const char* group;   ///< surface to look up after reading (null: none)
  const char* expect;  ///< substring of the message
};

const char* const kSquare = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
1 1 "inlet"
$EndPhysicalNames
$Nodes
3
1 0 0 0
2 1 0 0
3 0 1 0
$EndNodes
$Elements
2
1 1 2 1 1 1 3
2 2 2 2 1 1 2 3
$EndElements
)";

TEST(BadInput, MeshFilesAreRefusedWithFileAndReason) {
  const std::string dir = testing::temp_dir("bad");
  const BadCase cases[] = {
      {"missing.stl", nullptr, 3, nullptr, "cannot open"},
      {"folder.stl", nullptr, 3, nullptr, "not a regular file"},
      {"shape.ply", "ply\n", 3, nullptr, "unsupported mesh format '.ply'"},
      {"noext", "solid x\nendsolid x\n", 3, nullptr, "unsupported mesh format"},
      {"empty.stl", "solid x\nendsolid x\n", 3, nullptr, "empty mesh"},
      {"nan.stl",
       "solid x\nfacet normal 0 0 1\nouter loop\nvertex nan 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
       "endloop\nendfacet\nendsolid x\n",
       3, nullptr, "facet 0 (line 4) has a non-finite vertex (nan, 0, 0)"},
      {"inf.stl",
       "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex inf 0 0\nvertex 0 1 0\n"
       "endloop\nendfacet\nendsolid x\n",
       3, nullptr, "facet 0 (line 5) has a non-finite vertex (inf, 0, 0)"},
      {"one_bad.stl",
       "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
       "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 1\nvertex 1 0 1\n"
       "vertex 0 1 -nan\nendloop\nendfacet\nendsolid x\n",
       3, nullptr, "facet 1 (line 13) has a non-finite vertex (0, 1, -nan)"},
      {"group.msh", kSquare, 2, "outlet", "no physical curve named 'outlet'; the file has inlet"},
      {"garbage.msh", "$MeshFormat\nthis is not a mesh\n", 2, nullptr, ""},
      {"dim.stl", "solid x\nendsolid x\n", 4, nullptr, "dimension must be 2 or 3"},
  };
  std::filesystem::create_directories(dir + "/folder.stl");
  for (const BadCase& c : cases) {
    const std::string path = dir + "/" + c.file;
    if (c.content) std::ofstream(path) << c.content;
    try {
      const MeshFile mf = read_mesh(path, c.dimension);
      if (c.group) (void)mf.surface(c.group);
      ADD_FAILURE() << c.file << ": accepted";
    } catch (const InvalidArgument& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(path), std::string::npos) << c.file << ": " << msg;
      EXPECT_NE(msg.find(c.expect), std::string::npos) << c.file << ": " << msg;
    }
  }
}

TEST(BadInput, BinaryStlWithOneNonFiniteVertexIsRefused) {
  SurfaceMesh m = testing::sphere_mesh({}, 1.0, 8);
  const int bad = m.triangles[5][1];
  m.vertices[static_cast<std::size_t>(bad)].y = std::numeric_limits<double>::infinity();
  std::size_t first = 0;  // the first facet that uses the vertex
  while (m.triangles[first][0] != bad && m.triangles[first][1] != bad &&
         m.triangles[first][2] != bad) {
    ++first;
  }
  const std::string path = testing::temp_dir("bad") + "/one_inf.stl";
  testing::write_stl_binary(path, m);
  try {
    (void)read_mesh(path, 3);
    ADD_FAILURE() << "accepted";
  } catch (const InvalidArgument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path + ": facet " + std::to_string(first) + " has a non-finite vertex"),
              std::string::npos)
        << msg;
  }
}

TEST(BadInput, InMemoryMeshesNameTheElement) {
  SurfaceMesh m;
  m.source = "cell.stl";
  EXPECT_THROW(validate(m), InvalidArgument);  // empty
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 5}};
  try {
    validate(m);
    ADD_FAILURE();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("cell.stl: triangle 0 refers to vertex 5"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sadr::geometry
