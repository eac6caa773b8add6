// SPDX-License-Identifier: MIT
// Surface meshes of revolution (sphere, capsule, torus), a circle polyline, and STL writers, for
// the geometry tests and benchmark. Writing STL here is the test's own fixture; reading goes
// through sadr::geometry::read_mesh (gmsh).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <unistd.h>

#include "sadr/geometry/mesh.hpp"

namespace sadr::geometry::testing {

/// Revolves a profile (rho, z) about the z axis with `nlon` segments; the profile runs from the
/// south pole (rho = 0) to the north pole (rho = 0), or is a closed loop (`closed`: a torus).
/// Triangles are oriented outward (positive enclosed volume).
inline SurfaceMesh revolve(const std::vector<std::pair<double, double>>& profile, int nlon,
                           bool closed, Vec3 centre = {}) {
  SurfaceMesh m;
  m.dimension = 3;
  const double pi = std::numbers::pi;
  const int np = static_cast<int>(profile.size());
  const auto ring_index = [&](int i, int j) { return i * nlon + (j % nlon); };
  for (int i = 0; i < np; ++i) {
    for (int j = 0; j < nlon; ++j) {
      const double phi = 2 * pi * j / nlon;
      m.vertices.push_back(centre + Vec3{profile[i].first * std::cos(phi),
                                         profile[i].first * std::sin(phi), profile[i].second});
    }
  }
  const int rows = closed ? np : np - 1;
  for (int i = 0; i < rows; ++i) {
    const int i1 = (i + 1) % np;
    for (int j = 0; j < nlon; ++j) {
      const int a = ring_index(i, j), b = ring_index(i, j + 1), c = ring_index(i1, j + 1),
                d = ring_index(i1, j);
      // Rings of radius 0 (poles) give degenerate triangles; skip them.
      if (profile[i].first > 0) m.triangles.push_back({a, c, b});
      if (profile[i1].first > 0) m.triangles.push_back({a, d, c});
    }
  }
  double vol = 0;
  for (const auto& t : m.triangles) {
    vol += dot(m.vertices[t[0]], cross(m.vertices[t[1]], m.vertices[t[2]]));
  }
  if (vol < 0) {
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
  }
  return m;
}

inline SurfaceMesh sphere_mesh(Vec3 c, double r, int nlat) {
  std::vector<std::pair<double, double>> prof;
  for (int i = 0; i <= nlat; ++i) {
    const double th = std::numbers::pi * (1.0 - static_cast<double>(i) / nlat);
    prof.push_back({i == 0 || i == nlat ? 0.0 : r * std::sin(th), r * std::cos(th)});
  }
  return revolve(prof, 2 * nlat, false, c);
}

/// Capsule along z from z = -half_length to +half_length (segment), radius r.
inline SurfaceMesh capsule_mesh(Vec3 c, double half_length, double r, int nlat) {
  std::vector<std::pair<double, double>> prof;
  const double pi = std::numbers::pi;
  for (int i = 0; i <= nlat / 2; ++i) {
    const double th = pi * (1.0 - static_cast<double>(i) / nlat);
    prof.push_back({i == 0 ? 0.0 : r * std::sin(th), -half_length + r * std::cos(th)});
  }
  for (int i = nlat / 2; i <= nlat; ++i) {
    const double th = pi * (1.0 - static_cast<double>(i) / nlat);
    prof.push_back({i == nlat ? 0.0 : r * std::sin(th), half_length + r * std::cos(th)});
  }
  return revolve(prof, 2 * nlat, false, c);
}

inline SurfaceMesh torus_mesh(Vec3 c, double big_r, double small_r, int nu, int nv) {
  std::vector<std::pair<double, double>> prof;
  for (int i = 0; i < nv; ++i) {
    const double t = 2 * std::numbers::pi * i / nv;
    prof.push_back({big_r + small_r * std::cos(t), small_r * std::sin(t)});
  }
  return revolve(prof, nu, true, c);
}

/// Circle of n segments, counter-clockwise (2D).
inline SurfaceMesh circle_polyline(Vec3 c, double r, int n) {
  SurfaceMesh m;
  m.dimension = 2;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * i / n;
    m.vertices.push_back({c.x + r * std::cos(t), c.y + r * std::sin(t), 0});
    m.segments.push_back({i, (i + 1) % n});
  }
  return m;
}

inline void write_stl_binary(const std::string& path, const SurfaceMesh& m) {
  std::ofstream f(path, std::ios::binary);
  char header[80] = "sadr geometry test";
  f.write(header, 80);
  const auto n = static_cast<std::uint32_t>(m.triangles.size());
  f.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : m.triangles) {
    const Vec3 nn =
        normalized(cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]));
    float buf[12] = {static_cast<float>(nn.x), static_cast<float>(nn.y), static_cast<float>(nn.z)};
    for (int k = 0; k < 3; ++k) {
      for (int a = 0; a < 3; ++a) buf[3 + 3 * k + a] = static_cast<float>(m.vertices[t[k]][a]);
    }
    f.write(reinterpret_cast<const char*>(buf), sizeof buf);
    const std::uint16_t attr = 0;
    f.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

inline void write_stl_ascii(const std::string& path, const SurfaceMesh& m) {
  std::ofstream f(path);
  f.precision(17);
  f << "solid test\n";
  for (const auto& t : m.triangles) {
    f << " facet normal 0 0 0\n  outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const Vec3 v = m.vertices[t[k]];
      f << "   vertex " << v.x << ' ' << v.y << ' ' << v.z << '\n';
    }
    f << "  endloop\n endfacet\n";
  }
  f << "endsolid test\n";
}

/// A fresh temporary directory for one test's files (per process), removed at exit.
inline std::string temp_dir(const std::string& name) {
  struct Cleanup {
    std::vector<std::string> dirs;
    ~Cleanup() {
      std::error_code ec;
      for (const auto& d : dirs) std::filesystem::remove_all(d, ec);
    }
  };
  static Cleanup cleanup;
  const std::string d = std::string("/tmp/sadr_geometry_") + name + "_" +
                        std::to_string(static_cast<long>(::getpid()));
  std::filesystem::create_directories(d);
  cleanup.dirs.push_back(d);
  return d;
}

}  // namespace sadr::geometry::testing
