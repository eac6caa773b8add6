// SPDX-License-Identifier: MIT
// Lattice fill of a fluid domain with wall layers (particles.hpp).
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

#include "lattice.hpp"
#include "parallel.hpp"
#include "sadr/common/status.hpp"
#include "sadr/geometry/particles.hpp"

namespace sadr::geometry {

std::size_t ParticleSet::count(Kind k) const {
  return static_cast<std::size_t>(std::count(kind.begin(), kind.end(), k));
}

std::pair<double, int> nearest_surface(const FluidDomain& domain, Vec3 x, double limit) {
  double nearest = std::numeric_limits<double>::infinity();
  int id = -1;
  if (domain.body) {
    nearest = -domain.body->signed_distance_bounded(x, limit);
    id = domain.body_surface_id;
  }
  for (const auto& s : domain.solids) {
    const double d = s.shape->signed_distance_bounded(x, limit);
    if (d < nearest) nearest = d, id = s.surface_id;
  }
  if (nearest <= limit) return {nearest, id};
  return {std::numeric_limits<double>::infinity(), -1};
}

double fluid_signed_distance(const FluidDomain& domain, Vec3 p) {
  double d =
      domain.body ? domain.body->signed_distance(p) : -std::numeric_limits<double>::infinity();
  for (const auto& s : domain.solids) d = std::max(d, -s.shape->signed_distance(p));
  return d;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Site {
  Vec3 x;
  Kind kind;
  int surface;
  double distance;
  Vec3 normal;
};

class Filler {
 public:
  Filler(const FluidDomain& d, const FillOptions& o)
      : d_(d), o_(o), lat_(make_lattice(d.dimension, o.lattice, o.spacing, d.box, o.offset)) {}

  const LatticeCells& lattice() const { return lat_; }

  /// Cells [lo, hi) per axis; appends the sites it keeps to `out`.
  void block(std::array<long, 3> lo, std::array<long, 3> hi, std::vector<Site>& out) const {
    const Vec3 a =
        lat_.origin + Vec3{lo[0] * lat_.cell.x, lo[1] * lat_.cell.y, lo[2] * lat_.cell.z};
    Vec3 b = lat_.origin + Vec3{hi[0] * lat_.cell.x, hi[1] * lat_.cell.y, hi[2] * lat_.cell.z};
    if (d_.dimension == 2) b.z = a.z;
    const Vec3 c = 0.5 * (a + b);
    // Culled blocks hold no wall and no fluid within wall_depth + spacing of a surface.
    const double reach = 0.5 * norm(b - a) + o_.wall_depth + o_.spacing;
    const double body_sd = d_.body ? d_.body->signed_distance_bounded(c, reach) : -kInf;
    bool uniform = std::abs(body_sd) > reach;
    bool in_solid = false;
    for (std::size_t i = 0; uniform && i < d_.solids.size(); ++i) {
      const double s = d_.solids[i].shape->signed_distance_bounded(c, reach);
      uniform = std::abs(s) > reach;
      in_solid = in_solid || s < 0;
    }
    if (uniform) {
      if (body_sd < 0 && !in_solid) all_fluid(lo, hi, out);
      return;
    }
    long widest = 0;
    int axis = 0;
    for (int k = 0; k < d_.dimension; ++k) {
      if (hi[k] - lo[k] > widest) widest = hi[k] - lo[k], axis = k;
    }
    if (widest <= 1) {
      site_by_site(lo, hi, out);
      return;
    }
    auto mid_hi = hi, mid_lo = lo;
    mid_hi[axis] = mid_lo[axis] = lo[axis] + widest / 2;
    block(lo, mid_hi, out);
    block(mid_lo, hi, out);
  }

 private:
  template <class F>
  void for_sites(std::array<long, 3> lo, std::array<long, 3> hi, F&& f) const {
    for (long k = lo[2]; k < hi[2]; ++k) {
      for (long j = lo[1]; j < hi[1]; ++j) {
        for (long i = lo[0]; i < hi[0]; ++i) {
          for (std::size_t s = 0; s < lat_.basis.size(); ++s) {
            const Vec3 x = lat_.site(i, j, k, s);
            if (x.x < d_.box.hi.x && x.y < d_.box.hi.y &&
                (d_.dimension == 2 || x.z < d_.box.hi.z)) {
              f(x);
            }
          }
        }
      }
    }
  }
  void all_fluid(std::array<long, 3> lo, std::array<long, 3> hi, std::vector<Site>& out) const {
    for_sites(lo, hi, [&](Vec3 x) { out.push_back({x, Kind::kFluid, -1, kInf, {}}); });
  }
  void site_by_site(std::array<long, 3> lo, std::array<long, 3> hi, std::vector<Site>& out) const {
    const double depth = o_.wall_depth;
    // Distances beyond depth + spacing are not needed (fluid records +inf there).
    const double limit = depth + o_.spacing;
    for_sites(lo, hi, [&](Vec3 x) {
      const double body_sd = d_.body ? d_.body->signed_distance_bounded(x, limit) : -kInf;
      // Fluid: distance to the nearest surface and its id.
      double nearest = d_.body ? -body_sd : kInf;
      int nearest_id = d_.body ? d_.body_surface_id : -1;
      int solid_in = -1;  // the solid with the shallowest depth containing x
      double solid_depth = kInf;
      for (std::size_t i = 0; i < d_.solids.size(); ++i) {
        const double s = d_.solids[i].shape->signed_distance_bounded(x, limit);
        if (s < 0 && -s < solid_depth) solid_depth = -s, solid_in = static_cast<int>(i);
        if (s < nearest) nearest = s, nearest_id = d_.solids[i].surface_id;
      }
      if (body_sd < 0 && solid_in < 0) {
        if (nearest <= limit) {
          out.push_back({x, Kind::kFluid, nearest_id, nearest, {}});
        } else {
          out.push_back({x, Kind::kFluid, -1, kInf, {}});
        }
        return;
      }
      const bool body_wall = d_.body && body_sd >= 0 && body_sd <= depth;
      const bool solid_wall = solid_in >= 0 && solid_depth <= depth;
      if (!body_wall && !solid_wall) return;
      if (solid_wall && (!body_wall || solid_depth <= body_sd)) {
        const auto& s = d_.solids[solid_in];
        out.push_back({x, Kind::kWall, s.surface_id, solid_depth, s.shape->normal(x)});
      } else {
        out.push_back({x, Kind::kWall, d_.body_surface_id, body_sd, -d_.body->normal(x)});
      }
    });
  }
  const FluidDomain& d_;
  const FillOptions& o_;
  LatticeCells lat_;
};

void check(const FluidDomain& d, const FillOptions& o) {
  if (d.dimension != 2 && d.dimension != 3) {
    throw InvalidArgument("fill: dimension must be 2 or 3, got " + std::to_string(d.dimension));
  }
  if (d.box.empty() || !(d.box.extent().x > 0) || !(d.box.extent().y > 0) ||
      (d.dimension == 3 && !(d.box.extent().z > 0))) {
    throw InvalidArgument("fill: the box must have a positive extent on every axis");
  }
  if (!(o.spacing > 0) || !std::isfinite(o.spacing)) {
    throw InvalidArgument("fill: spacing must be finite and > 0, got " + format_value(o.spacing));
  }
  if (!(o.wall_depth >= 0) || !std::isfinite(o.wall_depth)) {
    throw InvalidArgument("fill: wall_depth must be finite and >= 0, got " +
                          format_value(o.wall_depth));
  }
  const auto check_shape = [&](const ShapePtr& s, const std::string& what) {
    if (!s) throw InvalidArgument("fill: " + what + " is null");
    if (s->dimension() != d.dimension) {
      throw InvalidArgument("fill: " + what + " has dimension " + std::to_string(s->dimension()) +
                            ", the domain " + std::to_string(d.dimension));
    }
    const Aabb b = s->bounds();
    const Aabb both = intersect(b, d.box);
    if (both.empty()) throw InvalidArgument("fill: " + what + " lies entirely outside the box");
  };
  if (d.body) check_shape(d.body, "the body");
  for (std::size_t i = 0; i < d.solids.size(); ++i) {
    check_shape(d.solids[i].shape, "solid " + std::to_string(i));
  }
  const double sites = [&] {
    double v = 1;
    for (int a = 0; a < d.dimension; ++a) v *= d.box.extent()[a] / o.spacing;
    return v;
  }();
  if (sites > 2e9) {
    throw InvalidArgument("fill: the box holds " + format_value(sites) +
                          " lattice sites at this spacing; the limit is 2e9");
  }
}

/// Drops wall sites with no fluid site within wall_depth (fluid far from every surface cannot be
/// that close to a wall, so only the near-surface fluid, distance < inf, is indexed).
void drop_unseen_walls(std::vector<Site>& sites, double depth, int dim) {
  const double cell = std::max(depth, 1e-300);
  const auto key = [&](Vec3 x, int dx, int dy, int dz) {
    const auto c = [&](double v, int o) {
      return static_cast<std::int64_t>(std::floor(v / cell)) + o;
    };
    return (c(x.x, dx) * 73856093) ^ (c(x.y, dy) * 19349663) ^ (c(x.z, dz) * 83492791);
  };
  std::unordered_map<std::int64_t, std::vector<Vec3>> grid;
  for (const auto& s : sites) {
    if (s.kind == Kind::kFluid && s.distance < kInf) grid[key(s.x, 0, 0, 0)].push_back(s.x);
  }
  const int zr = dim == 3 ? 1 : 0;
  std::erase_if(sites, [&](const Site& s) {
    if (s.kind != Kind::kWall) return false;
    for (int dz = -zr; dz <= zr; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = grid.find(key(s.x, dx, dy, dz));
          if (it == grid.end()) continue;
          for (const Vec3& f : it->second) {
            if (norm2(f - s.x) <= depth * depth) return false;
          }
        }
      }
    }
    return true;
  });
}

}  // namespace

ParticleSet fill(const FluidDomain& domain, const FillOptions& options) {
  check(domain, options);
  const Filler filler(domain, options);
  const LatticeCells& lat = filler.lattice();
  constexpr long kBlock = 8;
  std::array<long, 3> nb{};
  for (int a = 0; a < 3; ++a) nb[a] = (lat.n[a] + kBlock - 1) / kBlock;
  const std::size_t blocks = static_cast<std::size_t>(nb[0] * nb[1] * nb[2]);
  std::vector<std::vector<Site>> per_block(blocks);
  parallel_for(blocks, options.threads, [&](std::size_t b) {
    const long bi = static_cast<long>(b) % nb[0], bj = (static_cast<long>(b) / nb[0]) % nb[1];
    const long bk = static_cast<long>(b) / (nb[0] * nb[1]);
    const std::array<long, 3> lo{bi * kBlock, bj * kBlock, bk * kBlock};
    const std::array<long, 3> hi{std::min(lat.n[0], lo[0] + kBlock),
                                 std::min(lat.n[1], lo[1] + kBlock),
                                 std::min(lat.n[2], lo[2] + kBlock)};
    filler.block(lo, hi, per_block[b]);
  });
  std::vector<Site> sites;
  std::size_t total = 0;
  for (const auto& v : per_block) total += v.size();
  sites.reserve(total);
  for (auto& v : per_block) {
    sites.insert(sites.end(), v.begin(), v.end());
    std::vector<Site>().swap(v);
  }
  if (options.wall_depth > 0) drop_unseen_walls(sites, options.wall_depth, domain.dimension);

  ParticleSet p;
  p.dimension = domain.dimension;
  p.spacing = options.spacing;
  const double v0 = std::pow(options.spacing, domain.dimension);
  p.position.reserve(sites.size());
  for (const auto& s : sites) {
    p.position.push_back(s.x);
    p.kind.push_back(s.kind);
    p.surface_id.push_back(s.surface);
    p.distance.push_back(s.distance);
    p.normal.push_back(s.normal);
    p.volume.push_back(v0);
    p.mass.push_back(v0);
  }
  return p;
}

}  // namespace sadr::geometry
