// SPDX-License-Identifier: MIT
// Particle generation cost (#29): ~1e6 particles from a ~1e5-triangle STL torus (read through
// gmsh, winding-number inside tests, wall layers), and from a CSG of 20 shapes. Prints JSON.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>

#include "mesh_builders.hpp"
#include "sadr/geometry/mesh_io.hpp"
#include "sadr/geometry/particles.hpp"

using namespace sadr::geometry;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const double target = argc > 1 ? std::atof(argv[1]) : 1e6;
  const double pi = std::numbers::pi;
  // 1. STL torus R = 1, r = 0.35, 500 x 100 quads = 1e5 triangles.
  const std::string path = testing::temp_dir("bench") + "/torus.stl";
  testing::write_stl_binary(path, testing::torus_mesh({}, 1, 0.35, 500, 100));
  const std::clock_t cpu0 = std::clock();
  auto t0 = std::chrono::steady_clock::now();
  const MeshFile mf = read_mesh(path, 3);
  const double t_read = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const auto torus = make_mesh_shape(mf.boundary);
  const double t_bvh = seconds_since(t0);
  const double v_torus = 2 * pi * pi * 1 * 0.35 * 0.35;
  FluidDomain d;
  d.box = torus->bounds().inflated(0.15);
  d.body = torus;
  FillOptions o;
  o.spacing = std::cbrt(v_torus / target);
  o.wall_depth = 2.5 * o.spacing;
  t0 = std::chrono::steady_clock::now();
  const ParticleSet p = fill(d, o);
  const double t_fill = seconds_since(t0);
  const double cpu_stl = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  // 2. CSG: a union of 20 shapes (spheres, capsules, cylinders, tori) minus nothing, in a box.
  std::vector<ShapePtr> parts;
  for (int k = 0; k < 20; ++k) {
    const double a = 2 * pi * k / 20, x = std::cos(a), y = std::sin(a);
    switch (k % 4) {
      case 0:
        parts.push_back(make_sphere({x, y, 0}, 0.3));
        break;
      case 1:
        parts.push_back(make_capsule({x, y, -0.3}, {x, y, 0.3}, 0.2));
        break;
      case 2:
        parts.push_back(make_cylinder({0.8 * x, 0.8 * y, -0.2}, {x, y, 0.2}, 0.2));
        break;
      default:
        parts.push_back(translate(make_torus({}, 0.2, 0.08), {x, y, 0}));
        break;
    }
  }
  FluidDomain c;
  c.box = {{-1.5, -1.5, -1.5}, {1.5, 1.5, 1.5}};
  c.solids.push_back({csg_union(parts), 1});
  FillOptions oc;
  oc.spacing = std::cbrt(27.0 / target);
  oc.wall_depth = 2.5 * oc.spacing;
  const std::clock_t cpu1 = std::clock();
  t0 = std::chrono::steady_clock::now();
  const ParticleSet q = fill(c, oc);
  const double t_csg = seconds_since(t0);
  const double cpu_csg = static_cast<double>(std::clock() - cpu1) / CLOCKS_PER_SEC;
  std::printf(
      "{\"stl\": {\"triangles\": %zu, \"read_s\": %.3f, \"bvh_s\": %.3f, \"fill_s\": %.3f, "
      "\"cpu_s\": %.3f, \"fluid\": %zu, \"wall\": %zu, \"volume_error\": %.2e},\n"
      " \"csg20\": {\"fill_s\": %.3f, \"cpu_s\": %.3f, \"fluid\": %zu, \"wall\": %zu}}\n",
      mf.boundary.triangles.size(), t_read, t_bvh, t_fill, cpu_stl, p.count(Kind::kFluid),
      p.count(Kind::kWall),
      static_cast<double>(p.count(Kind::kFluid)) * std::pow(o.spacing, 3) / v_torus - 1, t_csg,
      cpu_csg, q.count(Kind::kFluid), q.count(Kind::kWall));
  std::printf("geometry_bench: STL %zu tris -> %zu particles in %.2f s; CSG20 -> %zu in %.2f s\n",
              mf.boundary.triangles.size(), p.size(), t_read + t_bvh + t_fill, q.size(), t_csg);
  return 0;
}
