// SPDX-License-Identifier: MIT
// Unit: the transport-velocity terms of the SDPD backend (sdpd_transport_velocity.cpp) on a
// small jittered periodic box, against the formulas of Adami, Hu & Adams 2013 evaluated here
// pair by pair: the shift s_i = (dt/2)(p_b/m_i) sum_j (V_i^2 + V_j^2) F_ij x_ij, the A-tensor
// acceleration, its zero total momentum, and the refusal of bad parameter values.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "fluid_test_scenes.hpp"
#include "sadr/common/status.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sdpd/sdpd_backend.hpp"

namespace sadr::fluid {
namespace {

constexpr int kSide = 6;
constexpr double kH = 2.5, kC0 = 10.0, kPbFactor = 5.0;

struct Scene {
  FluidModel model;
  ParticleState state;
};

Scene jittered(double tvf) {
  Scene s;
  test::LatticeSpec ls;
  ls.n = {kSide, kSide, 1};
  s.state = test::make_lattice(ls, s.model.box);
  for (std::size_t i = 0; i < s.state.size(); ++i) {
    const double k = static_cast<double>(i);
    s.state.positions[3 * i] += 0.2 * std::sin(1.7 * k + 0.3);
    s.state.positions[3 * i + 1] += 0.2 * std::cos(2.3 * k);
    s.state.velocities[3 * i] = 0.3 * std::sin(0.9 * k);
    s.state.velocities[3 * i + 1] = 0.2 * std::cos(1.3 * k + 1.0);
    s.state.densities[i] = 1.0 + 0.02 * std::sin(0.7 * k);
  }
  s.model.smoothing_length = kH;
  s.model.sound_speed = kC0;
  s.model.shear_viscosity = 0.5;
  s.model.backend_parameters = {{"transport_velocity", tvf}, {"shift_pressure", kPbFactor}};
  return s;
}

// x_ij with the minimum image on the kSide x kSide periodic box.
std::array<double, 2> offset(const ParticleState& p, std::size_t i, std::size_t j) {
  std::array<double, 2> d{};
  for (int a = 0; a < 2; ++a) {
    d[a] = p.positions[3 * i + a] - p.positions[3 * j + a];
    d[a] -= kSide * std::round(d[a] / kSide);
  }
  return d;
}

TEST(SdpdTransportVelocity, ShiftAndATensorMatchThePaperPairByPair) {
  Scene s = jittered(1.0);
  SdpdBackend b;
  b.initialize(s.model, s.state, {});
  ASSERT_TRUE(b.transport_velocity());
  const double dt = 0.01;
  SdpdBackend::Rates plain, tvf;
  b.evaluate_current(3, plain);
  b.evaluate_current(3, dt, tvf);
  const Kernel kernel(KernelType::kLucy, 2, kH);
  const ParticleState& p = s.state;
  const std::size_t n = p.size();
  const double pb = kPbFactor * 1.0 * kC0 * kC0;
  std::vector<double> vol(n), shift(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) vol[i] = p.masses[i] / p.densities[i];
  double shift_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const auto d = offset(p, i, j);
      const double f = kernel.f(std::hypot(d[0], d[1]));
      for (int a = 0; a < 2; ++a)
        shift[3 * i + a] +=
            0.5 * dt * pb / p.masses[i] * (vol[i] * vol[i] + vol[j] * vol[j]) * f * d[a];
    }
    shift_max = std::max({shift_max, std::fabs(shift[3 * i]), std::fabs(shift[3 * i + 1])});
  }
  ASSERT_GT(shift_max, 1e-3);  // the jitter gives a real push
  ASSERT_EQ(tvf.shift.size(), 3 * n);
  for (std::size_t k = 0; k < 3 * n; ++k) EXPECT_NEAR(tvf.shift[k], shift[k], 1e-12 * shift_max);
  // A term: (1/m_i) sum_j (V_i^2 + V_j^2) 1/2 (A_i + A_j) . grad_i W_ij, A = rho v s,
  // grad_i W_ij = -F_ij x_ij.
  std::array<double, 2> total{};
  double a_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::array<double, 2> acc{};
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const auto d = offset(p, i, j);
      const double f = kernel.f(std::hypot(d[0], d[1]));
      const double sxi = shift[3 * i] * d[0] + shift[3 * i + 1] * d[1];
      const double sxj = shift[3 * j] * d[0] + shift[3 * j + 1] * d[1];
      for (int a = 0; a < 2; ++a) {
        const double ai = p.densities[i] * p.velocities[3 * i + a] * sxi;
        const double aj = p.densities[j] * p.velocities[3 * j + a] * sxj;
        acc[a] -= (vol[i] * vol[i] + vol[j] * vol[j]) * 0.5 * (ai + aj) * f / p.masses[i];
      }
    }
    for (int a = 0; a < 2; ++a) {
      const double got = tvf.acc[3 * i + a] - plain.acc[3 * i + a];
      EXPECT_NEAR(got, acc[a], 1e-9 * (1.0 + std::fabs(plain.acc[3 * i + a]))) << i << " " << a;
      total[a] += p.masses[i] * got;
      a_max = std::max(a_max, std::fabs(acc[a]));
    }
  }
  ASSERT_GT(a_max, 1e-6);  // the term is there to be checked
  for (int a = 0; a < 2; ++a) EXPECT_NEAR(total[a], 0.0, 1e-9) << "momentum of the A term";
}

TEST(SdpdTransportVelocity, OffGivesNoShiftAndTheSameRates) {
  Scene on = jittered(1.0), off = jittered(0.0);
  SdpdBackend a, b;
  a.initialize(off.model, off.state, {});
  b.initialize(on.model, on.state, {});
  EXPECT_FALSE(a.transport_velocity());
  SdpdBackend::Rates ra, rb;
  a.evaluate_current(1, 0.01, ra);
  b.evaluate_current(1, rb);  // without the transport-velocity pass
  EXPECT_TRUE(ra.shift.empty());
  ASSERT_EQ(ra.acc.size(), rb.acc.size());
  for (std::size_t k = 0; k < ra.acc.size(); ++k)
    EXPECT_NEAR(ra.acc[k], rb.acc[k], 1e-10 * (1.0 + std::fabs(rb.acc[k])));
}

TEST(SdpdTransportVelocity, RefusesValuesOutsideTheSchema) {
  for (const auto& [key, value] : std::vector<std::pair<std::string, double>>{
           {"transport_velocity", 2.0}, {"shift_pressure", -1.0}, {"tvf", 1.0}}) {
    Scene s = jittered(1.0);
    s.model.backend_parameters[key] = value;
    SdpdBackend b;
    EXPECT_THROW(b.initialize(s.model, s.state, {}), InvalidArgument) << key;
  }
}

}  // namespace
}  // namespace sadr::fluid
