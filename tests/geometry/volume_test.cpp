// SPDX-License-Identifier: MIT
// Fluid volume N dx^3 of a sphere, a torus and a capsule, as built-in shapes and as STL files
// read back through gmsh (the torus also with 12 triangles removed): within 1 % of the exact
// volume at 20 particles across the smallest feature, for 4 lattice offsets; and the observed
// convergence order of the RMS error over offsets (validation).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include "mesh_builders.hpp"
#include "sadr/geometry/mesh_io.hpp"
#include "sadr/geometry/particles.hpp"

namespace sadr::geometry {
namespace {

constexpr double kPi = std::numbers::pi;
const Vec3 kOffsets[4] = {{0, 0, 0}, {0.31, 0.57, 0.13}, {0.71, 0.23, 0.89}, {0.47, 0.91, 0.37}};

struct Case {
  const char* name;
  ShapePtr shape;
  double exact, feature;
};

/// Relative volume errors at `across` particles over the feature, one per offset.
std::vector<double> volume_errors(const Case& c, double across) {
  std::vector<double> e;
  for (const Vec3& off : kOffsets) {
    FluidDomain d;
    d.box = c.shape->bounds().inflated(0.1 * c.feature);
    d.body = c.shape;
    FillOptions o;
    o.spacing = c.feature / across;
    o.offset = off;
    const ParticleSet p = fill(d, o);
    e.push_back(static_cast<double>(p.count(Kind::kFluid)) * std::pow(o.spacing, 3) / c.exact - 1);
  }
  return e;
}

ShapePtr from_stl(SurfaceMesh m, const std::string& name, std::size_t drop = 0) {
  if (drop > 0) {
    const auto at = m.triangles.begin() + static_cast<long>(m.triangles.size() / 3);
    m.triangles.erase(at, at + static_cast<long>(drop));
  }
  const std::string path = testing::temp_dir("volume") + "/" + name + ".stl";
  testing::write_stl_binary(path, m);
  return make_mesh_shape(read_mesh(path, 3).boundary);
}

std::vector<Case> cases() {
  const double r_t = 0.25, big_r = 1.0, r_c = 0.5, half = 0.5;
  const double v_sphere = 4.0 / 3.0 * kPi, v_torus = 2 * kPi * kPi * big_r * r_t * r_t,
               v_caps = kPi * r_c * r_c * 2 * half + 4.0 / 3.0 * kPi * std::pow(r_c, 3);
  return {
      {"sphere", make_sphere({}, 1), v_sphere, 2},
      {"torus", make_torus({}, big_r, r_t), v_torus, 2 * r_t},
      {"capsule", make_capsule({0, 0, -half}, {0, 0, half}, r_c), v_caps, 2 * r_c},
      {"sphere.stl", from_stl(testing::sphere_mesh({}, 1, 128), "sphere"), v_sphere, 2},
      {"torus.stl", from_stl(testing::torus_mesh({}, big_r, r_t, 256, 64), "torus"), v_torus,
       2 * r_t},
      {"torus-with-holes.stl",
       from_stl(testing::torus_mesh({}, big_r, r_t, 256, 64), "torus_holes", 12), v_torus, 2 * r_t},
      {"capsule.stl", from_stl(testing::capsule_mesh({}, half, r_c, 128), "capsule"), v_caps,
       2 * r_c},
  };
}

#ifndef SADR_GEOMETRY_VALIDATION
TEST(Volume, WithinOnePercentAtTwentyAcross) {
  for (const Case& c : cases()) {
    const auto e = volume_errors(c, 20);
    double worst = 0;
    for (double x : e) worst = std::max(worst, std::abs(x));
    std::printf("[volume] %-22s 20 across: max |error| over 4 offsets %.4f %%\n", c.name,
                100 * worst);
    EXPECT_LT(worst, 0.01) << c.name;
  }
}

#else
TEST(VolumeValidation, ObservedConvergenceOrder) {
  const double res[] = {8, 12, 20, 32, 48};
  for (const Case& c : cases()) {
    std::vector<double> lx, ly;
    std::printf("[volume] %-22s", c.name);
    for (double a : res) {
      double ms = 0;
      for (double x : volume_errors(c, a)) ms += x * x / 4;
      std::printf(" %g:%.2e", a, std::sqrt(ms));
      lx.push_back(std::log(a));
      ly.push_back(0.5 * std::log(ms));
    }
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < lx.size(); ++i) mx += lx[i] / 5, my += ly[i] / 5;
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < lx.size(); ++i) {
      sxy += (lx[i] - mx) * (ly[i] - my);
      sxx += (lx[i] - mx) * (lx[i] - mx);
    }
    const double order = -sxy / sxx;
    std::printf("  observed order %.2f\n", order);
    // Lattice counting of a smooth body: RMS error over offsets ~ dx^2 (surface noise); a mesh
    // levels off at its own chord error, so only the built-in shapes must show order >= 1.5.
    if (std::string(c.name).find(".stl") == std::string::npos) {
      EXPECT_GT(order, 1.5) << c.name;
    }
  }
}

#endif

}  // namespace
}  // namespace sadr::geometry
