// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/frame_writers.hpp"

#include <charconv>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/atomic_file.hpp"

namespace sadr::orchestrator {

void append_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void append_integer(std::string& out, std::uint64_t v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

namespace {

void check_columns(const ParticleState& p, std::span<const SpeciesColumn> species) {
  for (const auto& s : species) {
    if (s.values.size() != p.size()) {
      throw InvalidArgument("frame writer: species '" + s.name + "' has " +
                            std::to_string(s.values.size()) + " values, expected " +
                            std::to_string(p.size()) + " (one per particle)");
    }
  }
}

double velocity(const ParticleState& p, std::size_t i, int a) {
  return p.velocities.empty() ? 0.0 : p.velocities[3 * i + static_cast<std::size_t>(a)];
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::uint64_t id_of(const ParticleState& p, std::size_t i) {
  return p.ids.empty() ? i : p.ids[i];
}

void float_array(std::string& x, const char* name, int components, std::size_t n,
                 const auto& value) {
  x += "        <DataArray type=\"Float64\" Name=\"";
  x += name;
  x += "\" NumberOfComponents=\"" + std::to_string(components) + "\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    x += "          ";
    for (int c = 0; c < components; ++c) {
      if (c) x += ' ';
      append_number(x, value(i, c));
    }
    x += '\n';
  }
  x += "        </DataArray>\n";
}

/// The <PointData> and <Points> parts shared by .vtu and .vtp.
void point_sections(std::string& x, const ParticleState& p,
                    std::span<const SpeciesColumn> species) {
  const std::size_t n = p.size();
  x += "      <PointData Scalars=\"density\" Vectors=\"velocity\">\n";
  x += "        <DataArray type=\"UInt64\" Name=\"id\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    x += "          ";
    append_integer(x, id_of(p, i));
    x += '\n';
  }
  x += "        </DataArray>\n";
  x += "        <DataArray type=\"UInt8\" Name=\"kind\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    x += "          ";
    append_integer(x, static_cast<std::uint64_t>(p.kind(i)));
    x += '\n';
  }
  x += "        </DataArray>\n";
  float_array(x, "velocity", 3, n, [&](std::size_t i, int c) { return velocity(p, i, c); });
  float_array(x, "density", 1, n, [&](std::size_t i, int) { return p.densities[i]; });
  float_array(x, "mass", 1, n, [&](std::size_t i, int) { return p.masses[i]; });
  for (const auto& s : species) {
    float_array(x, s.name.c_str(), 1, n, [&](std::size_t i, int) { return s.values[i]; });
  }
  x += "      </PointData>\n      <Points>\n";
  float_array(x, "Points", 3, n, [&](std::size_t i, int c) {
    return p.positions[3 * i + static_cast<std::size_t>(c)];
  });
  x += "      </Points>\n";
}

std::string header(const char* type, double time) {
  std::string x = "<?xml version=\"1.0\"?>\n<VTKFile type=\"";
  x += type;
  x += "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <";
  x += type;
  x += ">\n    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TimeValue\" "
       "NumberOfTuples=\"1\" format=\"ascii\">";
  append_number(x, time);
  x += "</DataArray>\n    </FieldData>\n";
  return x;
}

void connectivity(std::string& x, std::size_t n) {
  x += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    x += "          ";
    append_integer(x, i);
    x += '\n';
  }
  x += "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" "
       "format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    x += "          ";
    append_integer(x, i + 1);
    x += '\n';
  }
  x += "        </DataArray>\n";
}

}  // namespace

void write_vtu(const std::filesystem::path& path, double time, const ParticleState& p,
               std::span<const SpeciesColumn> species) {
  check_columns(p, species);
  const std::size_t n = p.size();
  std::string x = header("UnstructuredGrid", time);
  x += "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" +
       std::to_string(n) + "\">\n";
  point_sections(x, p, species);
  x += "      <Cells>\n";
  connectivity(x, n);
  x += "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) x += "          1\n";  // VTK_VERTEX
  x += "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  write_file_atomic(path, x);
}

void write_vtp(const std::filesystem::path& path, double time, const ParticleState& p,
               std::span<const SpeciesColumn> species) {
  check_columns(p, species);
  const std::size_t n = p.size();
  std::string x = header("PolyData", time);
  x += "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfVerts=\"" +
       std::to_string(n) + "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  point_sections(x, p, species);
  x += "      <Verts>\n";
  connectivity(x, n);
  x += "      </Verts>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  write_file_atomic(path, x);
}

std::string frame_csv_header(std::span<const SpeciesColumn> species) {
  std::string h = "time,id,kind,x,y,z,vx,vy,vz,density,mass";
  for (const auto& s : species) h += "," + s.name;
  return h;
}

void write_frame_csv(const std::filesystem::path& path, double time, const ParticleState& p,
                     std::span<const SpeciesColumn> species) {
  check_columns(p, species);
  std::string x = frame_csv_header(species) + "\n";
  for (std::size_t i = 0; i < p.size(); ++i) {
    append_number(x, time);
    x.push_back(',');
    append_integer(x, id_of(p, i));
    x.push_back(',');
    append_integer(x, static_cast<std::uint64_t>(p.kind(i)));
    for (int a = 0; a < 3; ++a) {
      x += ',';
      append_number(x, p.positions[3 * i + static_cast<std::size_t>(a)]);
    }
    for (int a = 0; a < 3; ++a) {
      x += ',';
      append_number(x, velocity(p, i, a));
    }
    x += ',';
    append_number(x, p.densities[i]);
    x += ',';
    append_number(x, p.masses[i]);
    for (const auto& s : species) {
      x += ',';
      append_number(x, s.values[i]);
    }
    x += '\n';
  }
  write_file_atomic(path, x);
}

void PvdCollection::add(double time, const std::filesystem::path& frame_file) {
  const auto dir = path_.parent_path();
  std::filesystem::path rel = frame_file;
  if (frame_file.is_absolute() || !dir.empty()) {
    rel = std::filesystem::proximate(frame_file, dir.empty() ? "." : dir);
  }
  entries_.push_back({time, rel.generic_string()});
  write_file_atomic(path_, xml());
}

std::string PvdCollection::xml() const {
  std::string x =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" "
      "byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const auto& e : entries_) {
    x += "    <DataSet timestep=\"";
    append_number(x, e.time);
    x += "\" group=\"\" part=\"0\" file=\"" + xml_escape(e.file) + "\"/>\n";
  }
  x += "  </Collection>\n</VTKFile>\n";
  return x;
}

}  // namespace sadr::orchestrator
