// SPDX-License-Identifier: MIT
#include <cmath>
#include <limits>
#include <string>

#include "bvh.hpp"
#include "sadr/common/status.hpp"
#include "sadr/geometry/mesh.hpp"

namespace sadr::geometry {

void validate(const SurfaceMesh& m) {
  const std::string src = m.source.empty() ? std::string("<mesh>") : m.source;
  if (m.dimension != 2 && m.dimension != 3) {
    throw InvalidArgument(src + ": mesh dimension must be 2 or 3, got " +
                          std::to_string(m.dimension));
  }
  if (m.size() == 0) {
    throw InvalidArgument(src + ": empty mesh (no " +
                          std::string(m.dimension == 3 ? "triangles" : "segments") + ")");
  }
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    if (!all_finite(m.vertices[i])) {
      throw InvalidArgument(src + ": vertex " + std::to_string(i) + " is not finite (" +
                            format_value(m.vertices[i].x) + ", " + format_value(m.vertices[i].y) +
                            ", " + format_value(m.vertices[i].z) + ")");
    }
  }
  const auto check = [&](auto const& elems, const char* kind) {
    for (std::size_t e = 0; e < elems.size(); ++e) {
      for (int v : elems[e]) {
        if (v < 0 || static_cast<std::size_t>(v) >= m.vertices.size()) {
          throw InvalidArgument(src + ": " + kind + " " + std::to_string(e) + " refers to vertex " +
                                std::to_string(v) + ", the mesh has " +
                                std::to_string(m.vertices.size()));
        }
      }
    }
  };
  if (m.dimension == 3) check(m.triangles, "triangle");
  if (m.dimension == 2) check(m.segments, "segment");
}

MeshShape::MeshShape(SurfaceMesh mesh, MeshShapeOptions options)
    : mesh_(std::move(mesh)), opt_(options) {
  const auto& v = mesh_.vertices;
  double vol = 0;
  if (mesh_.dimension == 3) {
    for (const auto& t : mesh_.triangles) vol += dot(v[t[0]], cross(v[t[1]], v[t[2]])) / 6.0;
  } else {
    for (auto& s : mesh_.vertices) s.z = 0;
    for (const auto& s : mesh_.segments) {
      vol += 0.5 * (v[s[0]].x * v[s[1]].y - v[s[1]].x * v[s[0]].y);
    }
  }
  if (vol < 0) {  // inverted normals: flip every element
    inverted_ = true;
    vol = -vol;
    for (auto& t : mesh_.triangles) std::swap(t[1], t[2]);
    for (auto& s : mesh_.segments) std::swap(s[0], s[1]);
  }
  volume_ = vol;
  std::vector<Element> elems;
  elems.reserve(mesh_.size());
  if (mesh_.dimension == 3) {
    for (const auto& t : mesh_.triangles) elems.push_back({v[t[0]], v[t[1]], v[t[2]]});
  } else {
    for (const auto& s : mesh_.segments) elems.push_back({v[s[0]], v[s[1]], v[s[1]]});
  }
  for (const auto& e : elems) {
    for (int k = 0; k < mesh_.dimension; ++k) box_.add(e[k]);
  }
  bvh_ = std::make_unique<Bvh>(mesh_.dimension, std::move(elems), opt_.leaf_size);
}

std::optional<double> MeshShape::exact_area() const {
  const auto& v = mesh_.vertices;
  double a = 0;
  for (const auto& t : mesh_.triangles)
    a += 0.5 * norm(cross(v[t[1]] - v[t[0]], v[t[2]] - v[t[0]]));
  for (const auto& s : mesh_.segments) a += norm(v[s[1]] - v[s[0]]);
  return a;
}

MeshShape::~MeshShape() = default;

double MeshShape::winding_number(Vec3 p) const {
  if (mesh_.dimension == 2) p.z = 0;
  return bvh_->winding(p, opt_.far_field_beta);
}

double MeshShape::winding_number_exact(Vec3 p) const {
  if (mesh_.dimension == 2) p.z = 0;
  return bvh_->winding(p, 0.0);
}

bool MeshShape::inside(Vec3 p) const {
  return winding_number(p) > 0.5;
}

MeshShape::Closest MeshShape::closest(Vec3 p) const {
  if (mesh_.dimension == 2) p.z = 0;
  const auto hit = bvh_->closest(p);
  return {hit.point, std::sqrt(hit.distance2), hit.element};
}

double MeshShape::signed_distance(Vec3 p) const {
  const double d = closest(p).distance;
  return inside(p) ? -d : d;
}

double MeshShape::signed_distance_bounded(Vec3 p, double limit) const {
  if (mesh_.dimension == 2) p.z = 0;
  const double cut = std::nextafter(limit, std::numeric_limits<double>::infinity());
  const auto hit = bvh_->closest(p, cut * cut);
  const double d = hit.element >= 0 ? std::sqrt(hit.distance2) : cut;
  return inside(p) ? -d : d;
}

Vec3 MeshShape::normal(Vec3 p) const {
  if (mesh_.dimension == 2) p.z = 0;
  const auto c = closest(p);
  const double scale = std::max(norm(box_.extent()), 1e-300);
  if (c.distance > 1e-9 * scale) {
    const Vec3 n = (p - c.point) / c.distance;
    return inside(p) ? -n : n;
  }
  return bvh_->element_normal(c.element);
}

std::shared_ptr<const MeshShape> make_mesh_shape(SurfaceMesh mesh, MeshShapeOptions options) {
  validate(mesh);
  if (!(options.far_field_beta >= 0)) {
    throw InvalidArgument(mesh.source + ": far_field_beta must be >= 0, got " +
                          format_value(options.far_field_beta));
  }
  return std::make_shared<const MeshShape>(std::move(mesh), options);
}

}  // namespace sadr::geometry
