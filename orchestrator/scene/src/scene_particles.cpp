// SPDX-License-Identifier: MIT
// Scene sections "regions" and "particles": shapes, lattice generation,
// particle CSV files, and region membership.
#include <array>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {

constexpr std::array<std::string_view, 6> kShapes{"box",     "sphere",  "disk",
                                                  "annulus", "channel", "ids"};
constexpr std::array<std::string_view, 11> kRegionKeys{
    "name",         "shape",        "lower", "upper", "center", "radius",
    "inner_radius", "outer_radius", "axis",  "kinds", "ids"};
constexpr std::array<std::string_view, 4> kParticleKinds{"fluid", "wall", "inlet", "outlet"};
constexpr std::array<std::string_view, 3> kAxisNames{"x", "y", "z"};

std::vector<std::string_view> shape_keys(RegionShape shape) {
  switch (shape) {
    case RegionShape::kBox:
      return {"lower", "upper"};
    case RegionShape::kSphere:
      return {"center", "radius"};
    case RegionShape::kAnnulus:
      return {"center", "inner_radius", "outer_radius"};
    case RegionShape::kChannel:
      return {"axis", "lower", "upper"};
    case RegionShape::kIds:
      return {"ids"};
    case RegionShape::kAll:
      break;
  }
  return {};
}

/// `ids`: a non-empty list of distinct whole numbers (particle ids = particle
/// CSV rows or lattice order); checked against the particle count later.
void read_region_ids(SceneContext& ctx, const Field& f, Region& rg) {
  YamlReader& r = ctx.reader;
  const Field list = YamlReader::child(f, "ids");
  if (!YamlReader::present(list)) {
    r.error(list, "missing; required for shape 'ids': a list of particle ids, e.g. [0, 4, 7]");
    return;
  }
  if (!list.node.IsSequence() || list.node.size() == 0) {
    r.error(list, "expected a non-empty list of particle ids (whole numbers >= 0), e.g. [0, 4, 7]");
    return;
  }
  std::set<std::uint32_t> seen;
  for (std::size_t i = 0; i < list.node.size(); ++i) {
    const Field e = YamlReader::element(list, i);
    const auto v = r.number_at(e, Bound::kNonNegative, "particle id");
    if (!v) continue;
    if (*v != std::floor(*v) || *v > 4294967295.0) {
      r.error(e, format_number(*v) + " is not a particle id; allowed: a whole number in [0, 2^32)");
    } else if (!seen.insert(static_cast<std::uint32_t>(*v)).second) {
      r.error(e, "particle id " + format_number(*v) + " is listed twice");
    }
  }
  rg.ids.assign(seen.begin(), seen.end());
  ctx.id_regions.emplace_back(ctx.scene.regions.size(), list);
}

void read_region_shape(SceneContext& ctx, const Field& f, Region& rg) {
  YamlReader& r = ctx.reader;
  const int d = ctx.scene.box.dimension;
  // Keys that belong to another shape are errors, not silently ignored.
  const auto keys = shape_keys(rg.shape);
  for (const auto& k : kRegionKeys) {
    if (k == "name" || k == "shape" || k == "kinds") continue;
    const Field c = YamlReader::child(f, k);
    if (YamlReader::present(c) && std::find(keys.begin(), keys.end(), k) == keys.end()) {
      r.error(c, "key '" + std::string(k) + "' does not apply to shape '" +
                     std::string(to_string(rg.shape)) + "' (its keys: " + join_names(keys) + ")");
    }
  }
  switch (rg.shape) {
    case RegionShape::kBox: {
      const auto lo = r.vector(f, "lower", d, "length", true);
      const auto hi = r.vector(f, "upper", d, "length", true);
      if (lo && hi) {
        rg.lower = *lo;
        rg.upper = *hi;
        for (int a = 0; a < d; ++a) {
          const auto ua = static_cast<std::size_t>(a);
          if (rg.upper[ua] < rg.lower[ua]) {
            r.error(YamlReader::child(f, "upper"),
                    "axis " + std::to_string(a) + ": upper " + format_number(rg.upper[ua]) +
                        " is below lower " + format_number(rg.lower[ua]) +
                        "; allowed: upper >= lower");
          }
        }
      }
      break;
    }
    case RegionShape::kSphere:
      if (auto c = r.vector(f, "center", d, "length", true)) rg.center = *c;
      rg.radius = r.number(f, "radius", Bound::kPositive, "length", true).value_or(0.0);
      break;
    case RegionShape::kAnnulus: {
      if (auto c = r.vector(f, "center", d, "length", true)) rg.center = *c;
      rg.inner_radius =
          r.number(f, "inner_radius", Bound::kNonNegative, "length", true).value_or(0.0);
      const auto outer = r.number(f, "outer_radius", Bound::kPositive, "length", true);
      rg.radius = outer.value_or(0.0);
      if (outer && !(rg.radius > rg.inner_radius)) {
        r.error(YamlReader::child(f, "outer_radius"),
                format_number(rg.radius) +
                    " is not allowed; allowed: outer_radius > inner_radius (" +
                    format_number(rg.inner_radius) + ")");
      }
      break;
    }
    case RegionShape::kChannel: {
      const std::span<const std::string_view> axes(kAxisNames.data(), static_cast<std::size_t>(d));
      if (auto ax = r.choice(f, "axis", axes, true, "axis")) {
        rg.axis = static_cast<int>(std::find(axes.begin(), axes.end(), *ax) - axes.begin());
      }
      const auto lo = r.number(f, "lower", Bound::kAny, "length", true);
      const auto hi = r.number(f, "upper", Bound::kAny, "length", true);
      rg.axis_lower = lo.value_or(0.0);
      rg.axis_upper = hi.value_or(0.0);
      if (lo && hi && *hi < *lo) {
        r.error(YamlReader::child(f, "upper"), format_number(*hi) + " is below lower " +
                                                   format_number(*lo) +
                                                   "; allowed: upper >= lower");
      }
      break;
    }
    case RegionShape::kIds:
      read_region_ids(ctx, f, rg);
      break;
    case RegionShape::kAll:
      break;
  }
}

}  // namespace

void read_regions(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  ctx.all_region.name = std::string(kAllRegion);
  ctx.all_region.shape = RegionShape::kAll;
  const Field list = YamlReader::child(root, "regions");
  if (!r.expect_sequence(list)) return;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.node.size(); ++i) {
    const Field f = YamlReader::element(list, i);
    if (!r.expect_map(f, kRegionKeys)) continue;
    Region rg;
    rg.name = r.string(f, "name", true).value_or("");
    const Field nf = YamlReader::child(f, "name");
    if (!rg.name.empty()) {
      if (!valid_identifier(rg.name)) {
        r.error(nf, "'" + rg.name + "' is not a valid name; allowed: [A-Za-z_][A-Za-z0-9_]*");
      } else if (rg.name == kAllRegion) {
        r.error(nf, "'all' is the built-in region (every particle) and cannot be redefined");
      } else if (!names.insert(rg.name).second) {
        r.error(nf, "region name '" + rg.name + "' is already used; region names must be unique");
      }
    }
    // A region with a bad shape is still recorded so that references to it
    // do not produce a second, misleading "unknown region" error.
    const auto shape = r.choice(f, "shape", kShapes, true, "shape");
    rg.shape = !shape                ? RegionShape::kAll
               : *shape == "box"     ? RegionShape::kBox
               : *shape == "annulus" ? RegionShape::kAnnulus
               : *shape == "channel" ? RegionShape::kChannel
               : *shape == "ids"     ? RegionShape::kIds
                                     : RegionShape::kSphere;
    if (auto kinds = r.string_list(f, "kinds", false)) {
      for (const auto& k : *kinds) {
        if (auto kind = parse_kind(k)) {
          rg.kinds.push_back(*kind);
        } else {
          r.error(YamlReader::child(f, "kinds"), "unknown particle kind '" + k + "' (allowed: " +
                                                     join_names(kParticleKinds) + ")");
        }
      }
    }
    if (shape && (ctx.geometry_ok || rg.shape == RegionShape::kIds)) read_region_shape(ctx, f, rg);
    ctx.scene.regions.push_back(std::move(rg));
  }
}

const Region* lookup_region(SceneContext& ctx, const Field& where, const std::string& name) {
  if (name == kAllRegion) return &ctx.all_region;
  // The walls behind a surface or a group that a species boundary names ("BODY/NAME",
  // scene_chemistry.cpp) are regions of the scene that the file cannot name.
  const Region* found = ctx.scene.find_region(name);
  if (found && valid_identifier(name)) return found;
  std::vector<std::string_view> known{kAllRegion};
  for (const auto& rg : ctx.scene.regions) {
    if (valid_identifier(rg.name)) known.push_back(rg.name);
  }
  std::string msg = "unknown region '" + name + "'";
  if (auto near = nearest_name(name, known)) msg += "; did you mean '" + *near + "'?";
  msg += " (defined: " + join_names(known) + ")";
  ctx.reader.error(where, msg);
  return nullptr;
}

}  // namespace sadr::orchestrator::detail
