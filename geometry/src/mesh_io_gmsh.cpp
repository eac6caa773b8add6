// SPDX-License-Identifier: MIT
// read_mesh through the gmsh API (libgmsh 4.8), loaded at the first read (gmsh_dl.hpp).
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <unordered_map>

#include "gmsh_dl.hpp"
#include "mesh_io_parts.hpp"
#include "sadr/common/status.hpp"
#include "sadr/geometry/mesh_io.hpp"

namespace sadr::geometry {
namespace gmsh = gmsh_dl;
namespace {

std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

/// gmsh::initialize / finalize around one read (gmsh keeps global state).
struct GmshSession {
  GmshSession() {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

struct Elements {
  std::vector<std::array<int, 2>> lines;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 4>> quads, tets;
};

class Reader {
 public:
  Reader(std::string path, int dim) : path_(std::move(path)), dim_(dim) {}

  void load_nodes() {
    std::vector<std::size_t> tags;
    std::vector<double> xyz, param;
    gmsh::model::mesh::getNodes(tags, xyz, param, -1, -1, false, false);
    vertices_.resize(tags.size());
    for (std::size_t i = 0; i < tags.size(); ++i) {
      index_[tags[i]] = static_cast<int>(i);
      vertices_[i] = {xyz[3 * i], xyz[3 * i + 1], dim_ == 2 ? 0.0 : xyz[3 * i + 2]};
      if (!all_finite({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]})) {
        throw InvalidArgument(path_ + ": node " + std::to_string(tags[i]) +
                              " has a non-finite coordinate (" + format_value(xyz[3 * i]) + ", " +
                              format_value(xyz[3 * i + 1]) + ", " + format_value(xyz[3 * i + 2]) +
                              ")");
      }
    }
  }

  /// Elements of dimension `dim` on entity `tag` (-1: all entities).
  Elements elements(int dim, int tag) const {
    Elements out;
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> etags, ntags;
    gmsh::model::mesh::getElements(types, etags, ntags, dim, tag);
    for (std::size_t t = 0; t < types.size(); ++t) {
      std::string name;
      int edim = 0, order = 0, nnodes = 0, nprimary = 0;
      std::vector<double> local;
      gmsh::model::mesh::getElementProperties(types[t], name, edim, order, nnodes, local, nprimary);
      const std::size_t count = etags[t].size();
      for (std::size_t e = 0; e < count; ++e) {
        const std::size_t* n = &ntags[t][e * nnodes];
        const auto node = [&](int k) { return lookup(n[k], etags[t][e]); };
        if (edim == 1 && nprimary == 2) {
          out.lines.push_back({node(0), node(1)});
        } else if (edim == 2 && nprimary == 3) {
          out.triangles.push_back({node(0), node(1), node(2)});
        } else if (edim == 2 && nprimary == 4) {
          out.quads.push_back({node(0), node(1), node(2), node(3)});
        } else if (edim == 3 && nprimary == 4) {
          out.tets.push_back({node(0), node(1), node(2), node(3)});
        } else if (edim > 0) {
          throw InvalidArgument(path_ + ": element " + std::to_string(etags[t][e]) + " is a " +
                                name + ", not supported (lines, triangles, quadrangles and " +
                                "tetrahedra are)");
        }
      }
    }
    return out;
  }

  Elements group_elements(int dim, int group) const {
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(dim, group, entities);
    Elements all;
    for (int ent : entities) {
      Elements e = elements(dim, ent);
      all.lines.insert(all.lines.end(), e.lines.begin(), e.lines.end());
      all.triangles.insert(all.triangles.end(), e.triangles.begin(), e.triangles.end());
      all.quads.insert(all.quads.end(), e.quads.begin(), e.quads.end());
      all.tets.insert(all.tets.end(), e.tets.begin(), e.tets.end());
    }
    return all;
  }

  SurfaceMesh make(const std::string& what) const {
    SurfaceMesh m;
    m.dimension = dim_;
    m.vertices = vertices_;
    m.source = path_ + (what.empty() ? "" : " (" + what + ")");
    return m;
  }

  /// Surface elements as given (3D: triangles + split quads; 2D: segments).
  SurfaceMesh as_surface(const Elements& e, const std::string& what) const {
    SurfaceMesh m = make(what);
    m.triangles = e.triangles;
    for (const auto& q : e.quads) {
      m.triangles.push_back({q[0], q[1], q[2]});
      m.triangles.push_back({q[0], q[2], q[3]});
    }
    m.segments = e.lines;
    return m;
  }

  /// Outward boundary of volume elements (3D tets; 2D triangles and quads): faces seen once.
  SurfaceMesh boundary_of(const Elements& e, const std::string& what) const {
    SurfaceMesh m = make(what);
    const auto& v = vertices_;
    if (dim_ == 3) {
      std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> faces;
      for (auto t : e.tets) {
        if (dot(v[t[1]] - v[t[0]], cross(v[t[2]] - v[t[0]], v[t[3]] - v[t[0]])) < 0) {
          std::swap(t[1], t[2]);
        }
        const std::array<std::array<int, 3>, 4> f{
            {{t[0], t[2], t[1]}, {t[0], t[1], t[3]}, {t[0], t[3], t[2]}, {t[1], t[2], t[3]}}};
        for (const auto& face : f) count(faces, face);
      }
      for (const auto& [key, val] : faces) {
        if (val.first == 1) m.triangles.push_back(val.second);
      }
      return m;
    }
    std::map<std::array<int, 2>, std::pair<int, std::array<int, 2>>> edges;
    auto polygon = [&](const int* p, int n) {
      double a = 0;
      for (int i = 0, j = n - 1; i < n; j = i++) a += v[p[j]].x * v[p[i]].y - v[p[i]].x * v[p[j]].y;
      for (int i = 0, j = n - 1; i < n; j = i++) {
        count(edges, a >= 0 ? std::array<int, 2>{p[j], p[i]} : std::array<int, 2>{p[i], p[j]});
      }
    };
    for (const auto& t : e.triangles) polygon(t.data(), 3);
    for (const auto& q : e.quads) polygon(q.data(), 4);
    for (const auto& [key, val] : edges) {
      if (val.first == 1) m.segments.push_back(val.second);
    }
    return m;
  }

 private:
  template <std::size_t N>
  static void count(std::map<std::array<int, N>, std::pair<int, std::array<int, N>>>& map,
                    const std::array<int, N>& face) {
    auto key = face;
    std::sort(key.begin(), key.end());
    auto [it, fresh] = map.try_emplace(key, 0, face);
    ++it->second.first;
  }
  int lookup(std::size_t node_tag, std::size_t element_tag) const {
    const auto it = index_.find(node_tag);
    if (it == index_.end()) {
      throw InvalidArgument(path_ + ": element " + std::to_string(element_tag) +
                            " refers to node " + std::to_string(node_tag) +
                            ", which is not defined");
    }
    return it->second;
  }
  std::string path_;
  int dim_;
  std::vector<Vec3> vertices_;
  std::unordered_map<std::size_t, int> index_;
};

std::string lower_extension(const std::string& path) {
  const auto dot_pos = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot_pos == std::string::npos || (slash != std::string::npos && dot_pos < slash)) return "";
  std::string ext = path.substr(dot_pos);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

const SurfaceMesh& find_group(const std::map<std::string, SurfaceMesh>& groups,
                              const std::string& name, const std::string& path,
                              const std::string& kind) {
  const auto it = groups.find(name);
  if (it != groups.end()) return it->second;
  std::string known;
  for (const auto& [n, m] : groups) known += (known.empty() ? "" : ", ") + n;
  throw InvalidArgument(path + ": no physical " + kind + " named '" + name + "'; the file has " +
                        (known.empty() ? std::string("none") : known));
}

}  // namespace

const SurfaceMesh& MeshFile::surface(const std::string& name) const {
  return find_group(surfaces, name, path, dimension == 3 ? "surface" : "curve");
}
const SurfaceMesh& MeshFile::region(const std::string& name) const {
  return find_group(regions, name, path, dimension == 3 ? "volume" : "surface");
}
std::vector<std::string> MeshFile::surface_names() const {
  std::vector<std::string> n;
  for (const auto& [k, v] : surfaces) n.push_back(k);
  return n;
}
std::vector<std::string> MeshFile::region_names() const {
  std::vector<std::string> n;
  for (const auto& [k, v] : regions) n.push_back(k);
  return n;
}

MeshFile read_mesh(const std::string& path, int dimension) {
  if (dimension != 2 && dimension != 3) {
    throw InvalidArgument(path + ": mesh dimension must be 2 or 3, got " +
                          std::to_string(dimension));
  }
  const std::string ext = lower_extension(path);
  if (ext != ".msh" && ext != ".stl" && ext != ".obj") {
    throw InvalidArgument(path + ": unsupported mesh format '" + ext +
                          "'; supported: .msh (gmsh v2, v4), .stl (ASCII, binary) and .obj");
  }
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    throw InvalidArgument(path + ": not a regular file (expected a mesh file)");
  }
  if (!std::ifstream(path, std::ios::binary).good()) {
    throw InvalidArgument(path + ": cannot open the mesh file (missing or unreadable)");
  }
  if (ext == ".obj") return read_obj(path, dimension);
  if (ext == ".stl") check_stl_vertices(path);
  std::lock_guard lock(gmsh_mutex());
  GmshSession session;
  try {
    gmsh::open(path);
  } catch (const std::exception& e) {
    throw InvalidArgument(path + ": gmsh cannot read it: " + e.what());
  } catch (...) {
    std::string err;
    gmsh::logger::getLastError(err);
    throw InvalidArgument(path + ": gmsh cannot read it: " + err);
  }
  Reader r(path, dimension);
  r.load_nodes();
  MeshFile out;
  out.path = path;
  out.dimension = dimension;
  const Elements top = r.elements(dimension, -1);
  const bool has_cells =
      dimension == 3 ? !top.tets.empty() : !(top.triangles.empty() && top.quads.empty());
  out.boundary =
      has_cells ? r.boundary_of(top, "") : r.as_surface(r.elements(dimension - 1, -1), "");
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  for (const auto& [gdim, gtag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(gdim, gtag, name);
    if (name.empty()) name = std::string(1, '#').append(std::to_string(gtag));
    out.group_dimensions[name] = gdim;
    if (gdim == dimension - 1) {
      out.surfaces[name] = r.as_surface(r.group_elements(gdim, gtag), "physical " + name);
      validate(out.surfaces[name]);
    } else if (gdim == dimension) {
      out.regions[name] = r.boundary_of(r.group_elements(gdim, gtag), "physical " + name);
      validate(out.regions[name]);
    }
  }
  validate(out.boundary);
  return out;
}

}  // namespace sadr::geometry
