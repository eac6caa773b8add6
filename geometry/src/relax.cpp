// SPDX-License-Identifier: MIT
// SPH number density, particle relaxation and volumes (particles.hpp).
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
  if (!(support > p.spacing) || !std::isfinite(support)) {
    throw InvalidArgument("kernel support must be finite and exceed the spacing " +
                          format_value(p.spacing) + ", got " + format_value(support));
  }
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

struct Errors {
  double max = 0, rms = 0;
};

Errors density_errors(const std::vector<double>& n, const std::vector<int>& fluid, double n0) {
  Errors e;
  for (int i : fluid) {
    const double r = std::abs(n[i] / n0 - 1);
    e.max = std::max(e.max, r);
    e.rms += r * r;
  }
  e.rms = fluid.empty() ? 0.0 : std::sqrt(e.rms / static_cast<double>(fluid.size()));
  return e;
}

}  // namespace

double reference_number_density(int dimension, Lattice lattice, double spacing, double support) {
  const double l = support + 4 * spacing;
  const Aabb box{{-l, -l, dimension == 3 ? -l : 0.0}, {l, l, dimension == 3 ? l : 0.0}};
  const LatticeCells lat = make_lattice(dimension, lattice, spacing, box, {});
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
  const WendlandC2 w(dimension, support);
  double n = 0;
  for (const Vec3& s : sites) n += w.w(norm(s - centre));
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
  const double h = o.support, h2 = h * h, dx = p.spacing;
  const WendlandC2 w(p.dimension, h);
  const double n0 = reference_number_density(p.dimension, lattice, dx, h);
  rep.reference_number_density = n0;
  // Fluid particles, and wall particles within half a support of their surface, move; deeper
  // walls stay on the lattice as a fixed backing.
  std::vector<int> fluid, moving;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] == Kind::kFluid) fluid.push_back(static_cast<int>(i));
    if (p.kind[i] == Kind::kFluid || p.distance[i] < 0.5 * h) moving.push_back(static_cast<int>(i));
  }
  CellGrid grid(domain.box, p.dimension, domain.periodic, h);
  // Pressure P = (n / n0)^2 / n: the denser side of a pair pushes harder, so the fixed point is a
  // uniform density, not only a vanishing kernel-gradient sum.
  const auto pressure = [&](double n) { return n / (n0 * n0); };
  // Stiffness of the move on the ideal lattice: a site displaced by eps comes back by k eps per
  // unit step; the step 0.5 / k then halves a displacement each iteration.
  double k_stiff = 0;
  {
    const double eps = 1e-3 * dx;
    for (int a = 0; a < p.dimension; ++a) {
      const double l = h + 4 * dx;
      const Aabb box{{-l, -l, p.dimension == 3 ? -l : 0.0}, {l, l, p.dimension == 3 ? l : 0.0}};
      const LatticeCells lat = make_lattice(p.dimension, lattice, dx, box, {});
      Vec3 centre{1e300, 0, 0};
      std::vector<Vec3> sites;
      for (long kk = 0; kk < lat.n[2]; ++kk)
        for (long j = 0; j < lat.n[1]; ++j)
          for (long i = 0; i < lat.n[0]; ++i)
            for (std::size_t b = 0; b < lat.basis.size(); ++b)
              sites.push_back(lat.site(i, j, kk, b));
      for (const Vec3& s : sites) {
        if (norm2(s) < norm2(centre)) centre = s;
      }
      Vec3 moved = centre;
      moved[a] += eps;
      Vec3 delta;
      for (const Vec3& s : sites) {
        const Vec3 d = moved - s;
        const double r = norm(d);
        if (norm2(s - centre) > 0 && r < h) delta += 2 * pressure(n0) * w.f(r) * d;
      }
      k_stiff = std::max(k_stiff, -delta[a] / eps);
    }
  }
  if (!(k_stiff > 0)) throw NumericalFailure("relax: the kernel gives no restoring force");
  const double lambda = o.step_factor / k_stiff;
  const double cap = o.max_step * dx;
  std::vector<double> n(p.size(), n0);
  std::vector<Vec3> next(p.position);
  for (int it = 0;; ++it) {
    grid.build(p.position);
    parallel_for(moving.size(), o.threads, [&](std::size_t f) {
      const int i = moving[f];
      double s = 0;
      grid.for_neighbors(p.position[i], p.position, [&](int, Vec3 d) {
        const double r2 = norm2(d);
        if (r2 < h2) s += w.w(std::sqrt(r2));
      });
      n[i] = s;
    });
    const Errors e = density_errors(n, fluid, n0);
    if (it == 0) rep.max_error_before = e.max, rep.rms_error_before = e.rms;
    rep.max_error = e.max;
    rep.rms_error = e.rms;
    rep.iterations = it;
    if (e.max < o.tolerance || it >= o.max_iterations) break;
    parallel_for(moving.size(), o.threads, [&](std::size_t f) {
      const int i = moving[f];
      const double pi = pressure(n[i]);
      Vec3 delta;
      grid.for_neighbors(p.position[i], p.position, [&](int j, Vec3 d) {
        const double r2 = norm2(d);
        if (j != i && r2 < h2) delta += (pi + pressure(n[j])) * w.f(std::sqrt(r2)) * d;
      });
      Vec3 step = lambda * delta;
      if (norm(step) > cap) step = cap / norm(step) * step;
      Vec3 x = grid.confine(p.position[i] + step);
      if (p.distance[i] < std::numeric_limits<double>::infinity()) {
        // Near a surface: each particle stays on its side, 0.1 dx clear of the surface (fluid
        // inside the region, walls in their layer).
        const double sd = fluid_signed_distance(domain, x);
        const double margin = 0.1 * dx;
        if (p.kind[i] == Kind::kFluid && sd > -margin) {
          x = grid.confine(x - (sd + margin) * region_normal(domain, x));
        } else if (p.kind[i] == Kind::kWall && sd < margin) {
          x = grid.confine(x + (margin - sd) * region_normal(domain, x));
        }
      }
      next[i] = x;
    });
    for (int i : moving) p.position[i] = next[i];
  }
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return rep;
}

double assign_volumes(ParticleSet& p, const FluidDomain& domain, double support,
                      double domain_volume, int threads) {
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
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] == Kind::kFluid) p.volume[i] = scale / n[i];
  }
  return scale;
}

}  // namespace sadr::geometry
