// SPDX-License-Identifier: MIT
// A check of an STL file's vertices before gmsh reads it: gmsh drops a facet with a non-finite
// vertex without a word, so one bad facet among good ones would leave a hole nobody was told of.
// This is not a reader (gmsh reads the file): it only looks at each vertex's three numbers.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "mesh_io_parts.hpp"
#include "sadr/common/status.hpp"

namespace sadr::geometry {
namespace {

[[noreturn]] void refuse(const std::string& path, std::size_t facet, const std::string& where,
                         const double v[3]) {
  std::ostringstream m;
  m.precision(6);
  m << path << ": facet " << facet << where << " has a non-finite vertex (" << v[0] << ", " << v[1]
    << ", " << v[2] << "); allowed: finite coordinates";
  throw InvalidArgument(m.str());
}

}  // namespace

void check_stl_vertices(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return;  // read_mesh reports unreadable files
  std::ifstream f(path, std::ios::binary);
  char header[84] = {};
  f.read(header, sizeof header);
  std::uint32_t count = 0;
  std::memcpy(&count, header + 80, 4);
  const bool binary =
      f.gcount() == 84 && size == 84 + 50 * static_cast<std::uintmax_t>(count) && count > 0;
  if (binary) {
    char rec[50];
    for (std::uint32_t t = 0; t < count && f.read(rec, sizeof rec); ++t) {
      for (int k = 0; k < 3; ++k) {
        float xyz[3];
        std::memcpy(xyz, rec + 12 + 12 * k, sizeof xyz);
        const double v[3] = {xyz[0], xyz[1], xyz[2]};
        if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
          refuse(path, t, "", v);
        }
      }
    }
    return;
  }
  f.clear();
  f.seekg(0);
  std::string line;
  std::size_t facet = 0, line_no = 0;
  while (std::getline(f, line)) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    const char* p = line.c_str() + first;
    if (std::strncmp(p, "endfacet", 8) == 0) {
      ++facet;
      continue;
    }
    if (std::strncmp(p, "vertex", 6) != 0) continue;
    p += 6;
    double v[3];
    for (double& x : v) {
      char* end = nullptr;
      x = std::strtod(p, &end);
      p = end;
    }
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
      refuse(path, facet, " (line " + std::to_string(line_no) + ")", v);
    }
  }
}

}  // namespace sadr::geometry
