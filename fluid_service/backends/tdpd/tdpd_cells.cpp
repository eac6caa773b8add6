// SPDX-License-Identifier: MIT
/// \file tdpd_cells.cpp
/// tdpd::build_half_list (see tdpd_cells.hpp).
#include "tdpd_cells.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "sadr/fluid/parallel.hpp"

namespace sadr::fluid::tdpd {
namespace {

// cells of width >= cutoff / kReach, the slab reach of the scheduler; kColours = kReach + 1
// colours, so a periodic layer count is a multiple of 3
constexpr int kReach = static_cast<int>(SlabScheduler::kReach);
constexpr int kColours = static_cast<int>(SlabScheduler::kColours);

}  // namespace

void build_half_list(const PeriodicBox& pbox, double cutoff, std::span<const double> x,
                     HalfList& out) {
  const Box& box = pbox.box();
  const int dim = box.dimension;
  const int sa = dim - 1;  // slab axis: the outermost cell index
  const std::size_t n = x.size() / 3;
  std::array<int, 3> nc{1, 1, 1};
  std::array<double, 3> inv_w{0.0, 0.0, 0.0};
  for (int a = 0; a < dim; ++a) {
    const double len = box.length(a);
    // (1 + 1e-9): a pair within the cutoff stays within kReach cells despite binning rounding
    int c = static_cast<int>(std::min(std::floor(kReach * len / (cutoff * (1.0 + 1e-9))), 1024.0));
    c = std::max(c, 1);
    if (a == sa && box.periodic[a]) {
      c -= c % kColours;
      if (c <= 2 * kReach) c = 1;  // layers +1, +2 would alias -2, -1: one slab (serial)
    }
    nc[a] = c;
    inv_w[a] = c / len;
  }
  const std::size_t ncells = static_cast<std::size_t>(nc[0]) * nc[1] * nc[2];
  const std::size_t per_layer = ncells / static_cast<std::size_t>(nc[sa]);
  // Bin (counting sort, stable): positions copied in cell order for contiguous candidate loops.
  std::vector<std::array<int, 3>> coord(n);
  std::vector<std::uint32_t> cell_of(n), cell_start(ncells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::array<int, 3> c{0, 0, 0};
    for (int a = 0; a < dim; ++a) {
      const double t = std::floor((x[3 * i + a] - box.lo[a]) * inv_w[a]);
      c[a] = static_cast<int>(std::clamp(t, 0.0, nc[a] - 1.0));
    }
    coord[i] = c;
    cell_of[i] = static_cast<std::uint32_t>(
        (static_cast<std::size_t>(c[2]) * nc[1] + static_cast<std::size_t>(c[1])) * nc[0] +
        static_cast<std::size_t>(c[0]));
    ++cell_start[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c < ncells; ++c) cell_start[c + 1] += cell_start[c];
  std::vector<std::uint32_t> sid(n);
  std::vector<double> sx(3 * n);
  {
    std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t k = fill[cell_of[i]]++;
      sid[k] = static_cast<std::uint32_t>(i);
      for (int a = 0; a < 3; ++a) sx[3 * k + a] = x[3 * i + a];
    }
  }
  SlabPartition& slabs = out.slabs;
  slabs.count = static_cast<std::uint32_t>(nc[sa]);
  slabs.wrap = box.periodic[sa];
  slabs.start.resize(slabs.count + 1);
  for (std::uint32_t s = 0; s <= slabs.count; ++s) slabs.start[s] = cell_start[s * per_layer];
  slabs.members = sid;  // by layer, in cell order within a layer (locality of the pair loop)

  // Distinct neighbour cell coordinates on axis a: the forward layers 0..kReach on the slab
  // axis (first entry: the own layer), -kReach..kReach on the others.
  auto axis_cells = [&](int a, int c, int* cells) {
    if (a >= dim) {
      cells[0] = 0;
      return 1;
    }
    int cnt = 0;
    for (int o = a == sa ? 0 : -kReach; o <= kReach; ++o) {
      int k = c + o;
      if (box.periodic[a]) {
        k = ((k % nc[a]) + nc[a]) % nc[a];
      } else if (k < 0 || k >= nc[a]) {
        continue;
      }
      bool dup = false;
      for (int m = 0; m < cnt; ++m) dup = dup || cells[m] == k;
      if (!dup) cells[cnt++] = k;
    }
    return cnt;
  };
  const double cut2 = cutoff * cutoff;
  // Fixed blocks of particles (not per thread): the concatenation is thread-count independent.
  constexpr std::int64_t kBlocks = 64;
  std::vector<std::vector<std::uint32_t>> seg(kBlocks);
  auto& offsets = out.list.offsets;
  offsets.assign(n + 1, 0);
  [[maybe_unused]] const auto ni = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(dynamic, 1) if (ni >= kMinParallel)
  for (std::int64_t blk = 0; blk < kBlocks; ++blk) {
    const std::size_t i0 = n * static_cast<std::size_t>(blk) / kBlocks;
    const std::size_t i1 = n * static_cast<std::size_t>(blk + 1) / kBlocks;
    auto& dst = seg[static_cast<std::size_t>(blk)];
    dst.clear();
    for (std::size_t i = i0; i < i1; ++i) {
      int cs[3][2 * kReach + 1];
      int cnt[3];
      for (int a = 0; a < 3; ++a) cnt[a] = axis_cells(a, coord[i][a], cs[a]);
      const double xi[3] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
      const std::size_t before = dst.size();
      for (int l = 0; l < cnt[sa]; ++l) {
        const bool own_layer = l == 0;  // j > i there, every pair once
        for (int iy = 0; iy < (sa >= 2 ? cnt[1] : 1); ++iy) {
          for (int ix = 0; ix < (sa >= 1 ? cnt[0] : 1); ++ix) {
            int c3[3] = {sa >= 1 ? cs[0][ix] : 0, sa >= 2 ? cs[1][iy] : 0, 0};
            c3[sa] = cs[sa][l];
            const std::size_t c =
                (static_cast<std::size_t>(c3[2]) * nc[1] + static_cast<std::size_t>(c3[1])) *
                    nc[0] +
                static_cast<std::size_t>(c3[0]);
            for (std::uint32_t k = cell_start[c]; k < cell_start[c + 1]; ++k) {
              const std::uint32_t j = sid[k];
              if (own_layer && j <= i) continue;
              double d[3] = {xi[0] - sx[3 * k], xi[1] - sx[3 * k + 1], xi[2] - sx[3 * k + 2]};
              pbox.minimum_image(d);
              double r2 = 0.0;
              for (int a = 0; a < dim; ++a) r2 += d[a] * d[a];
              if (r2 < cut2) dst.push_back(j);
            }
          }
        }
      }
      offsets[i + 1] = static_cast<std::uint32_t>(dst.size() - before);
    }
  }
  out.max_len = 0;
  for (std::size_t i = 0; i < n; ++i) {
    out.max_len = std::max<std::size_t>(out.max_len, offsets[i + 1]);
    offsets[i + 1] += offsets[i];
  }
  out.list.indices.resize(offsets[n]);
  std::size_t pos = 0;
  for (const auto& s : seg) {
    std::copy(s.begin(), s.end(), out.list.indices.begin() + static_cast<std::ptrdiff_t>(pos));
    pos += s.size();
  }
}

}  // namespace sadr::fluid::tdpd
