// SPDX-License-Identifier: MIT
// Wavefront .obj files (through assimp): the same surface as from STL, groups by name, quads
// triangulated, and bad files refused naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "mesh_builders.hpp"
#include "sadr/common/status.hpp"
#include "sadr/geometry/mesh.hpp"
#include "sadr/geometry/mesh_io.hpp"

namespace sadr::geometry {
namespace {

/// Writes `m` as an OBJ; the triangles from `split` on go into a second group.
void write_obj(const std::string& path, const SurfaceMesh& m, std::size_t split) {
  std::ofstream f(path);
  f.precision(17);
  for (const Vec3& v : m.vertices) f << "v " << v.x << ' ' << v.y << ' ' << v.z << '\n';
  f << "g upper\n";
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    if (i == split) f << "g lower\n";
    const auto& t = m.triangles[i];
    f << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  }
}

TEST(ObjFile, GivesTheSameSurfaceAsStl) {
  const SurfaceMesh sphere = testing::sphere_mesh({0.1, -0.2, 0.3}, 1.0, 24);
  const std::string dir = testing::temp_dir("obj");
  write_obj(dir + "/sphere.obj", sphere, sphere.triangles.size() / 2);
  testing::write_stl_binary(dir + "/sphere.stl", sphere);
  const MeshFile obj = read_mesh(dir + "/sphere.obj", 3);
  const MeshFile stl = read_mesh(dir + "/sphere.stl", 3);
  ASSERT_EQ(obj.boundary.triangles.size(), sphere.triangles.size());
  // Both groups by name, splitting the triangles between them.
  ASSERT_EQ(obj.surface_names(), (std::vector<std::string>{"lower", "upper"}));
  EXPECT_EQ(obj.surface("upper").triangles.size() + obj.surface("lower").triangles.size(),
            sphere.triangles.size());
  const auto a = make_mesh_shape(obj.boundary);
  const auto b = make_mesh_shape(stl.boundary);
  // Both readers store single-precision vertices: the two agree to float rounding.
  for (const Vec3 p : {Vec3{0.1, -0.2, 0.3}, Vec3{0.9, 0.0, 0.3}, Vec3{2.0, 1.0, -1.0},
                       Vec3{0.1, 0.5, 0.9}, Vec3{-0.7, -0.2, 0.3}}) {
    EXPECT_NEAR(a->signed_distance(p), b->signed_distance(p), 1e-6) << p.x << ' ' << p.y;
  }
  EXPECT_LT(a->signed_distance({0.1, -0.2, 0.3}), -0.9);
  EXPECT_GT(a->signed_distance({2.0, 1.0, -1.0}), 0.0);
}

TEST(ObjFile, QuadsAreTriangulated) {
  const std::string path = testing::temp_dir("obj") + "/cube.obj";
  std::ofstream(path) << "o cube\n"
                         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                         "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  const MeshFile m = read_mesh(path, 3);
  EXPECT_EQ(m.boundary.triangles.size(), 12u);
  EXPECT_EQ(m.surface("cube").triangles.size(), 12u);
  const auto cube = make_mesh_shape(m.boundary);
  EXPECT_NEAR(cube->signed_distance({0.5, 0.5, 0.5}), -0.5, 1e-12);
  EXPECT_NEAR(cube->signed_distance({0.5, 0.5, 1.25}), 0.25, 1e-12);
}

TEST(ObjFile, BadFilesAreRefusedNamingTheFile) {
  const std::string dir = testing::temp_dir("obj");
  struct Case {
    const char* name;
    const char* content;
    int dimension;
    const char* expect;
  };
  for (const Case& c : {
           Case{"two_d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 2, "a 2D scene takes"},
           Case{"points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n", 3, "empty mesh"},
           Case{"garbage.obj", "\x01\x02 this is not a mesh\n", 3, "empty mesh"},
           Case{"bad_index.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n", 3, "bad_index.obj"},
       }) {
    const std::string path = dir + "/" + c.name;
    std::ofstream(path) << c.content;
    try {
      (void)read_mesh(path, c.dimension);
      ADD_FAILURE() << c.name << " was read";
    } catch (const InvalidArgument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(c.name), std::string::npos) << what;
      EXPECT_NE(what.find(c.expect), std::string::npos) << c.name << ": " << what;
    }
  }
}

}  // namespace
}  // namespace sadr::geometry
