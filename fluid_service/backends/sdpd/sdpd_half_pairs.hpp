// SPDX-License-Identifier: MIT
/// \file sdpd_half_pairs.hpp
/// SdpdBackend::evaluate_half (included by sdpd_rates.cpp only): the pair loop for systems
/// without wall particles, Morris walls, transported species or reactions, evaluating every
/// pair ONCE (the full-list gather evaluates it from both sides) and writing +F to i and -F
/// to j, including the thermal-noise numbers (generated once per pair instead of twice).
///
/// Determinism without atomics: particles are binned into slabs of width >= list cutoff / R
/// (R = kSlabReach = 2) along the last active axis at each list build (rebuild_neighbors), so
/// a listed pair spans at most R + 1 consecutive slabs. The list is filtered to "forward" pairs:
/// j in the same slab with j > i, or j 1..R slabs ahead (mod the slab count on a periodic axis,
/// a multiple of R + 1 above 2R). Phase p runs the slabs s = p mod (R + 1) in parallel; slab s
/// writes only to slabs s..s+R, so no two threads write the same particle, and each particle
/// receives its contributions in an order fixed by (phase, slab, member index): independent
/// of the thread count. There is no barrier between the phases: a slab waits (release/acquire
/// flags) only for the slabs of earlier phases within R of it, the ones whose writes it must
/// follow (slab_phases_team). The slab assignment depends on the positions at the last list build,
/// which are saved with the state (blob version 2), so restarts stay bit-exact. The pair values are
/// those of the compact block (sdpd_pair_block.hpp); the j side uses the exact negatives (forces,
/// noise) and its own continuity / viscous-limit terms, so momentum is conserved to round-off.
///
/// Memory layout (measured: 2D 1e5 +35-45% per core, 3D +5-15%, bit-identical): what a pair
/// reads of j (HalfIn) and adds to j (HalfAcc) are one 64-byte line each, filled / reduced by
/// evaluate_dim; in 2D a few particles of a slab share one block (per-lane i quantities) so the
/// noise vectors are full. Neither changes an operation or the order of the sums.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>

#include "sadr/common/status.hpp"

#include "sadr/fluid/pair_noise_batch.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

// Defined here (one translation unit: sdpd_rates.cpp) next to the loops that use the slabs.
void SdpdBackend::rebuild_neighbors(const std::vector<double>& x) {
  builder_->build(x, nlist_);
  ++list_builds_;
  list_ref_x_ = x;
  if (!half_ok_) return;
  // Slabs along the last active axis of width >= cutoff/kSlabReach, so a listed pair spans at
  // most kSlabReach + 1 consecutive slabs; on a periodic axis a multiple of kSlabReach + 1 slabs
  // (the colours) and more than 2 kSlabReach (else one slab: serial, still exact).
  // kSlabReach = 2 rather than 1: 3D, 1e4 particles gives 12 slabs (4 per colour) instead of 6
  // (3 per colour, which caps 2 threads at 1.5x).
  const int axis = model_.box.dimension - 1;
  const double len = pbox_.length(axis);
  // (1 + 1e-9): a listed pair stays within kSlabReach slabs despite rounding in the binning
  auto ns = static_cast<std::uint32_t>(
      std::floor(kSlabReach * len / (builder_->cutoff() * (1.0 + 1e-9))));
  slab_wrap_ = pbox_.periodic(axis);
  if (slab_wrap_) {
    ns -= ns % (kSlabReach + 1);
    if (ns <= 2 * kSlabReach) ns = 1;
  }
  slab_count_ = std::max<std::uint32_t>(ns, 1);
  const double lo = model_.box.lo[axis], inv_w = slab_count_ / len;
  const std::size_t n = x.size() / 3;
  slab_of_.resize(n);
  slab_start_.assign(slab_count_ + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = std::floor((x[3 * i + axis] - lo) * inv_w);
    const auto s = static_cast<std::uint32_t>(std::clamp(t, 0.0, slab_count_ - 1.0));
    slab_of_[i] = s;
    ++slab_start_[s + 1];
  }
  for (std::uint32_t s = 0; s < slab_count_; ++s) slab_start_[s + 1] += slab_start_[s];
  slab_members_.resize(n);
  std::vector<std::uint32_t> fill(slab_start_.begin(), slab_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    slab_members_[fill[slab_of_[i]]++] = static_cast<std::uint32_t>(i);
  // Keep only the "forward" pairs (sdpd_half_pairs.hpp), in place: every pair is listed once,
  // which halves the list memory (and the pair loops need no slab test per entry).
  std::uint32_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t s = slab_of_[i];
    const std::uint32_t begin = nlist_.offsets[i], end = nlist_.offsets[i + 1];
    nlist_.offsets[i] = out;
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t j = nlist_.indices[k];
      // slab distance forward (mod the count on a periodic axis; "negative" is huge unsigned)
      std::uint32_t ds = slab_of_[j] - s;
      if (slab_wrap_ && slab_of_[j] < s) ds += slab_count_;
      if (ds == 0 ? j > i : ds <= kSlabReach) nlist_.indices[out++] = j;
    }
  }
  // The full list is symmetric, so exactly half of it must remain (no pair lost or doubled).
  if (2 * static_cast<std::size_t>(out) != nlist_.indices.size()) {
    throw NumericalFailure("sdpd: slab filter kept " + std::to_string(out) + " of " +
                               std::to_string(nlist_.indices.size()) + " list entries (internal)",
                           {{"quantity", "neighbour list"}});
  }
  nlist_.offsets[n] = out;
  nlist_.indices.resize(out);
  nlist_.indices.shrink_to_fit();
  if (slab_done_count_ != slab_count_) {
    slab_done_ = std::make_unique<std::atomic<std::uint32_t>[]>(slab_count_);
    for (std::uint32_t s = 0; s < slab_count_; ++s) slab_done_[s].store(0);
    slab_done_count_ = slab_count_;
  }
  // Work per slab (its members plus their forward entries), prefix-summed per colour: the
  // slabs hold one or two lattice rows/layers (width ~0.58 cutoff), so equal slab counts per
  // thread are not equal work.
  constexpr std::uint32_t colours = kSlabReach + 1;
  for (std::uint32_t c = 0; c < colours; ++c) {
    auto& w = colour_work_[c];
    w.assign(1, 0);
    for (std::uint32_t s = c; s < slab_count_; s += colours) {
      std::uint64_t work = slab_start_[s + 1] - slab_start_[s];
      for (std::uint32_t k = slab_start_[s]; k < slab_start_[s + 1]; ++k)
        work += nlist_.of(slab_members_[k]).size();
      w.push_back(w.back() + work);
    }
  }
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    !defined(__SANITIZE_ADDRESS__)
// AVX2 has no FMA, so the clone cannot contract mul + add (results equal the default clone's).
#define SADR_SIDE_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SADR_SIDE_CLONES
#endif

struct HalfSideParams {
  double two_dhc0, eps;
  double m_i = 0, vol_i = 0, rho_i = 0;  ///< one particle per block (!kLanes)
};

/// Vectorisable per-pair values of the half path (k < m; with kLanes the i quantities per lane,
/// as in sdpd_pair_block_lanes, else those of `p`): side[0..D) the noise impulse on i, amp z_a +
/// (amp_r z3) x_a (PairNoise::add); side[3] the j side of the continuity term, -m_i F (x.v) + 2
/// delta h c0 V_i (rho_i - rho_j) F r^2/(r^2 + eps h^2) (x_ji.v_ji = x_ij.v_ij; V_i = m_i/rho_i is
/// bitwise 1/d_i = b.inv_nd_i).
template <int D, bool kLanes>
SADR_SIDE_CLONES void half_side_terms(const SdpdPairBlock& b,
                                      const std::array<std::vector<float>, 4>& z,
                                      const std::vector<double>& m_i, std::size_t m,
                                      bool continuity, bool noise, HalfSideParams p,
                                      std::array<std::vector<double>, 4>& side) {
  if (continuity) {
    double* __restrict dj = side[3].data();
    const double* __restrict f = b.f.data();
    const double* __restrict r2 = b.r2.data();
    const double* __restrict rhoj = b.rho_j.data();
    const double* __restrict mi = m_i.data();
    const double* __restrict voli = b.inv_nd_i.data();
    const double* __restrict rhoi = b.rho_i.data();
    const double* __restrict x0 = b.x[0].data();
    const double* __restrict x1 = b.x[1].data();
    const double* __restrict x2 = b.x[2].data();
    const double* __restrict v0 = b.v[0].data();
    const double* __restrict v1 = b.v[1].data();
    const double* __restrict v2 = b.v[2].data();
    for (std::size_t k = 0; k < m; ++k) {
      double xv = x0[k] * v0[k];
      if constexpr (D > 1) xv += x1[k] * v1[k];
      if constexpr (D > 2) xv += x2[k] * v2[k];
      const double m_i_k = kLanes ? mi[k] : p.m_i;
      const double vol_i_k = kLanes ? voli[k] : p.vol_i;
      const double rho_i_k = kLanes ? rhoi[k] : p.rho_i;
      dj[k] = -m_i_k * f[k] * xv +
              p.two_dhc0 * vol_i_k * (rho_i_k - rhoj[k]) * f[k] * r2[k] / (r2[k] + p.eps);
    }
  }
  if (noise) {
    const double* __restrict amp = b.amp.data();
    const double* __restrict amp_r = b.amp_r.data();
    const float* __restrict z3 = z[3].data();
    for (int a = 0; a < D; ++a) {
      double* __restrict out = side[a].data();
      const double* __restrict xa = b.x[a].data();
      const float* __restrict za = z[a].data();
      for (std::size_t k = 0; k < m; ++k) {
        const double s3 = amp_r[k] * static_cast<double>(z3[k]);
        out[k] = amp[k] * static_cast<double>(za[k]) + s3 * xa[k];
      }
    }
  }
}

template <class PerSlab, class After>
void SdpdBackend::slab_phases_team(PerSlab&& per_slab, After&& after) {
  constexpr std::uint32_t colours = kSlabReach + 1;
  const auto nt = static_cast<std::uint64_t>(team_size());
  const auto t = static_cast<std::uint64_t>(thread_index());
  PairScratch& sc = scratch_[t];
  const std::uint32_t epoch = slab_epoch_;
  // Slab s writes to the particles of slabs s..s+R, so two slabs conflict iff they are at most
  // R apart; the particles of slab q receive from slabs q-R..q, one of each colour, in colour
  // order. Instead of a barrier after each colour, slab s waits for the conflicting slabs of
  // lower colours only (point-to-point, release/acquire flags holding the pass number): the
  // same order of every sum, but a thread does not wait for the whole other half of the box.
  auto wait_done = [&](std::uint32_t sq) {
    for (int spin = 0; slab_done_[sq].load(std::memory_order_acquire) != epoch; ++spin) {
      if (spin < 4096) {
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#endif
      } else {
        std::this_thread::yield();
      }
    }
  };
  // slab at offset o from s (o in [-R, R]), or slab_count_ if there is none (walled axis)
  auto slab_at = [&](std::uint32_t s, std::int64_t o) -> std::uint32_t {
    const std::int64_t q = static_cast<std::int64_t>(s) + o;
    if (slab_wrap_) return static_cast<std::uint32_t>((q + slab_count_) % slab_count_);
    return q < 0 || q >= static_cast<std::int64_t>(slab_count_) ? slab_count_
                                                                : static_cast<std::uint32_t>(q);
  };
  // The run [k0, k1) of the phase's slabs that this thread owns: contiguous (about the same part
  // of the box in every phase, so its particle data stays in its core's cache), cut by work:
  // slab k goes to the thread whose share holds the middle of its work. The result does not
  // depend on the assignment (each particle's sums keep the slab/member order).
  auto own_run = [&](std::uint32_t phase) {
    const std::vector<std::uint64_t>& w = colour_work_[phase];
    const std::uint64_t tasks = w.size() - 1, total = w.back();
    auto owner = [&](std::uint64_t k) {
      const std::uint64_t o = total > 0 ? (w[k] + w[k + 1]) * nt / (2 * total) : k * nt / tasks;
      return std::min(o, nt - 1);
    };
    std::uint64_t k0 = 0;
    while (k0 < tasks && owner(k0) < t) ++k0;
    std::uint64_t k1 = k0;
    while (k1 < tasks && owner(k1) == t) ++k1;
    return std::pair<std::uint64_t, std::uint64_t>{k0, k1};
  };
  auto members = [&](std::uint32_t s) {
    return std::pair<const std::uint32_t*, const std::uint32_t*>{
        slab_members_.data() + slab_start_[s], slab_members_.data() + slab_start_[s + 1]};
  };
  // The two ends of a run (next to other threads' slabs) go first: the other threads wait for
  // them.
  auto each_end_first = [](std::uint64_t k0, std::uint64_t k1, auto&& f) {
    if (k1 > k0) f(k0);
    if (k1 > k0 + 1) f(k1 - 1);
    for (std::uint64_t k = k0 + 1; k + 1 < k1; ++k) f(k);
  };
  for (std::uint32_t phase = 0; phase < colours; ++phase) {
    const auto [k0, k1] = own_run(phase);
    each_end_first(k0, k1, [&](std::uint64_t k) {
      const auto s = static_cast<std::uint32_t>(phase + colours * k);
      if (nt > 1) {
        for (std::int64_t o = -static_cast<std::int64_t>(kSlabReach); o <= kSlabReach; ++o) {
          const std::uint32_t q = slab_at(s, o);
          if (o != 0 && q < slab_count_ && q % colours < phase) wait_done(q);
        }
      }
      const auto [first, last] = members(s);
      per_slab(first, last, sc);
      slab_done_[s].store(epoch, std::memory_order_release);
    });
  }
  if constexpr (!std::is_same_v<std::decay_t<After>, std::nullptr_t>) {
    // after(first, last) on the members of each own slab q once its writers q-R..q are done
    // (nobody reads or writes its particles' hin_/hacc_ entries afterwards in this pass). The
    // interior of the runs first, the ends (which may wait for other threads) last.
    for (int pass = 0; pass < 2; ++pass) {
      for (std::uint32_t phase = 0; phase < colours; ++phase) {
        const auto [k0, k1] = own_run(phase);
        for (std::uint64_t k = k0; k < k1; ++k) {
          const bool end = k == k0 || k + 1 == k1;
          if (end != (pass == 1)) continue;
          const auto s = static_cast<std::uint32_t>(phase + colours * k);
          if (nt > 1) {
            for (std::int64_t o = -static_cast<std::int64_t>(kSlabReach); o < 0; ++o) {
              const std::uint32_t q = slab_at(s, o);
              if (q < slab_count_) wait_done(q);
            }
          }
          const auto [first, last] = members(s);
          after(first, last);
        }
      }
    }
  }
}

void SdpdBackend::next_slab_pass() {
  if (++slab_epoch_ == 0) slab_epoch_ = 1;
}

template <class PerSlab>
void SdpdBackend::slab_phases(PerSlab&& per_slab) {
  [[maybe_unused]] const auto ni = static_cast<std::int64_t>(mass_.size());
  // (the summation-density pass runs before evaluate_dim sizes the scratch; UBSan found it)
  if (scratch_.size() < static_cast<std::size_t>(max_threads()))
    scratch_.resize(static_cast<std::size_t>(max_threads()));
  // One parallel region for the three colours (the barriers order them): fewer thread
  // wake-ups on a loaded machine than one region per colour.
  next_slab_pass();
#pragma omp parallel if (ni > kMinParallel)
  slab_phases_team(per_slab, nullptr);
}

template <int D>
void SdpdBackend::summation_half(Y& y) {
  // SPEC eq 19, rho_i = m_i W(0) + sum_j m_j W_ij, with each pair evaluated once (no walls here)
  const std::size_t n = mass_.size();
  const double h2 = kernel_.support() * kernel_.support();
  for (std::size_t i = 0; i < n; ++i) y.rho[i] = mass_[i] * kernel_.w0();
  const double* x = y.x.data();
  double* rho = y.rho.data();
  slab_phases([&](const std::uint32_t* first, const std::uint32_t* last, PairScratch&) {
    for (; first != last; ++first) {
      const std::uint32_t i = *first;
      const double* xi = &x[3 * i];
      double sum = 0;
      for (const std::uint32_t j : nlist_.of(i)) {
        double d[D];
        const double r2 = pbox_.offset_first<D>(xi, &x[3 * j], d);
        if (r2 >= h2) continue;
        const double w = kernel_.w(std::sqrt(r2));
        sum += mass_[j] * w;
        rho[j] += mass_[i] * w;
      }
      rho[i] += sum;
    }
  });
}

template <int D, class After>
void SdpdBackend::half_pairs_team(const Y& y, std::uint64_t noise_step, bool noise_on,
                                  const SdpdPairParams& pp, After&& after) {
  const double h = kernel_.support();
  const double h2 = h * h;
  const bool continuity = model_.density_mode != DensityMode::kSummation;
  const double* x = y.x.data();
  const HalfIn* __restrict hin = hin_.data();  // filled by evaluate_dim
  HalfAcc* __restrict hacc = hacc_.data();     // zeroed by evaluate_dim
  // A few consecutive members of a slab share one block: 2D has ~12 pairs per particle, so one
  // particle per block leaves the 16-lane noise vectors a quarter empty and pays the call
  // overheads per 12 pairs. Every pair gives the same bits as alone, and the scatter below
  // keeps the particle order, so the result is bit-identical to one particle per block.
  constexpr std::size_t kGroupEntries = 64;  // list entries per block (3D: one particle)
  auto per_slab = [&](const std::uint32_t* first, const std::uint32_t* last, PairScratch& sc) {
    while (first != last) {
      const std::uint32_t* group_end = first;
      std::size_t entries = 0;
      while (group_end != last && entries < kGroupEntries)
        entries += nlist_.of(*group_end++).size();
      sc.reserve(entries);
      sc.seg_end.resize(static_cast<std::size_t>(group_end - first));
      SdpdPairBlock& b = sc.block;
      // 3D (~46 pairs per particle): one particle per block, i quantities broadcast (the
      // per-lane copies cost more than the fuller vectors gain there)
      const bool lanes = group_end - first > 1;
      // Per particle, two passes (callgrind, 3D 1e4: -6.5% instructions against one pass):
      // (1) minimum image and r^2 for every forward entry, compacted branch-free (each entry
      // written at slot m, m advances if r < h: the cut-off branch is unpredictable, ~1/3 of
      // the entries lie in the skin); (2) the per-particle data of the pairs within h only.
      // Block pointers are hoisted (GCC reloads them from the vectors otherwise).
      std::uint32_t* __restrict bj = b.j.data();
      std::uint32_t* __restrict bi = b.i.data();
      double* __restrict bx[3] = {b.x[0].data(), b.x[1].data(), b.x[2].data()};
      double* __restrict bv[3] = {b.v[0].data(), b.v[1].data(), b.v[2].data()};
      double* __restrict br2 = b.r2.data();
      double* __restrict bpd2 = b.pd2_j.data();
      double* __restrict bind = b.inv_nd_j.data();
      double* __restrict bm = b.m_j.data();
      double* __restrict bvol = b.vol_j.data();
      double* __restrict brho = b.rho_j.data();
      double* __restrict bsq = b.sqrt_inv_nd_j.data();
      double* __restrict bpd2i = b.pd2_i.data();
      double* __restrict bindi = b.inv_nd_i.data();
      double* __restrict brhoi = b.rho_i.data();
      double* __restrict bsqi = b.sqrt_inv_nd_i.data();
      double* __restrict bmi = sc.m_i.data();
      std::size_t m = 0;
      for (const std::uint32_t* p = first; p != group_end; ++p) {
        const std::uint32_t i = *p;
        const std::size_t m0 = m;
        const double* xi = &x[3 * i];
        for (const std::uint32_t j : nlist_.of(i)) {  // forward pairs only (rebuild_neighbors)
          double d[D];
          const double r2 = pbox_.offset_first<D>(xi, &x[3 * j], d);
          bj[m] = j;
          for (int a = 0; a < D; ++a) bx[a][m] = d[a];
          br2[m] = r2;
          m += r2 < h2 ? 1 : 0;
        }
        const HalfIn& pi = hin[i];
        for (std::size_t k = m0; k < m; ++k) {
          const HalfIn& pj = hin[bj[k]];
          for (int a = 0; a < D; ++a) bv[a][k] = pi.v[a] - pj.v[a];
          bpd2[k] = pj.pd2;
          bind[k] = pj.inv_nd;
          bm[k] = pj.m;
          bvol[k] = pj.inv_nd;  // V_j = m_j/rho_j, bitwise 1/d_j
          brho[k] = pj.rho;
          bsq[k] = pj.sqrt_inv_nd;
        }
        for (std::size_t k = m0; k < m && lanes; ++k) {
          bi[k] = i;
          bpd2i[k] = pi.pd2;
          bindi[k] = pi.inv_nd;
          brhoi[k] = pi.rho;
          bsqi[k] = pi.sqrt_inv_nd;
          bmi[k] = pi.m;
        }
        sc.seg_end[static_cast<std::size_t>(p - first)] = static_cast<std::uint32_t>(m);
      }
      float* z[4] = {sc.z[0].data(), sc.z[1].data(), sc.z[2].data(), sc.z[3].data()};
      // core's noise clones: avx512f (16 lanes) / avx2 / default, the same bits on each
      HalfSideParams sp{2.0 * pp.delta_h_c0, pp.eps_h2};
      if (m > 0 && lanes) {
        sdpd_pair_block_lanes<D>(pp, m, b);
        if (noise_on) {
          pair_noise_numbers_lanes(model_.seed, noise_step, b.i.data(), b.j.data(), m, model_.noise,
                                   z[0], z[1], z[2], z[3]);
        }
        half_side_terms<D, true>(b, sc.z, sc.m_i, m, continuity, noise_on, sp, sc.side);
      } else if (m > 0) {
        const HalfIn& pi = hin[*first];
        sdpd_pair_block<D>(pp, {*first, pi.pd2, pi.inv_nd, pi.rho, pi.sqrt_inv_nd}, m, b);
        if (noise_on) {
          pair_noise_numbers(model_.seed, noise_step, *first, b.j.data(), m, model_.noise, z[0],
                             z[1], z[2], z[3]);
        }
        sp.m_i = pi.m;
        sp.vol_i = pi.inv_nd;
        sp.rho_i = pi.rho;
        half_side_terms<D, false>(b, sc.z, sc.m_i, m, continuity, noise_on, sp, sc.side);
      }
      // Scatter particle by particle (member order): i sums its pairs in list order, j gets the
      // exact negatives (and its own terms).
      const double* dj = sc.side[3].data();
      std::size_t k = 0;
      for (const std::uint32_t* p = first; p != group_end; ++p) {
        const std::uint32_t i = *p;
        const std::size_t end = sc.seg_end[static_cast<std::size_t>(p - first)];
        if (k == end) continue;  // no pair within h: i is left untouched
        const double ind_i = hin[i].inv_nd;
        double force[D] = {}, fn[D] = {}, dr = 0, fs = 0;
        for (; k < end; ++k) {
          HalfAcc& aj = hacc[b.j[k]];
          const double f = b.f[k];
          for (int a = 0; a < D; ++a) {
            force[a] += b.force[a][k];
            aj.force[a] -= b.force[a][k];
          }
          fs += f * b.inv_nd_j[k];
          aj.fsum += f * ind_i;
          if (continuity) {
            dr += b.drho[k];
            aj.drho += dj[k];
          }
          if (noise_on) {
            for (int a = 0; a < D; ++a) {
              fn[a] += sc.side[a][k];
              aj.noise[a] -= sc.side[a][k];
            }
          }
        }
        HalfAcc& ai = hacc[i];
        for (int a = 0; a < D; ++a) ai.force[a] += force[a];
        ai.fsum += fs;
        if (continuity) ai.drho += dr;
        if (noise_on) {
          for (int a = 0; a < D; ++a) ai.noise[a] += fn[a];
        }
      }
      first = group_end;
    }
  };
  slab_phases_team(per_slab, after);
}

template <int D>
inline void SdpdBackend::half_rates(std::size_t i, const Y& y, bool noise_on, double* acc,
                                    double* acc_noise, double* drho, double& max_visc) const {
  const HalfAcc& ai = hacc_[i];
  max_visc = std::max(max_visc, ai.fsum / y.rho[i]);
  const double inv_m = 1.0 / mass_[i];
  const auto& bq = model_.boussinesq;
  double body[3] = {model_.gravity[0], model_.gravity[1], model_.gravity[2]};
  if (bq.species >= 0) {
    const double bqa = bq.coefficient * (y.c[bq.species][i] - bq.reference);
    for (int a = 0; a < 3; ++a) body[a] += bqa * bq.direction[a];
  }
  for (int a = 0; a < 3; ++a) acc[a] = a < D ? ai.force[a] * inv_m + body[a] : 0.0;
  if (noise_on) {
    for (int a = 0; a < 3; ++a) acc_noise[a] = a < D ? ai.noise[a] * inv_m : 0.0;
  }
  *drho = ai.drho;
}

template <int D>
void SdpdBackend::evaluate_half(const Y& y, std::uint64_t noise_step, Rates& out, bool noise_on,
                                const SdpdPairParams& pp, double c_d) {
  const std::size_t n = mass_.size();
  const auto ni = static_cast<std::int64_t>(n);
  if (scratch_.size() < static_cast<std::size_t>(max_threads()))
    scratch_.resize(static_cast<std::size_t>(max_threads()));
  next_slab_pass();
#pragma omp parallel if (ni > kMinParallel)
  half_pairs_team<D>(y, noise_step, noise_on, pp, nullptr);
  double max_visc = 0;
  double* acc = out.acc.data();
  double* accn = noise_on ? out.acc_noise.data() : nullptr;
  double* drho = out.drho.data();
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight) reduction(max : max_visc)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    half_rates<D>(i, y, noise_on, &acc[3 * i], noise_on ? &accn[3 * i] : nullptr, &drho[i],
                  max_visc);
  }
  out.max_k_sum = 0;
  out.max_visc_sum = 2.0 * c_d * max_visc;
}

}  // namespace sadr::fluid
