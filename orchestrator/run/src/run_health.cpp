// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/run_health.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "sadr/common/periodic.hpp"
#include "sadr/orchestrator/scene.hpp"
#include "sadr/orchestrator/scene_wall_tangents.hpp"

namespace sadr::orchestrator {
namespace {

using Index = std::array<long, 3>;

/// A cell grid over the particles: on a periodic axis the box in floor(L / s) cells, on the
/// others the particles' extent from their minimum in cells of size s.
struct Grid {
  int d = 3;
  std::array<double, 3> lo{}, cell{1, 1, 1}, len{};
  Index n{1, 1, 1};
  std::array<bool, 3> periodic{};

  [[nodiscard]] std::size_t cells() const {
    return static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) *
           static_cast<std::size_t>(n[2]);
  }
  [[nodiscard]] Index index(const double* x) const {
    Index k{0, 0, 0};
    for (int a = 0; a < d; ++a) {
      const auto ua = static_cast<std::size_t>(a);
      const double v = periodic[ua] ? wrap_into(x[a], lo[ua], lo[ua] + len[ua]) : x[a];
      k[ua] = std::clamp(static_cast<long>(std::floor((v - lo[ua]) / cell[ua])), 0L, n[ua] - 1);
    }
    return k;
  }
  [[nodiscard]] std::size_t flat(const Index& k) const {
    return static_cast<std::size_t>((k[2] * n[1] + k[1]) * n[0] + k[0]);
  }
  /// The neighbour of k shifted by `off` (periodic wrap), or false outside the grid.
  [[nodiscard]] bool shift(Index k, const Index& off, Index& out) const {
    for (std::size_t a = 0; a < 3; ++a) {
      k[a] += off[a];
      if (k[a] < 0 || k[a] >= n[a]) {
        if (!periodic[a] || static_cast<int>(a) >= d) return false;
        k[a] = (k[a] % n[a] + n[a]) % n[a];
      }
    }
    out = k;
    return true;
  }
  [[nodiscard]] double separation(const double* x, const double* y) const {
    double r2 = 0;
    for (int a = 0; a < d; ++a) {
      const auto ua = static_cast<std::size_t>(a);
      double dx = x[a] - y[a];
      if (periodic[ua]) dx = minimum_image(dx, len[ua]);
      r2 += dx * dx;
    }
    return std::sqrt(r2);
  }
};

Grid make_grid(const ParticleState& p, const Box& box, double s) {
  Grid g;
  g.d = box.dimension;
  for (int a = 0; a < g.d; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    g.periodic[ua] = box.periodic[ua];
    if (g.periodic[ua]) {
      g.lo[ua] = box.lo[ua];
      g.len[ua] = box.length(a);
      g.n[ua] = std::max(1L, static_cast<long>(std::floor(g.len[ua] / s)));
      g.cell[ua] = g.len[ua] / static_cast<double>(g.n[ua]);
    } else {
      double lo = 0, hi = 0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double v = p.positions[3 * i + ua];
        lo = i ? std::min(lo, v) : v;
        hi = i ? std::max(hi, v) : v;
      }
      g.lo[ua] = lo;
      g.cell[ua] = s;
      g.n[ua] = static_cast<long>(std::floor((hi - lo) / s)) + 1;
    }
  }
  return g;
}

/// The distinct neighbour offsets of a cell (3^d, fewer on a periodic axis of < 3 cells).
std::vector<Index> neighbour_offsets(const Grid& g) {
  std::vector<Index> out;
  const long r0 = g.d > 0 ? 1 : 0, r1 = g.d > 1 ? 1 : 0, r2 = g.d > 2 ? 1 : 0;
  for (long c = -r2; c <= r2; ++c) {
    for (long b = -r1; b <= r1; ++b) {
      for (long a = -r0; a <= r0; ++a) {
        const Index o{a, b, c};
        bool dup = false;
        for (std::size_t ax = 0; ax < 3; ++ax) {
          // On a periodic axis of 1 or 2 cells, offsets -1 and +1 reach cells 0 already visits.
          if (g.periodic[ax] && o[ax] != 0 && g.n[ax] <= 2 && (g.n[ax] == 1 || o[ax] < 0)) {
            dup = true;
          }
        }
        if (!dup) out.push_back(o);
      }
    }
  }
  return out;
}

/// Particles binned by cell (counting sort).
struct Bins {
  std::vector<std::size_t> start, items;
};
Bins bin(const Grid& g, const ParticleState& p, const std::vector<std::size_t>& which) {
  Bins b;
  b.start.assign(g.cells() + 1, 0);
  std::vector<std::size_t> cell(which.size());
  for (std::size_t k = 0; k < which.size(); ++k) {
    cell[k] = g.flat(g.index(&p.positions[3 * which[k]]));
    ++b.start[cell[k] + 1];
  }
  for (std::size_t c = 0; c < g.cells(); ++c) b.start[c + 1] += b.start[c];
  b.items.resize(which.size());
  std::vector<std::size_t> fill(b.start.begin(), b.start.end() - 1);
  for (std::size_t k = 0; k < which.size(); ++k) b.items[fill[cell[k]]++] = which[k];
  return b;
}

constexpr std::size_t kMaxCells = std::size_t{1} << 26;

/// A grid of cell size >= s with at most kMaxCells cells (doubling s).
Grid bounded_grid(const ParticleState& p, const Box& box, double s) {
  Grid g = make_grid(p, box, s);
  while (g.cells() > kMaxCells) {
    s *= 2;
    g = make_grid(p, box, s);
  }
  return g;
}

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

std::string point(const std::array<double, 3>& x, int d) {
  std::string s = "(";
  for (int a = 0; a < d; ++a) s += (a ? ", " : "") + fmt(x[static_cast<std::size_t>(a)]);
  return s + ")";
}

nlohmann::json place_json(const HealthPlace& p) {
  return {{"id", p.id}, {"x", p.x}, {"time", p.time}, {"frame", p.frame}, {"value", p.value}};
}

}  // namespace

HealthContext health_context(const Scene& s) {
  HealthContext c;
  c.box = s.box;
  c.spacing = s.lattice_spacing;
  c.support = s.fluid.smoothing_length;
  c.reference_density = s.fluid.reference_density;
  c.from_scene = true;
  for (const WallPlane& w : s.fluid.wall_planes) {
    HealthContext::Surface sf;
    sf.region = w.region;
    sf.surface.point = w.point;
    sf.surface.inward_normal = w.normal;
    sf.surface.radius = w.radius;
    if (const Region* r = s.find_region(w.region)) {
      for (const std::uint32_t i : r->particles) {
        if (s.particles.kind(i) == ParticleKind::kWall) sf.wall_ids.push_back(i);
      }
    }
    c.surfaces.push_back(std::move(sf));
  }
  c.tangents = scene_wall_tangents(s);
  // A turning body's tangent planes turn with it: each frame turns their normals to its time.
  if (s.geometry && !c.tangents.empty()) {
    std::vector<int> body_of(s.particles.size(), -1);
    for (const auto& b : s.geometry->bodies) {
      if (!b.moving || b.moving->angular_velocity == 0.0) continue;
      const Region* r = s.find_region(b.name);
      if (!r) continue;
      for (const std::uint32_t i : r->particles) body_of[i] = static_cast<int>(c.turning.size());
      c.turning.push_back(*b.moving);
    }
    if (!c.turning.empty()) {
      c.tangent_turns.resize(c.tangents.size());
      for (std::size_t k = 0; k < c.tangents.size(); ++k) {
        c.tangent_turns[k] = body_of[c.tangents.particles[k]];
      }
    }
  }
  for (const Species& sp : s.species) {
    HealthContext::SpeciesInfo info;
    info.name = sp.name;
    info.stochastic = sp.stochastic;
    for (const Reaction& r : s.reactions) {
      long net = 0;
      for (const auto& e : r.products) net += e.species == sp.name ? long{e.count} : 0;
      for (const auto& e : r.reactants) net -= e.species == sp.name ? long{e.count} : 0;
      if (net == 0) continue;
      if (r.boundary_particles.empty()) {
        info.reactions.push_back(r.name);
      } else {
        info.boundaries.push_back("boundary flux " + r.name);
      }
    }
    for (const SpeciesBoundary& b : sp.boundaries) {
      if (b.condition == BoundaryCondition::kDirichlet ||
          b.condition == BoundaryCondition::kNeumann || b.condition == BoundaryCondition::kInflow) {
        info.boundaries.push_back(b.region + ": " + std::string(to_string(b.condition)));
      }
    }
    if (s.fluid.open_boundary) info.boundaries.emplace_back("open boundary");
    c.species.push_back(std::move(info));
  }
  c.species_known = true;
  return c;
}

double estimate_spacing(const ParticleState& p, const Box& box) {
  const std::size_t n = p.size();
  if (n < 2) return 0;
  const int d = box.dimension;
  double volume = 1;
  for (int a = 0; a < d; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    double lo = p.positions[ua], hi = lo;
    for (std::size_t i = 1; i < n; ++i) {
      lo = std::min(lo, p.positions[3 * i + ua]);
      hi = std::max(hi, p.positions[3 * i + ua]);
    }
    volume *= box.periodic[ua] ? box.length(a) : std::max(hi - lo, 1e-300);
  }
  const double guess = 2 * std::pow(volume / static_cast<double>(n), 1.0 / d);
  const Grid g = bounded_grid(p, box, guess);
  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  const Bins b = bin(g, p, all);
  const auto offsets = neighbour_offsets(g);
  std::vector<double> nearest;
  for (std::size_t i = 0; i < n; ++i) {
    double best = -1;
    const Index k = g.index(&p.positions[3 * i]);
    for (const Index& o : offsets) {
      Index m;
      if (!g.shift(k, o, m)) continue;
      const std::size_t c = g.flat(m);
      for (std::size_t q = b.start[c]; q < b.start[c + 1]; ++q) {
        const std::size_t j = b.items[q];
        if (j == i) continue;
        const double r = g.separation(&p.positions[3 * i], &p.positions[3 * j]);
        if (best < 0 || r < best) best = r;
      }
    }
    if (best > 0) nearest.push_back(best);
  }
  if (nearest.empty()) return 0;
  std::nth_element(nearest.begin(), nearest.begin() + static_cast<long>(nearest.size() / 2),
                   nearest.end());
  return nearest[nearest.size() / 2];
}

PenetrationResult find_wall_penetration(const ParticleState& p, const HealthContext& c) {
  PenetrationResult res;
  const double dx = c.spacing;
  const double h = c.support > 0 ? c.support : 2 * dx;
  if (!(dx > 0)) return res;
  // Wall particles tagged with their surface (-1: none, the dx/2 test).
  std::map<std::uint64_t, int> surface_of;
  for (std::size_t s = 0; s < c.surfaces.size(); ++s) {
    for (const auto id : c.surfaces[s].wall_ids) surface_of.emplace(id, static_cast<int>(s));
  }
  // Wall particles with a tangent plane (tangent_of: its entry in c.tangents, -1: none).
  std::map<std::uint64_t, int> tangent_index;
  for (std::size_t k = 0; k < c.tangents.size(); ++k) {
    tangent_index.emplace(c.tangents.particles[k], static_cast<int>(k));
  }
  std::vector<std::size_t> walls, fluid;
  std::vector<int> tag(p.size(), -1), tangent_of(p.size(), -1);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) == ParticleKind::kWall) {
      walls.push_back(i);
      const std::uint64_t id = p.ids.empty() ? i : p.ids[i];
      const auto it = surface_of.find(id);
      if (it != surface_of.end()) tag[i] = it->second;
      const auto t = tangent_index.find(id);
      if (t != tangent_index.end()) tangent_of[i] = t->second;
    } else if (p.kind(i) == ParticleKind::kFluid) {
      fluid.push_back(i);
    }
  }
  if (fluid.empty()) return res;
  const Grid g = bounded_grid(p, c.box, std::max(h, dx));
  const Bins b = bin(g, p, walls);
  const auto offsets = neighbour_offsets(g);
  std::vector<char> near(c.surfaces.size());
  for (const std::size_t i : fluid) {
    const double* x = &p.positions[3 * i];
    std::fill(near.begin(), near.end(), 0);
    double depth = 0;
    double foot_best = h;      // the tangent wall particle whose closest surface point is nearest
    double tangent_depth = 0;  // how far past that particle's tangent plane
    const Index k = g.index(x);
    for (const Index& o : offsets) {
      Index m;
      if (!g.shift(k, o, m)) continue;
      const std::size_t cell = g.flat(m);
      for (std::size_t q = b.start[cell]; q < b.start[cell + 1]; ++q) {
        const std::size_t j = b.items[q];
        const double r = g.separation(x, &p.positions[3 * j]);
        if (tangent_of[j] >= 0) {
          if (r >= h) continue;
          const auto t = static_cast<std::size_t>(tangent_of[j]);
          double rij[3] = {0, 0, 0}, foot2 = 0;
          for (int a = 0; a < g.d; ++a) {
            const auto ua = static_cast<std::size_t>(a);
            rij[ua] = x[ua] - p.positions[3 * j + ua];
            if (g.periodic[ua]) rij[ua] = minimum_image(rij[ua], g.len[ua]);
            const double f = rij[ua] - c.tangents.depths[t] * c.tangents.normals[3 * t + ua];
            foot2 += f * f;
          }
          const double foot = std::sqrt(foot2);
          if (foot < foot_best) {
            foot_best = foot;
            tangent_depth = -c.tangents.signed_distance(t, rij);
          }
          continue;
        }
        if (tag[j] < 0) {
          if (r < 0.5 * dx) depth = std::max(depth, 0.5 * dx - r);
        } else if (r < h) {
          near[static_cast<std::size_t>(tag[j])] = 1;
        }
      }
    }
    if (tangent_depth > kHealthTangentSlack * dx) depth = std::max(depth, tangent_depth);
    for (std::size_t s = 0; s < c.surfaces.size(); ++s) {
      // A plane counts near its region's wall particles; a circle or sphere everywhere.
      if (!near[s] && !(c.surfaces[s].surface.radius > 0)) continue;
      depth = std::max(depth, -c.surfaces[s].surface.signed_distance(x));
    }
    if (depth > 0) {
      ++res.count;
      if (!res.worst.found || depth > res.worst.value) {
        res.worst.found = true;
        res.worst.value = depth;
        res.worst.id = p.ids.empty() ? i : p.ids[i];
        res.worst.x = {x[0], x[1], x[2]};
      }
    }
  }
  return res;
}

HoleResult find_holes(const ParticleState& p, const HealthContext& c) {
  HoleResult res;
  const double dx = c.spacing;
  const double h = c.support > 0 ? c.support : 2 * dx;
  if (!(h > 0) || p.size() == 0) return res;
  const Grid g = make_grid(p, c.box, h);
  res.cell = g.cell[0];
  if (g.cells() > kMaxCells) {
    res.checked = false;
    return res;
  }
  std::vector<std::uint32_t> count(g.cells(), 0);
  std::vector<char> fluid(g.cells(), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t cell = g.flat(g.index(&p.positions[3 * i]));
    ++count[cell];
    if (p.kind(i) == ParticleKind::kFluid) fluid[cell] = 1;
  }
  std::vector<Index> faces;
  for (int a = 0; a < g.d; ++a) {
    Index o{0, 0, 0};
    o[static_cast<std::size_t>(a)] = -1;
    faces.push_back(o);
    o[static_cast<std::size_t>(a)] = 1;
    faces.push_back(o);
  }
  std::vector<char> seen(g.cells(), 0);
  std::vector<Index> stack;
  for (long z = 0; z < g.n[2]; ++z) {
    for (long y = 0; y < g.n[1]; ++y) {
      for (long x = 0; x < g.n[0]; ++x) {
        const Index start{x, y, z};
        const std::size_t s = g.flat(start);
        if (count[s] || seen[s]) continue;
        seen[s] = 1;
        stack.assign(1, start);
        std::size_t cells = 0, border = 0, border_fluid = 0;
        bool edge = false;
        std::array<double, 3> centre{};
        while (!stack.empty()) {
          const Index k = stack.back();
          stack.pop_back();
          ++cells;
          for (std::size_t a = 0; a < 3; ++a) {
            centre[a] += g.lo[a] + (static_cast<double>(k[a]) + 0.5) * g.cell[a];
          }
          for (const Index& o : faces) {
            Index m;
            if (!g.shift(k, o, m)) {
              edge = true;
              continue;
            }
            const std::size_t f = g.flat(m);
            if (count[f]) {
              ++border;
              border_fluid += fluid[f] ? 1 : 0;
            } else if (!seen[f]) {
              seen[f] = 1;
              stack.push_back(m);
            }
          }
        }
        if (edge || border == 0 || 2 * border_fluid < border) continue;
        ++res.count;
        if (cells > res.largest) {
          res.largest = cells;
          for (std::size_t a = 0; a < 3; ++a) {
            res.centre[a] = static_cast<int>(a) < g.d ? centre[a] / static_cast<double>(cells) : 0;
          }
        }
      }
    }
  }
  return res;
}

DensityResult density_deviation(const ParticleState& p, double reference_density) {
  DensityResult res;
  double sum2 = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) != ParticleKind::kFluid) continue;
    const double dev = p.densities[i] / reference_density - 1;
    ++res.fluid;
    sum2 += dev * dev;
    if (res.fluid == 1 || std::abs(dev) > res.max) {
      res.max = std::abs(dev);
      res.max_id = p.ids.empty() ? i : p.ids[i];
      res.max_x = {p.positions[3 * i], p.positions[3 * i + 1], p.positions[3 * i + 2]};
    }
  }
  if (res.fluid) res.rms = std::sqrt(sum2 / static_cast<double>(res.fluid));
  return res;
}

void HealthCheck::add_frame(const ParticleState& p, std::span<const SpeciesColumn> species,
                            double time, const std::string& frame, std::size_t run) {
  if (frames_ == 0) {
    if (!c_.from_scene) {  // the dimension: the last axis with a non-zero coordinate
      c_.box.dimension = 1;
      for (std::size_t i = 0; i < p.size(); ++i) {
        for (int a = 2; a >= c_.box.dimension; --a) {
          if (p.positions[3 * i + static_cast<std::size_t>(a)] != 0) c_.box.dimension = a + 1;
        }
      }
    }
    if (!(c_.spacing > 0)) c_.spacing = estimate_spacing(p, c_.box);
    if (!(c_.support > 0)) c_.support = 2 * c_.spacing;
    if (!(c_.rest_density > 0)) {
      std::vector<double> rho;
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.kind(i) == ParticleKind::kFluid) rho.push_back(p.densities[i]);
      }
      if (!rho.empty()) {
        std::nth_element(rho.begin(), rho.begin() + static_cast<long>(rho.size() / 2), rho.end());
        c_.rest_density = rho[rho.size() / 2];
      }
    }
  }
  ++frames_;
  const auto at = [&](HealthPlace& place, double value, std::uint64_t id,
                      const std::array<double, 3>& x) {
    place = {id, x, time, frame, value, true};
  };
  PenetrationResult pen;
  if (c_.tangent_turns.empty()) {
    pen = find_wall_penetration(p, c_);
  } else {  // turning bodies: their tangent planes at this frame's time
    HealthContext turned = c_;
    for (std::size_t k = 0; k < turned.tangent_turns.size(); ++k) {
      if (turned.tangent_turns[k] < 0) continue;
      const RigidMotion& m = turned.turning[static_cast<std::size_t>(turned.tangent_turns[k])];
      const std::array<double, 3> n = m.rotate(&c_.tangents.normals[3 * k], time);
      for (std::size_t a = 0; a < 3; ++a) turned.tangents.normals[3 * k + a] = n[a];
    }
    pen = find_wall_penetration(p, turned);
  }
  penetration_last = pen.count;
  if (pen.count) ++penetration_frames;
  if (pen.count > penetration_max) {
    penetration_max = pen.count;
    penetration_max_time = time;
  }
  if (pen.worst.found && (!penetration_worst.found || pen.worst.value > penetration_worst.value)) {
    at(penetration_worst, pen.worst.value, pen.worst.id, pen.worst.x);
  }
  const HoleResult holes = find_holes(p, c_);
  holes_checked = holes_checked && holes.checked;
  hole_cell = holes.cell;
  holes_last = holes.count;
  if (holes.count) ++hole_frames;
  if (holes.count > holes_max) {
    holes_max = holes.count;
    holes_max_time = time;
  }
  if (holes.largest > hole_largest) {
    hole_largest = holes.largest;
    at(hole_worst, static_cast<double>(holes.largest), 0, holes.centre);
  }
  if (c_.rest_density > 0) {
    const DensityResult rho = density_deviation(p, c_.rest_density);
    if (rho.fluid) {
      if (!density_worst.found || rho.max > density_worst.value) {
        at(density_worst, rho.max, rho.max_id, rho.max_x);
      }
      density_rms_last = rho.rms;
      if (rho.rms >= density_rms_max) {
        density_rms_max = rho.rms;
        density_rms_max_time = time;
      }
    }
  }
  if (runs_.size() <= run) runs_.resize(run + 1);
  RunTotals& t = runs_[run];
  std::vector<double> totals;
  std::vector<std::string> names;
  for (const SpeciesColumn& col : species) {
    const auto info = std::find_if(c_.species.begin(), c_.species.end(),
                                   [&](const auto& s) { return s.name == col.name; });
    if (c_.species_known && info == c_.species.end()) continue;  // an assigned species
    const bool amount = info != c_.species.end() && !info->stochastic;
    double sum = 0;
    for (std::size_t i = 0; i < col.values.size() && i < p.size(); ++i) {
      sum += amount ? col.values[i] * p.volume(i) : col.values[i];
    }
    names.push_back(col.name);
    totals.push_back(sum);
  }
  if (!t.any) {
    t.any = true;
    t.names = names;
    t.first = totals;
    t.first_time = time;
  }
  if (names == t.names) {
    t.last = totals;
    t.last_time = time;
  }
}

std::vector<SpeciesBudget> HealthCheck::budgets() const {
  std::vector<SpeciesBudget> out;
  if (runs_.empty() || !runs_.front().any) return out;
  for (std::size_t k = 0; k < runs_.front().names.size(); ++k) {
    SpeciesBudget b;
    b.name = runs_.front().names[k];
    const auto info = std::find_if(c_.species.begin(), c_.species.end(),
                                   [&](const auto& s) { return s.name == b.name; });
    b.known = c_.species_known && info != c_.species.end();
    b.amount = info != c_.species.end() && !info->stochastic;
    b.first = runs_.front().first[k];
    b.last = runs_.front().last[k];
    b.first_time = runs_.front().first_time;
    b.last_time = runs_.front().last_time;
    if (!b.known) {
      b.verdict = "unknown";
    } else {
      b.reactions = info->reactions;
      b.boundaries = info->boundaries;
      b.verdict = b.reactions.empty() ? (b.boundaries.empty() ? "conserved" : "boundaries")
                                      : (b.boundaries.empty() ? "reactions" : "both");
    }
    if (b.verdict == "conserved") {
      for (const RunTotals& r : runs_) {
        if (!r.any || k >= r.first.size()) continue;
        const double change = std::abs(r.last[k] - r.first[k]);
        const double scale = std::max(std::abs(r.first[k]), std::abs(r.last[k]));
        b.warning = b.warning || (b.amount ? change > kHealthAmountRelWarn * scale : change > 0);
      }
    }
    out.push_back(std::move(b));
  }
  return out;
}

std::vector<std::string> HealthCheck::warnings() const {
  std::vector<std::string> w;
  if (penetration_max >= kHealthPenetrationWarn) {
    w.push_back("fluid particles inside walls at " + std::to_string(penetration_frames) +
                " checked frame(s), up to " + std::to_string(penetration_max) +
                " (threshold: any)");
  }
  if (holes_max >= kHealthHoleWarn) {
    w.push_back("empty holes larger than the kernel support at " + std::to_string(hole_frames) +
                " checked frame(s), up to " + std::to_string(holes_max) + " (threshold: any)");
  }
  if (density_worst.found && density_worst.value > kHealthDensityMaxWarn) {
    w.push_back("max |rho/rho0 - 1| = " + fmt(density_worst.value) + " > " +
                fmt(kHealthDensityMaxWarn));
  }
  if (density_rms_max > kHealthDensityRmsWarn) {
    w.push_back("RMS of rho/rho0 - 1 = " + fmt(density_rms_max) + " > " +
                fmt(kHealthDensityRmsWarn) + " at t = " + fmt(density_rms_max_time));
  }
  for (const SpeciesBudget& b : budgets()) {
    if (b.warning) {
      w.push_back("species " + b.name +
                  ": its total changed, but no reaction or boundary creates or removes it");
    }
  }
  return w;
}

std::vector<std::string> HealthCheck::lines() const {
  std::vector<std::string> out;
  const int d = c_.box.dimension;
  out.push_back("health (" + std::to_string(frames_) +
                " frame(s) checked; dx = " + fmt(c_.spacing) + ", h = " + fmt(c_.support) +
                (c_.from_scene ? " from the scene" : " estimated from the first frame") +
                "; rho0 = " + fmt(c_.rest_density) +
                ", the median fluid density at the first frame" +
                (c_.reference_density > 0 && c_.reference_density != c_.rest_density
                     ? " (fluid.reference_density = " + fmt(c_.reference_density) + ")"
                     : "") +
                "):");
  std::string tests;
  for (const auto& s : c_.surfaces) tests += (tests.empty() ? "" : ", ") + s.region;
  tests = tests.empty() ? "wall particles closer than dx/2"
                        : "past the wall_planes of " + tests + "; other walls: closer than dx/2";
  if (!c_.tangents.empty()) {
    tests = "past the tangent plane of the nearest wall particle by more than " +
            fmt(kHealthTangentSlack) + " dx";
  }
  if (penetration_max == 0) {
    out.push_back("  fluid inside walls: none (" + tests + ")");
  } else {
    const HealthPlace& w = penetration_worst;
    out.push_back("  fluid inside walls: up to " + std::to_string(penetration_max) +
                  " (t = " + fmt(penetration_max_time) + "), " + std::to_string(penetration_last) +
                  " at the last frame (" + tests + ")");
    out.push_back("    deepest: particle " + std::to_string(w.id) + " at " + point(w.x, d) + ", " +
                  fmt(w.value) + " past the surface, t = " + fmt(w.time) + " (" + w.frame + ")");
  }
  const std::string cells = "cells of " + fmt(hole_cell) + " >= h";
  if (!holes_checked) {
    out.push_back("  empty holes: not checked (the grid of cells of size h is too large)");
  } else if (holes_max == 0) {
    out.push_back("  empty holes: none (" + cells + ")");
  } else {
    const HealthPlace& w = hole_worst;
    out.push_back("  empty holes: up to " + std::to_string(holes_max) +
                  " (t = " + fmt(holes_max_time) + "), " + std::to_string(holes_last) +
                  " at the last frame (" + cells + ")");
    out.push_back("    largest: " + std::to_string(hole_largest) + " empty cell(s), volume " +
                  fmt(static_cast<double>(hole_largest) * std::pow(hole_cell, d)) + ", around " +
                  point(w.x, d) + ", t = " + fmt(w.time) + " (" + w.frame + ")");
  }
  if (density_worst.found) {
    const HealthPlace& w = density_worst;
    out.push_back("  density |rho/rho0 - 1|: max " + fmt(w.value) + " (particle " +
                  std::to_string(w.id) + " at " + point(w.x, d) + ", t = " + fmt(w.time) +
                  "), RMS " + fmt(density_rms_last) + " at the last frame, up to " +
                  fmt(density_rms_max) + " (t = " + fmt(density_rms_max_time) + ")");
  } else {
    out.push_back("  density |rho/rho0 - 1|: no fluid particles");
  }
  const auto budgets_now = budgets();
  if (!budgets_now.empty()) {
    out.push_back("  species, first -> last frame (t = " + fmt(budgets_now.front().first_time) +
                  " -> " + fmt(budgets_now.front().last_time) + ")" +
                  (runs_.size() > 1 ? " of the first run (WARNINGs: of every run)" : "") +
                  ", what can change the total:");
  }
  for (const SpeciesBudget& b : budgets_now) {
    const double change = b.last - b.first;
    std::string what;
    const auto list = [](const std::vector<std::string>& v) {
      std::string s;
      for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
      return s;
    };
    if (b.verdict == "conserved") {
      what = "nothing: no reaction or boundary changes it";
    } else if (b.verdict == "boundaries") {
      what = "boundaries only (" + list(b.boundaries) + "): " + fmt(change) +
             (change >= 0 ? " created" : " removed") + " by them";
    } else if (b.verdict == "reactions") {
      what = "reactions only (" + list(b.reactions) + ")";
    } else if (b.verdict == "both") {
      what = "reactions (" + list(b.reactions) + ") and boundaries (" + list(b.boundaries) +
             "): not separable from the frames";
    } else {
      what = "unknown (the scene could not be read)";
    }
    out.push_back("    " + b.name + (b.amount ? " (amount)" : "") + ": " + fmt(b.first) + " -> " +
                  fmt(b.last) + " (" + (change >= 0 ? "+" : "") + fmt(change) + "); " + what);
  }
  const auto w = warnings();
  for (const auto& line : w) out.push_back("  WARNING: " + line);
  if (w.empty()) out.push_back("  no warnings");
  return out;
}

nlohmann::json HealthCheck::report() const {
  nlohmann::json species = nlohmann::json::array();
  for (const SpeciesBudget& b : budgets()) {
    species.push_back({{"name", b.name},
                       {"amount", b.amount},
                       {"first", b.first},
                       {"last", b.last},
                       {"reactions", b.reactions},
                       {"boundaries", b.boundaries},
                       {"verdict", b.verdict},
                       {"warning", b.warning}});
  }
  return {
      {"frames", frames_},
      {"context",
       {{"spacing", c_.spacing},
        {"support", c_.support},
        {"reference_density", c_.reference_density},
        {"rest_density", c_.rest_density},
        {"from_scene", c_.from_scene}}},
      {"penetration",
       {{"frames", penetration_frames},
        {"max", penetration_max},
        {"last", penetration_last},
        {"worst", place_json(penetration_worst)}}},
      {"holes",
       {{"checked", holes_checked},
        {"cell", hole_cell},
        {"frames", hole_frames},
        {"max", holes_max},
        {"last", holes_last},
        {"largest_cells", hole_largest},
        {"largest", place_json(hole_worst)}}},
      {"density",
       {{"max", place_json(density_worst)},
        {"rms_last", density_rms_last},
        {"rms_max", density_rms_max}}},
      {"species", species},
      {"warnings", warnings()},
  };
}

}  // namespace sadr::orchestrator
