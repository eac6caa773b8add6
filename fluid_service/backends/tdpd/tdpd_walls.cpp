// SPDX-License-Identifier: MIT
/// \file tdpd_walls.cpp
/// Effective walls of li2015 sec. II B (see tdpd_walls.hpp and docs/tdpd.md).
#include "tdpd_walls.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "sadr/common/rng.hpp"
#include "sadr/common/status.hpp"

namespace sadr::fluid::tdpd {
namespace {

constexpr double kPaperRc = 1.58;  // r_c = r_cc of the li2015 fits [length]

}  // namespace

void EffectiveWalls::setup(const FluidModel& model, double a, double gamma, double r_cc,
                           double rho) {
  planes_.clear();
  const Box& box = model.box;
  if (box.dimension != 3) {
    throw InvalidArgument("tdpd: effective_walls needs a 3D box (the li2015 fits are 3D), got " +
                          std::to_string(box.dimension) + "D");
  }
  dim_ = box.dimension;
  rc_ = model.smoothing_length;
  rcc_ = r_cc;
  kbt_ = model.temperature;
  rho_ = rho;
  // The fits include rho, a, gamma and g(r) of the calibration set. They are evaluated at the
  // same h / r_c and scaled by the prefactors of the integrals they approximate (all are
  // r_c^3 x a function of h / r_c); exact for the calibration set, an extrapolation otherwise.
  scale_fc_ = (a / 18.75) * (rho / 4.0) * std::pow(rc_ / kPaperRc, 3);
  scale_gamma_ = (gamma / 4.5) * (rho / 4.0) * std::pow(rc_ / kPaperRc, 3);
  scale_phi_ = std::pow(rcc_ / kPaperRc, 3);
  volume_ = box.length(0) * box.length(1) * box.length(2);
  for (int k = 0; k < 3; ++k) {
    if (box.periodic[k]) continue;
    const double area = volume_ / box.length(k);
    for (const double sign : {1.0, -1.0}) {
      WallPlane p;
      p.axis = k;
      p.position = sign > 0.0 ? box.lo[k] : box.hi[k];
      p.sign = sign;
      p.area = area;
      int region = -1;
      for (std::size_t r = 0; r < model.wall_regions.size() && region < 0; ++r) {
        if (model.wall_regions[r].inward_normal[k] * sign > 0.5) region = static_cast<int>(r);
      }
      for (const auto& sp : model.species) {
        WallCondition wc = sp.default_wall;
        if (region >= 0 && static_cast<std::size_t>(region) < sp.wall_conditions.size())
          wc = sp.wall_conditions[static_cast<std::size_t>(region)];
        if (wc.type == WallCondition::Type::kFree) wc = {};
        p.species.push_back(wc);
      }
      planes_.push_back(std::move(p));
    }
  }
  if (planes_.empty()) {
    throw InvalidArgument("tdpd: effective_walls = 1 but every axis of the box is periodic");
  }
}

double EffectiveWalls::f_c(double h) const {
  return scale_fc_ * fit_fc(std::max(h, 0.0) / rc_);
}
double EffectiveWalls::gamma_tau(double h) const {
  const double q = std::max(h, 0.05 * rc_) / rc_;  // li2015 cap at 0.05 r_c
  return scale_gamma_ * fit_inv_h(10.3101, 3.6212, 2.2090, 3.45, q, kPaperRc);
}
double EffectiveWalls::gamma_n(double h) const {
  const double q = std::max(h, 0.1 * rc_) / rc_;  // li2015 cap at 0.1 r_c
  return scale_gamma_ * fit_inv_h(20.7789, 2.1245, 5.4566, 2.30, q, kPaperRc);
}
double EffectiveWalls::phi(double h) const {
  const double q = std::max(h, 0.01 * rcc_) / rcc_;  // li2015 cap at 0.01 r_cc
  return scale_phi_ * fit_inv_h(4.9562e-2, 4.1517, 7.1697, 4.09, q, kPaperRc);
}
double EffectiveWalls::phibar(double h) const {
  return (kPaperRc / rcc_) * fit_phibar(std::max(h, 0.0) / rcc_);
}

void EffectiveWalls::add_forces(const std::vector<double>& x, const std::vector<double>& v,
                                const std::vector<std::uint8_t>& frozen, std::uint64_t seed,
                                std::uint64_t noise_key, std::uint32_t sub, double dt,
                                std::vector<double>& force) const {
  const rng::CounterRng rng{seed};
  const double noise = kbt_ > 0.0 ? std::sqrt(2.0 * kbt_ / dt) : 0.0;
  const auto n = static_cast<std::uint32_t>(frozen.size());
  for (std::size_t pi = 0; pi < planes_.size(); ++pi) {
    const WallPlane& p = planes_[pi];
    const auto k = static_cast<std::size_t>(p.axis);
    for (std::uint32_t i = 0; i < n; ++i) {
      if (frozen[i]) continue;
      const double h = p.sign * (x[3 * i + k] - p.position);
      if (h >= rc_) continue;
      const double gt = gamma_tau(h);
      const double gn = gamma_n(h);
      force[3 * i + k] += p.sign * f_c(h);
      std::array<double, 4> xi{0.0, 0.0, 0.0, 0.0};
      if (noise > 0.0) {
        const auto j = static_cast<std::uint32_t>(2 * pi);
        const auto a = rng.normal2(rng::Purpose::kWallNoise, noise_key, i, j, sub);
        const auto b = rng.normal2(rng::Purpose::kWallNoise, noise_key, i, j + 1, sub);
        xi = {a[0], a[1], b[0], b[1]};
      }
      for (std::size_t c = 0; c < 3; ++c) {
        const double g = c == k ? gn : gt;
        force[3 * i + c] += -g * v[3 * i + c] + noise * std::sqrt(g) * xi[c];
      }
    }
  }
}

void EffectiveWalls::add_fluxes(const std::vector<double>& x,
                                const std::vector<std::uint8_t>& frozen,
                                const std::vector<int>& transported,
                                const std::vector<double>& kappa,
                                const std::vector<std::vector<double>>& c,
                                std::vector<std::vector<double>>& flux, bool with_dirichlet) const {
  const std::size_t n = frozen.size();
  std::size_t n_fluid = 0;
  for (std::size_t i = 0; i < n; ++i) n_fluid += frozen[i] ? 0 : 1;
  const double rho_n = static_cast<double>(n_fluid) / volume_;
  const double two_pi_rho = 2.0 * std::numbers::pi * rho_;
  for (const WallPlane& p : planes_) {
    const auto k = static_cast<std::size_t>(p.axis);
    bool any_neumann = false;
    for (const int s : transported) {
      any_neumann |= p.species[static_cast<std::size_t>(s)].type == WallCondition::Type::kNeumann;
    }
    double phibar_sum = 0.0;  // fixed order: identical on any thread count
    if (any_neumann) {
      for (std::size_t i = 0; i < n; ++i) {
        if (!frozen[i]) phibar_sum += phibar(p.sign * (x[3 * i + k] - p.position));
      }
    }
    for (const int s : transported) {
      const auto su = static_cast<std::size_t>(s);
      const WallCondition& wc = p.species[su];
      if (wc.type == WallCondition::Type::kDirichlet) {
        if (!with_dirichlet) continue;  // integrated exactly by relax_dirichlet()
        const double kf = kappa[su] * two_pi_rho;
        for (std::size_t i = 0; i < n; ++i) {
          const double h = p.sign * (x[3 * i + k] - p.position);
          if (frozen[i] || h >= rcc_) continue;
          flux[su][i] += kf * phi(h) * (wc.value - c[su][i]);
        }
      } else if (wc.type == WallCondition::Type::kNeumann && phibar_sum > 0.0) {
        // Total inward amount per time q A (amount = sum_i C_i / rho_n): exact for any
        // near-wall density profile.
        const double scale = wc.value * rho_n * p.area / phibar_sum;
        for (std::size_t i = 0; i < n; ++i) {
          const double h = p.sign * (x[3 * i + k] - p.position);
          if (frozen[i] || h >= rcc_) continue;
          flux[su][i] += scale * phibar(h);
        }
      }
    }
  }
}

void EffectiveWalls::relax_dirichlet(const std::vector<double>& x,
                                     const std::vector<std::uint8_t>& frozen,
                                     const std::vector<int>& transported,
                                     const std::vector<double>& kappa, double tau,
                                     std::vector<std::vector<double>>& c) const {
  const double two_pi_rho = 2.0 * std::numbers::pi * rho_;
  const std::size_t n = frozen.size();
  for (const WallPlane& p : planes_) {
    const auto k = static_cast<std::size_t>(p.axis);
    for (const int s : transported) {
      const auto su = static_cast<std::size_t>(s);
      const WallCondition& wc = p.species[su];
      if (wc.type != WallCondition::Type::kDirichlet) continue;
      const double kf = kappa[su] * two_pi_rho * tau;
      for (std::size_t i = 0; i < n; ++i) {
        const double h = p.sign * (x[3 * i + k] - p.position);
        if (frozen[i] || h >= rcc_) continue;
        // Exact solution of dC/dt = k (C_w - C) over tau: a convex combination of C and C_w.
        c[su][i] = wc.value + (c[su][i] - wc.value) * std::exp(-kf * phi(h));
      }
    }
  }
}

std::size_t EffectiveWalls::reflect(std::vector<double>& x, std::vector<double>& v,
                                    std::vector<double>& v_pred,
                                    const std::vector<std::uint8_t>& frozen) const {
  std::size_t count = 0;
  const std::size_t n = frozen.size();
  for (const WallPlane& p : planes_) {
    const auto k = static_cast<std::size_t>(p.axis);
    for (std::size_t i = 0; i < n; ++i) {
      if (frozen[i]) continue;
      const double h = p.sign * (x[3 * i + k] - p.position);
      if (h >= 0.0) continue;
      x[3 * i + k] = 2.0 * p.position - x[3 * i + k];
      for (std::size_t c = 0; c < 3; ++c) {
        v[3 * i + c] = -v[3 * i + c];
        v_pred[3 * i + c] = -v_pred[3 * i + c];
      }
      ++count;
    }
  }
  return count;
}

}  // namespace sadr::fluid::tdpd
