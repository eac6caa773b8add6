// SPDX-License-Identifier: MIT
// Morris walls made by a scene's geometry (scene_wall_tangents): every wall particle's tangent
// plane. A plane made by geometry gives the beta of the equivalent fluid.wall_planes plane; a
// sphere's tangent planes give distances within h^2 / R of the exact sphere distance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sadr/common/wall_surface.hpp"
#include "sadr/orchestrator/run_health.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_wall_tangents.hpp"

namespace sadr::orchestrator {
namespace {

/// A 2D channel, periodic along x, walls below y = 0 and above y = 1 (the fluid body's faces).
const std::string kChannel =
    "dimension: 2\n"
    "box: {lower: [0.0, -0.15], upper: [1.0, 1.15], periodic: [true, false]}\n"
    "geometry:\n"
    "  spacing: 0.05\n"
    "  bodies:\n"
    "    - {name: channel, role: fluid, shape: {type: box, lower: [-1.0, 0.0], upper: [2.0, "
    "1.0]}}\n"
    "fluid: {backend: sdpd, h_over_dx: 3.0, sound_speed: 1, shear_viscosity: 0.1, "
    "wall_model: morris}\n"
    "time: {coupling_step: 0.1, end: 0.2}\n";

/// A 3D box of fluid around a solid sphere of radius 0.3 (10 spacings).
const std::string kSphere =
    "dimension: 3\n"
    "box: {lower: [-0.6, -0.6, -0.6], upper: [0.6, 0.6, 0.6], periodic: [true, true, true]}\n"
    "geometry:\n"
    "  spacing: 0.03\n"
    "  bodies:\n"
    "    - {name: ball, role: solid, shape: {type: sphere, center: [0, 0, 0], radius: 0.3}}\n"
    "fluid: {backend: sdpd, h_over_dx: 3.0, sound_speed: 1, shear_viscosity: 0.1, "
    "wall_model: morris}\n"
    "time: {coupling_step: 0.1, end: 0.2}\n";

double minimum_image(double d, double len) {
  return d - len * std::round(d / len);
}

TEST(SceneWallTangents, AGeometryPlaneGivesTheBetaOfTheEquivalentWallPlane) {
  const Scene s = parse_scene(kChannel, "channel.yaml");
  const WallTangents t = scene_wall_tangents(s);
  const ParticleState& p = s.particles;
  std::size_t walls = 0;
  for (std::size_t i = 0; i < p.size(); ++i) walls += p.kind(i) == ParticleKind::kWall;
  ASSERT_GT(walls, 0U);
  ASSERT_EQ(t.size(), walls);  // every wall particle carries its plane
  EXPECT_TRUE(t.problems(p.size()).empty());
  const WallSurface bottom{{0, 0, 0}, {0, 1, 0}, 0.0}, top{{0, 1, 0}, {0, -1, 0}, 0.0};
  const double h = s.fluid.smoothing_length, len = s.box.length(0);
  std::size_t pairs = 0;
  double worst = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const std::uint32_t j = t.particles[k];
    const double* xj = &p.positions[3 * j];
    const WallSurface& plane = xj[1] < 0.5 ? bottom : top;
    EXPECT_NEAR(t.depths[k], plane.depth(xj), 1e-12) << "wall particle " << j;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.kind(i) != ParticleKind::kFluid) continue;
      const double* xi = &p.positions[3 * i];
      double r[3] = {minimum_image(xi[0] - xj[0], len), xi[1] - xj[1], 0.0};
      if (std::hypot(r[0], r[1]) >= h) continue;
      const double b_tangent = morris_beta(t.depths[k], t.signed_distance(k, r), h);
      const double b_plane = morris_beta(plane.depth(xj), plane.signed_distance(xi), h);
      worst = std::max(worst, std::abs(b_tangent - b_plane));
      ++pairs;
    }
  }
  EXPECT_GT(pairs, 100U);
  EXPECT_LT(worst, 1e-12) << "over " << pairs << " fluid-wall pairs";
}

TEST(SceneWallTangents, ASpheresTangentPlanesAreWithinHSquaredOverROfTheSphereDistance) {
  // Fluid outside a solid sphere of radius R: the tangent plane at wall particle j's closest
  // surface point lies outside the sphere, so a fluid particle i at distance delta from the
  // sphere is d = rho cos(theta) - R in front of the plane (rho = |x_i|, theta the angle between
  // x_i and n_j): 0 <= delta - d = rho (1 - cos theta) <= (rho sin theta)^2 / rho <= |x_i -
  // x_j|^2 / R < h^2 / R (theta < 90 degrees). Here h^2 / R = 0.27 h; and exact on the
  // particle's own normal line.
  const Scene s = parse_scene(kSphere, "sphere.yaml");
  const WallTangents t = scene_wall_tangents(s);
  const ParticleState& p = s.particles;
  ASSERT_GT(t.size(), 100U);
  const double h = s.fluid.smoothing_length, radius = 0.3;
  double worst = 0, most_negative = 0;
  std::size_t pairs = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const std::uint32_t j = t.particles[k];
    const double* xj = &p.positions[3 * j];
    const double rj = std::sqrt(xj[0] * xj[0] + xj[1] * xj[1] + xj[2] * xj[2]);
    EXPECT_NEAR(t.depths[k], radius - rj, 1e-12) << "wall particle " << j;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(t.normals[3 * k + a], xj[a] / rj, 1e-12);
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.kind(i) != ParticleKind::kFluid) continue;
      const double* xi = &p.positions[3 * i];
      const double r[3] = {xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]};
      const double sep = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
      if (sep >= h) continue;
      const double exact = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]) - radius;
      const double err = exact - t.signed_distance(k, r);
      EXPECT_LE(err, sep * sep / radius + 1e-12);
      most_negative = std::min(most_negative, err);
      worst = std::max(worst, err);
      ++pairs;
    }
  }
  EXPECT_GT(pairs, 10000U);
  EXPECT_GE(most_negative, -1e-12);  // the plane never puts i farther than the sphere does
  EXPECT_LT(worst, h * h / radius);
  std::printf(
      "sphere R = 10 dx, h = 3 dx: %zu pairs, max (exact - tangent) = %.4f dx (bound "
      "h^2/R = %.2f dx)\n",
      pairs, worst / 0.03, h * h / radius / 0.03);
}

TEST(SceneWallTangents, NoneWithoutMorrisOrWithWallPlanes) {
  std::string stationary = kChannel;
  stationary.replace(stationary.find(", wall_model: morris"), 20, "");
  EXPECT_TRUE(scene_wall_tangents(parse_scene(stationary, "s.yaml")).empty());
}

TEST(SceneWallTangents, TheHealthCheckFindsNoFluidInsideTheSphereAtTheStartButAParticlePushedIn) {
  Scene s = parse_scene(kSphere, "sphere.yaml");
  const HealthContext c = health_context(s);
  ASSERT_FALSE(c.tangents.empty());
  EXPECT_EQ(find_wall_penetration(s.particles, c).count, 0U);
  // The fluid particle nearest the sphere moved 0.3 dx inside it.
  std::size_t nearest = 0;
  double best = 1e9;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    if (s.particles.kind(i) != ParticleKind::kFluid) continue;
    const double* x = &s.particles.positions[3 * i];
    const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (r < best) best = r, nearest = i;
  }
  double* x = &s.particles.positions[3 * nearest];
  const double scale = (0.3 - 0.3 * 0.03) / best;
  for (int a = 0; a < 3; ++a) x[a] *= scale;
  const PenetrationResult res = find_wall_penetration(s.particles, c);
  EXPECT_EQ(res.count, 1U);
  EXPECT_NEAR(res.worst.value, 0.3 * 0.03, 0.3 * 0.03 * 0.5);
}

}  // namespace
}  // namespace sadr::orchestrator
