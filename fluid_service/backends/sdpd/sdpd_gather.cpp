// SPDX-License-Identifier: MIT
/// \file sdpd_gather.cpp
/// The SDPD pair loop over full neighbour lists, for systems with wall particles, Morris walls,
/// transported species or reactions: each particle gathers the evaluators of sdpd_pair_physics.hpp
/// and pair_terms.hpp (SdpdMomentumTerm, ContinuityTerm, PairNoise, DiffusionTerm) over its own
/// list, in list order, so every sum is independent of the thread count. Bulk fluids take the half
/// path (sdpd_half_path.cpp, each pair once).
#include <algorithm>
#include <cmath>
#include <span>

#include "sadr/fluid/pair_noise_batch.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

struct SdpdBackend::GatherTerms {
  double h, h2;
  bool summation, noise_on, species_on;
  SdpdMomentumTerm momentum;
  ContinuityTerm continuity;
  DiffusionTerm diffusion;
  double noise_amp;  ///< sqrt(2 k_B T c_D eta)
  SdpdPairParams pair_params;
};

template <int D>
struct SdpdBackend::GatherSums {
  std::array<double, D> force{};
  double drho = 0, k_sum = 0, f_sum = 0;
  std::size_t npairs = 0;  ///< noise pairs in the block
};

template <int D>
void SdpdBackend::summation_gather(Y& y) {
  // Summation density (docs/method.md), rho_i = m_i W(0) + sum_j m_j W_ij, replaces the
  // integrated one (fluid particles).
  const auto ni = static_cast<std::int64_t>(mass_.size());
  const double* x = y.x.data();
#pragma omp parallel for schedule(static) if (ni > kMinParallel)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    // wall layers have truncated support: keep their initial density; buffers: prescribed
    if (wall_[i] || open_.buffer(i)) continue;
    double rho = mass_[i] * kernel_.w0();
    PairGeometry<D> g{};
    for (const std::uint32_t j : nlist_.of(i)) {
      if (pair_geometry<D>(x, i, j, g)) rho += mass_[j] * kernel_.w(g.r);
    }
    y.rho[i] = rho;
  }
}

template <int D>
void SdpdBackend::evaluate_gather(Y& y, std::uint64_t noise_step, Rates& out, bool noise_on) {
  const std::size_t n = mass_.size();
  const auto ni = static_cast<std::int64_t>(n);
  const double h = kernel_.support();
  const double h2 = h * h;
  const bool summation = model_.density_mode == DensityMode::kSummation;
  out.acc.assign(3 * n, 0.0);
  if (noise_on) {
    out.acc_noise.assign(3 * n, 0.0);
  } else {
    out.acc_noise.clear();
  }
  out.drho.assign(n, 0.0);
  out.dc.resize(y.c.size());
  for (auto& d : out.dc) d.assign(n, 0.0);
  if (summation) summation_gather<D>(y);
  pd2_.resize(n);
  inv_nd_.resize(n);
  vol_.resize(n);
  if (noise_on) sqrt_inv_nd_.resize(n);
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const double nd_inv = mass_[i] / y.rho[i];  // 1/d_i
    inv_nd_[i] = nd_inv;
    pd2_[i] = eos_.pressure(y.rho[i]) * nd_inv * nd_inv;
    vol_[i] = mass_[i] / y.rho[i];
    if (noise_on) sqrt_inv_nd_[i] = std::sqrt(nd_inv);
  }
  if (adami_) adami_wall_values<D>(y);  // wall pressure and velocity from this fluid state
  // c_D: see make_pair_params
  const double c_d = sdpd::viscosity_factor<D>();
  const GatherTerms t{h,
                      h2,
                      summation,
                      noise_on,
                      !species_.transported().empty(),
                      SdpdMomentumTerm{c_d * model_.shear_viscosity},
                      ContinuityTerm{model_.density_diffusion * h * model_.sound_speed, 0.01 * h2},
                      DiffusionTerm{model_.diffusion_eps * h2},
                      std::sqrt(2.0 * model_.temperature * c_d * model_.shear_viscosity),
                      make_pair_params<D>(noise_on)};
  scratch_.resize(static_cast<std::size_t>(max_threads()));
  double max_k_sum = 0, max_visc = 0;
#pragma omp parallel if (ni > kMinParallel)
  {
    PairScratch& sc = scratch_[static_cast<std::size_t>(thread_index())];
#pragma omp for schedule(static) reduction(max : max_k_sum, max_visc)
    for (std::int64_t ii = 0; ii < ni; ++ii) {
      gather_particle<D>(static_cast<std::size_t>(ii), y, noise_step, t, sc, out, max_k_sum,
                         max_visc);
    }
  }  // omp parallel
  out.max_k_sum = max_k_sum;
  out.max_visc_sum = 2.0 * c_d * max_visc;  // (a + b)/rho_i sum_j V_j F_ij
  if (!bodies_.walls.empty()) body_forces_at<D>(y, out);
}

// Fast path (fluid particle, stationary walls): gather the pairs within h into the SIMD block,
// the SIMD pair terms, then the sums in neighbour order.
template <int D>
void SdpdBackend::gather_block(std::size_t i, const Y& y, const GatherTerms& t, PairScratch& sc,
                               GatherSums<D>& s, Rates& out) {
  SdpdPairBlock& b = sc.block;
  const double* x = y.x.data();
  const double* xi = &x[3 * i];
  const double* vi = &y.v[3 * i];
  const bool noise_on = t.noise_on;
  std::size_t m = 0;
  for (const std::uint32_t j : nlist_.of(i)) {
    double d[D];
    const double r2 = pbox_.offset_first<D>(xi, &x[3 * j], d);
    if (r2 >= t.h2) continue;
    b.j[m] = j;
    for (int a = 0; a < D; ++a) {
      b.x[a][m] = d[a];
      b.v[a][m] = vi[a] - y.v[3 * j + a];
    }
    b.r2[m] = r2;
    b.pd2_j[m] = pd2_[j];
    b.inv_nd_j[m] = inv_nd_[j];
    b.m_j[m] = mass_[j];
    b.vol_j[m] = vol_[j];
    b.rho_j[m] = y.rho[j];
    if (noise_on) b.sqrt_inv_nd_j[m] = sqrt_inv_nd_[j];
    ++m;
  }
  sdpd_pair_block<D>(t.pair_params,
                     {static_cast<std::uint32_t>(i), pd2_[i], inv_nd_[i], y.rho[i],
                      noise_on ? sqrt_inv_nd_[i] : 0.0},
                     m, b);
  for (std::size_t k = 0; k < m; ++k) {
    for (int a = 0; a < D; ++a) s.force[a] += b.force[a][k];
    s.f_sum += b.f[k] * b.inv_nd_j[k];
  }
  if (!t.summation) {
    for (std::size_t k = 0; k < m; ++k) s.drho += b.drho[k];
  }
  if (t.species_on) {
    PairGeometry<D> g{};
    for (std::size_t k = 0; k < m; ++k) {
      for (int a = 0; a < D; ++a) g.x[a] = b.x[a][k];
      g.r2 = b.r2[k];
      g.r = b.r[k];
      g.f = b.f[k];
      g.inv_r2 = 1.0 / g.r2;
      const double kk = t.diffusion.coefficient(g, b.vol_j[k]);
      s.k_sum += kk;
      double xij[3] = {0.0, 0.0, 0.0};
      for (int a = 0; a < D; ++a) xij[a] = g.x[a];
      species_.add_pair(i, b.j[k], kk, xij, y.c, out.dc);
    }
  }
  s.npairs = noise_on ? m : 0;
}

// General path (wall particles, Morris walls, Adami walls): the evaluators pair by pair; the noise
// pairs are collected in the block for pair_noise_numbers.
template <int D>
void SdpdBackend::gather_pairs(std::size_t i, const Y& y, const GatherTerms& t, PairScratch& sc,
                               GatherSums<D>& s, Rates& out) {
  SdpdPairBlock& b = sc.block;
  const double* x = y.x.data();
  const double* vi = &y.v[3 * i];
  const bool wall_i = wall_[i] != 0;
  PairGeometry<D> g{};
  for (const std::uint32_t j : nlist_.of(i)) {
    if (!pair_geometry<D>(x, i, j, g)) continue;
    std::array<double, D> v;
    for (int a = 0; a < D; ++a) v[a] = vi[a] - y.v[3 * j + a];
    // walls are rigid: a wall-wall pair does not compress (moving walls: a lid next to walls at
    // rest; walls at rest have v = 0 there anyway)
    if (wall_i && wall_[j]) v.fill(0.0);
    if (!t.summation)
      s.drho += t.continuity.with_volume(g, v, mass_[j], vol_[j], y.rho[i], y.rho[j]);
    if (wall_i) {  // walls: density only, plus species on WallCondition::kFree walls
      if (t.species_on && species_.active_wall(i)) {
        const double k = t.diffusion.coefficient(g, vol_[j]);
        s.k_sum += k;
        double xij[3] = {0.0, 0.0, 0.0};
        for (int a = 0; a < D; ++a) xij[a] = g.x[a];
        species_.add_pair_wall(i, j, k, xij, y.c, out.dc);
      }
      continue;
    }
    // the wall model's pair term (fluid_pair_momentum); Morris' beta also scales Dirichlet
    // species, beta (C_w - C_i), the held value on the wall surface
    const double beta = fluid_pair_momentum<D>(y, i, j, g, v, t.momentum, t.h, s.force);
    s.f_sum += g.f * inv_nd_[j];
    if (t.noise_on) {
      // force_i = sign sqrt(amp2/2) (z0, z1, z2) + sqrt(amp2/2)/r x_ij z3 (PairNoise::add)
      const double amp =
          sdpd::noise_amplitude(t.noise_amp, kernel_.sqrt_f(g.r), sqrt_inv_nd_[i], sqrt_inv_nd_[j]);
      b.j[s.npairs] = j;
      b.amp[s.npairs] = i < j ? amp : -amp;
      b.amp_r[s.npairs] = amp / g.r;
      for (int a = 0; a < D; ++a) b.x[a][s.npairs] = g.x[a];
      ++s.npairs;
    }
    if (t.species_on) {
      const double k = t.diffusion.coefficient(g, vol_[j]);
      s.k_sum += beta * k;  // the diffusion limit sees the extrapolated pair's weight
      double xij[3] = {0.0, 0.0, 0.0};
      for (int a = 0; a < D; ++a) xij[a] = g.x[a];
      species_.add_pair(i, j, k, xij, y.c, out.dc, beta);
    }
  }
}

template <int D>
void SdpdBackend::gather_particle(std::size_t i, const Y& y, std::uint64_t noise_step,
                                  const GatherTerms& t, PairScratch& sc, Rates& out,
                                  double& max_k_sum, double& max_visc) {
  const bool wall_i = wall_[i] != 0;
  GatherSums<D> s;
  sc.reserve(nlist_.of(i).size());
  if (!wall_i && !morris_.enabled() && !adami_) {
    gather_block<D>(i, y, t, sc, s, out);
  } else {
    gather_pairs<D>(i, y, t, sc, s, out);
  }
  out.drho[i] = s.drho;
  if (open_.enabled() && open_.buffer(i)) {  // inlet/outlet: no forces, no noise, density set
    out.drho[i] = 0.0;                       // after each sub-step (apply_open_boundary)
    if (t.species_on) {
      max_k_sum = std::max(max_k_sum, s.k_sum);
      species_.add_reactions(i, y.c, out.dc);
    }
    return;
  }
  if (wall_i) {
    if (t.species_on && species_.active_wall(i)) {
      max_k_sum = std::max(max_k_sum, s.k_sum);
      species_.add_reactions(i, y.c, out.dc);
    }
    return;
  }
  max_k_sum = std::max(max_k_sum, s.k_sum);
  max_visc = std::max(max_visc, s.f_sum / y.rho[i]);
  const double inv_m = 1.0 / mass_[i];
  double body[3];
  body_acceleration(i, y.c, body);
  for (int a = 0; a < D; ++a) out.acc[3 * i + a] = s.force[a] * inv_m + body[a];
  if (t.noise_on) {
    const SdpdPairBlock& b = sc.block;
    pair_noise_numbers(model_.seed, noise_step, static_cast<std::uint32_t>(i), b.j.data(), s.npairs,
                       model_.noise, sc.z[0].data(), sc.z[1].data(), sc.z[2].data(),
                       sc.z[3].data());
    std::array<double, D> fnoise{};
    const float* z3 = sc.z[3].data();
    for (std::size_t k = 0; k < s.npairs; ++k) {
      const double s3 = b.amp_r[k] * static_cast<double>(z3[k]);
      for (int a = 0; a < D; ++a) {
        fnoise[a] += b.amp[k] * static_cast<double>(sc.z[a][k]) + s3 * b.x[a][k];
      }
    }
    for (int a = 0; a < D; ++a) out.acc_noise[3 * i + a] = fnoise[a] * inv_m;
  }
  if (t.species_on) species_.add_reactions(i, y.c, out.dc);
}

template void SdpdBackend::evaluate_gather<1>(Y&, std::uint64_t, Rates&, bool);
template void SdpdBackend::evaluate_gather<2>(Y&, std::uint64_t, Rates&, bool);
template void SdpdBackend::evaluate_gather<3>(Y&, std::uint64_t, Rates&, bool);

}  // namespace sadr::fluid
