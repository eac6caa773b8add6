// SPDX-License-Identifier: MIT
#include "sadr/fluid/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/fluid/parallel.hpp"

namespace sadr::fluid {

CellListBuilder::CellListBuilder(const Box& box, double cutoff) : pbox_(box), cutoff_(cutoff) {
  box.validate();
  if (!(std::isfinite(cutoff) && cutoff > 0)) {
    throw InvalidArgument("neighbour cutoff = " + format_value(cutoff) +
                          " (must be finite and > 0)");
  }
  for (int a = 0; a < box.dimension; ++a) {
    const double len = box.length(a);
    if (box.periodic[a] && len < 2.0 * cutoff) {
      throw InvalidArgument("periodic axis " + std::to_string(a) + " has length " +
                            format_value(len) + " < 2 x neighbour cutoff (" +
                            format_value(2.0 * cutoff) +
                            "); enlarge the box or reduce smoothing_length");
    }
    // cells of width >= cutoff / kCellReach: a neighbour lies at most kCellReach cells away
    // (capped as a double, before the int conversion could overflow)
    ncell_[a] = static_cast<int>(
        std::clamp(std::floor(kCellReach * len / cutoff), 1.0, static_cast<double>(1 << 20)));
    inv_cell_[a] = ncell_[a] / len;
  }
}

std::size_t CellListBuilder::expected_entries(std::size_t n) const {
  const Box& box = pbox_.box();
  double volume = 1, ball = 2 * cutoff_;  // 1D: a segment of length 2 rc
  for (int a = 0; a < box.dimension; ++a) volume *= box.length(a);
  if (box.dimension == 2) ball = std::numbers::pi * cutoff_ * cutoff_;
  if (box.dimension == 3) ball = 4.0 / 3.0 * std::numbers::pi * cutoff_ * cutoff_ * cutoff_;
  const double e = static_cast<double>(n) * std::min(static_cast<double>(n), n * ball / volume);
  return std::isfinite(e) && e > 0 ? static_cast<std::size_t>(std::min(e, 1e12)) : 0;
}

void CellListBuilder::build(std::span<const double> positions, NeighborList& out) const {
  const std::size_t n = positions.size() / 3;
  const Box& box = pbox_.box();
  const int dim = box.dimension;
  const std::size_t ncells =
      static_cast<std::size_t>(ncell_[0]) * static_cast<std::size_t>(ncell_[1]) * ncell_[2];
  // Bin particles (counting sort; deterministic).
  std::vector<std::uint32_t> cell_of(n);
  std::vector<std::uint32_t> cell_start(ncells + 1, 0);
  std::vector<std::array<int, 3>> coord(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::array<int, 3> c{0, 0, 0};
    for (int a = 0; a < dim; ++a) {
      // Clamped as a double: a position far outside the box (1e300) or NaN would make
      // the int conversion undefined (found by fuzz_fluid_requests).
      const double k = std::floor((positions[3 * i + a] - box.lo[a]) * inv_cell_[a]);
      c[a] = k >= 0 ? static_cast<int>(std::min(k, static_cast<double>(ncell_[a] - 1))) : 0;
    }
    coord[i] = c;
    cell_of[i] = static_cast<std::uint32_t>(
        (static_cast<std::size_t>(c[2]) * ncell_[1] + c[1]) * ncell_[0] + c[0]);
    ++cell_start[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c < ncells; ++c) cell_start[c + 1] += cell_start[c];
  std::vector<std::uint32_t> cell_particles(n);
  {
    std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      cell_particles[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  }
  // Distinct neighbouring cell coordinates per axis for each cell coordinate.
  auto axis_cells = [&](int a, int c, int* out_cells) -> int {
    if (a >= dim) {
      out_cells[0] = 0;
      return 1;
    }
    int cnt = 0;
    for (int o = -kCellReach; o <= kCellReach; ++o) {
      int k = c + o;
      if (pbox_.periodic(a)) {
        k = (k + ncell_[a]) % ncell_[a];
      } else if (k < 0 || k >= ncell_[a]) {
        continue;
      }
      bool dup = false;
      for (int m = 0; m < cnt; ++m) dup = dup || out_cells[m] == k;
      if (!dup) out_cells[cnt++] = k;
    }
    return cnt;
  };
  // Candidate coordinates in cell order, so the scan of a cell reads contiguous memory (the
  // same values as positions[3 j + a]: the distances and the list do not change).
  std::array<std::vector<double>, 3> cpos;
  for (int a = 0; a < 3; ++a) {
    cpos[a].resize(n);
    for (std::size_t k = 0; k < n; ++k) cpos[a][k] = positions[3 * cell_particles[k] + a];
  }
  const double* __restrict px = cpos[0].data();
  const double* __restrict py = cpos[1].data();
  const double* __restrict pz = cpos[2].data();
  const double rc2 = cutoff_ * cutoff_;
  // Appends the neighbours of i to `list` (unsorted). Branch-free: every candidate is written
  // and the end advances only if it is within the cutoff (about 1 in 3 is: unpredictable).
  auto scan = [&](std::size_t i, std::vector<std::uint32_t>& list) {
    int cx[2 * kCellReach + 1], cy[2 * kCellReach + 1], cz[2 * kCellReach + 1];
    const int nx = axis_cells(0, coord[i][0], cx);
    const int ny = axis_cells(1, coord[i][1], cy);
    const int nz = axis_cells(2, coord[i][2], cz);
    std::size_t cells[(2 * kCellReach + 1) * (2 * kCellReach + 1) * (2 * kCellReach + 1)];
    std::size_t nc = 0, candidates = 0;
    for (int iz = 0; iz < nz; ++iz) {
      for (int iy = 0; iy < ny; ++iy) {
        for (int ix = 0; ix < nx; ++ix) {
          const std::size_t c =
              (static_cast<std::size_t>(cz[iz]) * ncell_[1] + cy[iy]) * ncell_[0] + cx[ix];
          cells[nc++] = c;
          candidates += cell_start[c + 1] - cell_start[c];
        }
      }
    }
    std::size_t pos = list.size();
    list.resize(pos + candidates);
    std::uint32_t* __restrict dst = list.data();
    const double* xi = &positions[3 * i];
    for (std::size_t q = 0; q < nc; ++q) {
      const std::size_t c = cells[q];
      for (std::uint32_t k = cell_start[c]; k < cell_start[c + 1]; ++k) {
        const std::uint32_t j = cell_particles[k];
        double d[3] = {xi[0] - px[k], xi[1] - py[k], xi[2] - pz[k]};
        pbox_.minimum_image(d);
        dst[pos] = j;
        pos += static_cast<std::size_t>((d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < rc2) & (j != i));
      }
    }
    list.resize(pos);
  };
  // One scan per particle (a counting pass and a filling pass scanned every cell twice): each
  // thread appends its static, contiguous range of particles to its own buffer, then the
  // buffers are placed behind the prefix sum. Lists are sorted, so the result is the same for
  // any thread count.
  //
  // Memory: the old list is released first (build never reads it), and the buffers are reserved
  // from the expected count (density x cutoff ball, + 1/8) so they rarely grow by doubling, which
  // held the old and the new block at once. Thread 0's buffer (the front of the list, reserved
  // for all of it) becomes the list; the others are copied behind it.
  const std::size_t expected = expected_entries(n);
  std::vector<std::uint32_t>().swap(out.indices);
  out.offsets.assign(n + 1, 0);
  const auto ni = static_cast<std::int64_t>(n);
  const auto nt = static_cast<std::size_t>(max_threads());
  std::vector<std::vector<std::uint32_t>> buf(nt);
  std::vector<std::int64_t> first(nt, ni);
  bool adopted = false;
#pragma omp parallel if (ni > kMinParallel)
  {
    const auto t = static_cast<std::size_t>(thread_index());
    const auto team = static_cast<std::size_t>(team_size());
    std::vector<std::uint32_t>& mine = buf[t];
    // + one particle's candidates (about 4x its neighbours): the scan's last resize stays inside
    const std::size_t share = t == 0 ? expected : expected / team;
    mine.reserve(share + share / 8 + 4 * expected / std::max<std::size_t>(n, 1) + 64);
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < ni; ++i) {
      if (first[t] == ni) first[t] = i;
      const std::size_t start = mine.size();
      scan(static_cast<std::size_t>(i), mine);
      std::sort(mine.begin() + static_cast<std::ptrdiff_t>(start), mine.end());
      out.offsets[static_cast<std::size_t>(i) + 1] =
          static_cast<std::uint32_t>(mine.size() - start);
    }
#pragma omp single
    {
      for (std::size_t i = 0; i < n; ++i) out.offsets[i + 1] += out.offsets[i];
      adopted = first[0] == 0 || buf[0].empty();  // thread 0's lists start the whole list
      if (adopted) out.indices = std::move(buf[0]);
      out.indices.resize(out.offsets[n]);
    }
    if (!(t == 0 && adopted) && !mine.empty()) {
      std::copy(mine.begin(), mine.end(),
                out.indices.begin() + out.offsets[static_cast<std::size_t>(first[t])]);
    }
  }
}

NeighborList brute_force_neighbors(const Box& box, double cutoff,
                                   std::span<const double> positions) {
  const PeriodicBox pbox(box);
  const std::size_t n = positions.size() / 3;
  NeighborList out;
  out.offsets.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      double d[3] = {positions[3 * i] - positions[3 * j],
                     positions[3 * i + 1] - positions[3 * j + 1],
                     positions[3 * i + 2] - positions[3 * j + 2]};
      pbox.minimum_image(d);
      if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < cutoff * cutoff) {
        out.indices.push_back(static_cast<std::uint32_t>(j));
      }
    }
    out.offsets[i + 1] = static_cast<std::uint32_t>(out.indices.size());
  }
  return out;
}

}  // namespace sadr::fluid
