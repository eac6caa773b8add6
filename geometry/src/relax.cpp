// SPDX-License-Identifier: MIT
// SPH number density, particle relaxation and volumes (particles.hpp).
//
// Relaxation minimises E = sum over fluid i of (n_i / n_ref - 1)^2 over the fluid positions by a
// Gauss-Newton-scaled gradient step with a backtracking line search on E: the direction for
// particle k is (n_ref / S) sum_j (e_k + e_j) F(r_kj) (x_k - x_j), with e = n / n_ref - 1 for fluid
// and 0 for walls, and S = sum_j F(r_j)^2 r_j^2 over the ideal lattice (the diagonal of J^T J).
// Walls stay on the lattice; a fluid particle that would leave the fluid region is put back along
// the normal. Neighbours come from a Verlet list with a skin, rebuilt when a particle has moved
// half the skin.
#include <chrono>
#include <cmath>
#include <string>

#include "cell_grid.hpp"
#include "lattice.hpp"
#include "parallel.hpp"
#include "sadr/common/status.hpp"
#include "sadr/geometry/kernel.hpp"
#include "sadr/geometry/particles.hpp"

namespace sadr::geometry {
namespace {

void check_support(const ParticleSet& p, double support) {
  const std::size_t n = p.position.size();
  if (p.kind.size() != n || p.surface_id.size() != n || p.distance.size() != n ||
      p.normal.size() != n || p.volume.size() != n || p.mass.size() != n) {
    throw InvalidArgument("particle set: every array must have one entry per position (" +
                          std::to_string(n) + "); use the output of fill()");
  }
  if (p.dimension != 2 && p.dimension != 3) {
    throw InvalidArgument("particle set: dimension must be 2 or 3, got " +
                          std::to_string(p.dimension));
  }
  if (!(support > p.spacing) || !std::isfinite(support)) {
    throw InvalidArgument("kernel support must be finite and exceed the spacing " +
                          format_value(p.spacing) + ", got " + format_value(support));
  }
}

/// Offsets of the ideal lattice's sites within `support` of a site (the site excluded).
std::vector<Vec3> ideal_neighbours(int dim, Lattice lattice, double dx, double support) {
  const double l = support + 4 * dx;
  const Aabb box{{-l, -l, dim == 3 ? -l : 0.0}, {l, l, dim == 3 ? l : 0.0}};
  const LatticeCells lat = make_lattice(dim, lattice, dx, box, {});
  std::vector<Vec3> sites;
  for (long k = 0; k < lat.n[2]; ++k) {
    for (long j = 0; j < lat.n[1]; ++j) {
      for (long i = 0; i < lat.n[0]; ++i) {
        for (std::size_t b = 0; b < lat.basis.size(); ++b) sites.push_back(lat.site(i, j, k, b));
      }
    }
  }
  Vec3 centre = sites[0];
  for (const Vec3& s : sites) {
    if (norm2(s) < norm2(centre)) centre = s;
  }
  std::vector<Vec3> out;
  for (const Vec3& s : sites) {
    const double r2 = norm2(s - centre);
    if (r2 > 0 && r2 < support * support) out.push_back(s - centre);
  }
  return out;
}

/// Outward normal of the fluid region's boundary at p: that of the shape selected by the max in
/// fluid_signed_distance.
Vec3 region_normal(const FluidDomain& d, Vec3 p) {
  double best = d.body ? d.body->signed_distance(p) : -std::numeric_limits<double>::infinity();
  Vec3 n = d.body ? d.body->normal(p) : Vec3{};
  for (const auto& s : d.solids) {
    const double v = -s.shape->signed_distance(p);
    if (v > best) best = v, n = -s.shape->normal(p);
  }
  return n;
}

}  // namespace

double reference_number_density(int dimension, Lattice lattice, double spacing, double support) {
  const WendlandC2 w(dimension, support);
  double n = w.w(0);
  for (const Vec3& d : ideal_neighbours(dimension, lattice, spacing, support)) n += w.w(norm(d));
  return n;
}

std::vector<double> number_density(const ParticleSet& p, const FluidDomain& domain, double support,
                                   int threads) {
  check_support(p, support);
  CellGrid grid(domain.box, p.dimension, domain.periodic, support);
  grid.build(p.position);
  const WendlandC2 w(p.dimension, support);
  std::vector<double> n(p.size(), 0.0);
  const double h2 = support * support;
  parallel_for(p.size(), threads, [&](std::size_t i) {
    double s = 0;
    grid.for_neighbors(p.position[i], p.position, [&](int, Vec3 d) {
      const double r2 = norm2(d);
      if (r2 < h2) s += w.w(std::sqrt(r2));
    });
    n[i] = s;
  });
  return n;
}

RelaxReport relax(ParticleSet& p, const FluidDomain& domain, Lattice lattice,
                  const RelaxOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  check_support(p, o.support);
  RelaxReport rep;
  const double h = o.support, dx = p.spacing, skin = 0.3 * dx;
  const double reach2 = (h + skin) * (h + skin), h2 = h * h;
  const WendlandC2 w(p.dimension, h);
  const double n0 = reference_number_density(p.dimension, lattice, dx, h);
  rep.reference_number_density = n0;
  double s0 = 0;
  for (const Vec3& d : ideal_neighbours(p.dimension, lattice, dx, h)) {
    const double r = norm(d);
    s0 += w.f(r) * w.f(r) * r * r;
  }
  std::vector<int> fluid, slot(p.size(), -1);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] == Kind::kFluid) {
      slot[i] = static_cast<int>(fluid.size());
      fluid.push_back(static_cast<int>(i));
    }
  }
  const std::size_t nf = fluid.size();
  CellGrid grid(domain.box, p.dimension, domain.periodic, h + skin);
  std::vector<std::vector<int>> nbr(nf);
  std::vector<Vec3> at_build(nf);
  const auto build_list = [&] {
    grid.build(p.position);
    parallel_for(nf, o.threads, [&](std::size_t f) {
      const int i = fluid[f];
      nbr[f].clear();
      grid.for_neighbors(p.position[i], p.position, [&](int j, Vec3 d) {
        if (j != i && norm2(d) < reach2) nbr[f].push_back(j);
      });
      at_build[f] = p.position[i];
    });
  };
  // e = n / n0 - 1 of every fluid particle at positions x (fluid entries of x by slot).
  const auto errors = [&](const std::vector<Vec3>& x, std::vector<double>& e) {
    parallel_for(nf, o.threads, [&](std::size_t f) {
      double s = w.w(0);
      for (int j : nbr[f]) {
        const Vec3 xj = slot[j] >= 0 ? x[slot[j]] : p.position[j];
        const double r2 = norm2(grid.min_image(x[f] - xj));
        if (r2 < h2) s += w.w(std::sqrt(r2));
      }
      e[f] = s / n0 - 1;
    });
    double sum = 0;
    for (double v : e) sum += v * v;
    return sum;
  };
  const auto summarize = [&](const std::vector<double>& e, double& max, double& rms) {
    max = 0;
    rms = 0;
    for (double v : e) max = std::max(max, std::abs(v)), rms += v * v;
    rms = nf ? std::sqrt(rms / static_cast<double>(nf)) : 0.0;
  };
  std::vector<Vec3> x(nf), trial(nf), dir(nf);
  for (std::size_t f = 0; f < nf; ++f) x[f] = p.position[fluid[f]];
  std::vector<double> e(nf), e_trial(nf);
  build_list();
  double energy = errors(x, e);
  summarize(e, rep.max_error_before, rep.rms_error_before);
  rep.max_error = rep.max_error_before;
  rep.rms_error = rep.rms_error_before;
  double eta = 0.5;
  const double cap = o.max_step * dx;
  for (int it = 0; it < o.max_iterations && rep.max_error >= o.tolerance; ++it) {
    rep.iterations = it + 1;
    parallel_for(nf, o.threads, [&](std::size_t f) {
      Vec3 g;
      for (int j : nbr[f]) {
        const Vec3 xj = slot[j] >= 0 ? x[slot[j]] : p.position[j];
        const Vec3 d = grid.min_image(x[f] - xj);
        const double r2 = norm2(d);
        if (r2 < h2) g += (e[f] + (slot[j] >= 0 ? e[slot[j]] : 0.0)) * w.f(std::sqrt(r2)) * d;
      }
      dir[f] = (n0 / s0) * g;
    });
    bool accepted = false;
    for (int tries = 0; tries < 12 && !accepted; ++tries) {
      parallel_for(nf, o.threads, [&](std::size_t f) {
        Vec3 step = eta * dir[f];
        if (norm(step) > cap) step = cap / norm(step) * step;
        Vec3 y = grid.confine(x[f] + step);
        if (p.distance[fluid[f]] < std::numeric_limits<double>::infinity()) {
          const double sd = fluid_signed_distance(domain, y);
          const double margin = 0.1 * dx;
          if (sd > -margin) y = grid.confine(y - (sd + margin) * region_normal(domain, y));
        }
        trial[f] = y;
      });
      const double e2 = errors(trial, e_trial);
      if (e2 < energy) {
        accepted = true;
        energy = e2;
        x.swap(trial);
        e.swap(e_trial);
        eta = std::min(4.0, eta * 1.5);
      } else {
        eta *= 0.5;
      }
    }
    if (!accepted) break;  // no descent at any step length: a (local) minimum
    summarize(e, rep.max_error, rep.rms_error);
    double moved = 0;
    for (std::size_t f = 0; f < nf; ++f) moved = std::max(moved, norm2(x[f] - at_build[f]));
    if (4 * moved > skin * skin) {
      for (std::size_t f = 0; f < nf; ++f) p.position[fluid[f]] = x[f];
      build_list();
    }
  }
  for (std::size_t f = 0; f < nf; ++f) p.position[fluid[f]] = x[f];
  // Near-surface fluid particles moved: their distance and nearest surface again.
  parallel_for(nf, o.threads, [&](std::size_t f) {
    const int i = fluid[f];
    if (p.distance[i] == std::numeric_limits<double>::infinity()) return;
    const auto [dist, id] = nearest_surface(domain, p.position[i], h + dx);
    p.distance[i] = dist;
    p.surface_id[i] = id;
  });
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return rep;
}

double assign_volumes(ParticleSet& p, const FluidDomain& domain, double support,
                      double domain_volume, double rest_density, int threads) {
  if (!(rest_density > 0) || !std::isfinite(rest_density)) {
    throw InvalidArgument("assign_volumes: rest_density must be finite and > 0, got " +
                          format_value(rest_density));
  }
  if (!(domain_volume > 0) || !std::isfinite(domain_volume)) {
    throw InvalidArgument("assign_volumes: domain_volume must be finite and > 0, got " +
                          format_value(domain_volume));
  }
  const std::vector<double> n = number_density(p, domain, support, threads);
  double sum = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] == Kind::kFluid) sum += 1.0 / n[i];
  }
  if (!(sum > 0)) throw InvalidArgument("assign_volumes: there are no fluid particles");
  const double scale = domain_volume / sum;
  p.mass.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] == Kind::kFluid) p.volume[i] = scale / n[i];
    p.mass[i] = rest_density * p.volume[i];
  }
  return scale;
}

}  // namespace sadr::geometry
