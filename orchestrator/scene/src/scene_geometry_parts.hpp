// SPDX-License-Identifier: MIT
// The scene's geometry section, inside the loader: shapes read from the scene (primitives,
// meshes, transforms, CSG; scene_geometry_shapes.cpp) and what is measured of the particles
// made from them (fluid volume, thin features; scene_geometry_measure.cpp). read_geometry
// (scene_geometry.cpp) joins them.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sadr/geometry/mesh_io.hpp"
#include "sadr/geometry/particles.hpp"
#include "sadr/geometry/shape.hpp"
#include "scene_parts.hpp"
#include "scene_wall_motion.hpp"

namespace sadr::orchestrator::detail {

namespace g = sadr::geometry;

g::Vec3 to_vec(const std::array<double, 3>& a);
/// "(x, y)" or "(x, y, z)", 4 significant digits.
std::string point_text(g::Vec3 p, int d);
g::Aabb box_aabb(const Box& b);

/// One shape read from the scene, and what is known of it.
struct ShapeRead {
  g::ShapePtr shape;
  bool plain_box = false;  ///< an axis-aligned box, translated at most (bounds exact)
  /// A mesh file's shape (transformed at most, not inside CSG): the file, its path, and the
  /// shape's transforms, to place the file's physical groups where the shape is.
  std::shared_ptr<const g::MeshFile> mesh_file;
  std::string mesh_path;
  std::function<g::ShapePtr(g::ShapePtr)> place;
};

/// A fluid or solid body whose shape is a mesh file (ShapeRead::mesh_file): what a boundary
/// flux on one of its physical groups needs (scene_flux_surfaces.cpp).
struct MeshBody {
  std::shared_ptr<const g::MeshFile> file;
  std::string path;
  std::function<g::ShapePtr(g::ShapePtr)> place;  ///< the body's transforms (identity: null)
  g::ShapePtr shape;                              ///< the body as placed
};

/// One physical group of a mesh body's surface (`group: NAME` with `surface: BODY`).
struct SurfaceGroup {
  std::vector<std::uint8_t> part;  ///< per particle: 1 when its nearest surface element is one
                                   ///< of the group's
  std::optional<double> area;      ///< the group's exact area, placed as the body is
  bool inside_box = true;          ///< the group's bounds lie inside the box
};

/// The fluid or solid body of `geometry` that `surface: name` names (scene_surface_groups.cpp);
/// null, with an error at `sf` (the nearest name and the allowed ones; a region body has no
/// surface).
const GeometryBody* surface_body(SceneContext& ctx, const Field& sf, const std::string& name);

/// The particles of kind `kind` (fluid: next to the body; wall: behind it) whose nearest surface
/// element is one of `group`'s: those no farther from the group (placed as the body) than from
/// the body's whole surface, to 1e-6 spacings (a particle as near to two groups, at a corner,
/// belongs to both). Null, with an error at `gf`, when the body is not a mesh or its file has no
/// such group of dimension d - 1 (scene_surface_groups.cpp).
std::optional<SurfaceGroup> read_surface_group(SceneContext& ctx, const Field& gf,
                                               const GeometryBody& body, const std::string& group,
                                               ParticleKind kind);

struct BodyRead {
  std::string name;
  std::string role;
  Field field;
  Field shape_field;
  ShapeRead shape;
  std::string wall_layer, fluid_layer;
  double layer_thickness = 0.0;
  std::vector<ParticleKind> kinds;
  int surface_id = -1;
  std::optional<WallMotion> motion;  ///< solid bodies: the walls' prescribed motion
};

class GeometryReader {
 public:
  GeometryReader(SceneContext& ctx, int d) : ctx_(ctx), r_(ctx.reader), d_(d) {}

  ShapeRead read_shape(const Field& f, int depth);
  std::vector<std::string>& notes() { return notes_; }

 private:
  ShapeRead primitive(const Field& f, std::string_view type);
  ShapeRead mesh(const Field& f);
  ShapeRead transform(const Field& f, ShapeRead s);
  std::optional<std::vector<g::Vec3>> vertices(const Field& f);

  SceneContext& ctx_;
  YamlReader& r_;
  int d_;
  std::map<std::string, std::shared_ptr<const g::MeshFile>> meshes_;
  std::vector<std::string> notes_;
};

/// The fluid volume, where the shapes give it: the body's exact volume (or its clipped box, or
/// the box) minus solids whose bounding boxes lie inside the body and apart from each other.
std::optional<double> exact_fluid_volume(const g::FluidDomain& dom, const ShapeRead* body,
                                         const Box& box);

struct Thin {
  double thickness = std::numeric_limits<double>::infinity();
  g::Vec3 where{};
  std::size_t count = 0;  ///< surface particles where the feature is thinner than h
};

/// Thickness of solids (walls behind a solid's surface, marched into the solid) and of fluid
/// gaps (fluid next to a surface, marched away from it), along the surface normal, from every
/// particle within one spacing of a surface; per surface id.
std::map<int, std::pair<Thin, Thin>> measure_features(const g::ParticleSet& p,
                                                      const g::FluidDomain& dom,
                                                      const std::map<int, g::ShapePtr>& solids,
                                                      double h, double limit);

}  // namespace sadr::orchestrator::detail
