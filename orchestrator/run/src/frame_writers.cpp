// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/frame_writers.hpp"

#include <bit>
#include <charconv>
#include <cstring>
#include <string>
#include <type_traits>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/atomic_file.hpp"

namespace sadr::orchestrator {

void append_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, static_cast<std::size_t>(r.ptr - buf));
}

void append_integer(std::string& out, std::uint64_t v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, static_cast<std::size_t>(r.ptr - buf));
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

/// The XML of a .vtu/.vtp file and, in binary mode, its appended raw data: one block per
/// array, a UInt64 byte count then the values' bytes, at the offset the DataArray names
/// (counted from the byte after the '_' that opens <AppendedData>).
class VtkBody {
 public:
  explicit VtkBody(VtkEncoding encoding) : binary_(encoding == VtkEncoding::kBinary) {}
  std::string xml;

  /// A DataArray of n tuples of `components` values value(i, c), stored as T.
  template <typename T>
  void array(const char* type, const char* name, int components, std::size_t n, const auto& value) {
    xml += "        <DataArray type=\"";
    xml += type;
    xml += "\" Name=\"";
    xml += name;
    xml += '"';
    if (components != 1) xml += " NumberOfComponents=\"" + std::to_string(components) + '"';
    if (binary_) {
      xml += " format=\"appended\" offset=\"";
      append_integer(xml, appended_.size());
      xml += "\"/>\n";
      const std::uint64_t bytes = n * static_cast<std::size_t>(components) * sizeof(T);
      append_raw(bytes);
      for (std::size_t i = 0; i < n; ++i) {
        for (int c = 0; c < components; ++c) append_raw(static_cast<T>(value(i, c)));
      }
      return;
    }
    xml += " format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) {
      xml += "          ";
      for (int c = 0; c < components; ++c) {
        if (c) xml += ' ';
        if constexpr (std::is_floating_point_v<T>) {
          append_number(xml, static_cast<double>(value(i, c)));
        } else {
          append_integer(xml, static_cast<std::uint64_t>(value(i, c)));
        }
      }
      xml += '\n';
    }
    xml += "        </DataArray>\n";
  }

  /// Closes the file: the appended data (binary mode) and </VTKFile>.
  std::string finish() {
    if (binary_) {
      xml += "  <AppendedData encoding=\"raw\">\n   _";
      xml += appended_;
      xml += "\n  </AppendedData>\n";
    }
    xml += "</VTKFile>\n";
    return std::move(xml);
  }

 private:
  template <typename T>
  void append_raw(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    appended_.append(b, sizeof(T));
  }
  bool binary_;
  std::string appended_;
};

/// The <PointData> and <Points> parts shared by .vtu and .vtp.
void point_sections(VtkBody& x, const ParticleState& p, std::span<const SpeciesColumn> species) {
  const std::size_t n = p.size();
  x.xml += "      <PointData Scalars=\"density\" Vectors=\"velocity\">\n";
  x.array<std::uint64_t>("UInt64", "id", 1, n, [&](std::size_t i, int) { return id_of(p, i); });
  x.array<std::uint8_t>("UInt8", "kind", 1, n,
                        [&](std::size_t i, int) { return static_cast<int>(p.kind(i)); });
  x.array<double>("Float64", "velocity", 3, n,
                  [&](std::size_t i, int c) { return velocity(p, i, c); });
  x.array<double>("Float64", "density", 1, n, [&](std::size_t i, int) { return p.densities[i]; });
  x.array<double>("Float64", "mass", 1, n, [&](std::size_t i, int) { return p.masses[i]; });
  for (const auto& s : species) {
    x.array<double>("Float64", s.name.c_str(), 1, n,
                    [&](std::size_t i, int) { return s.values[i]; });
  }
  x.xml += "      </PointData>\n      <Points>\n";
  x.array<double>("Float64", "Points", 3, n, [&](std::size_t i, int c) {
    return p.positions[3 * i + static_cast<std::size_t>(c)];
  });
  x.xml += "      </Points>\n";
}

VtkBody header(const char* type, double time, VtkEncoding encoding) {
  VtkBody body(encoding);
  std::string& x = body.xml;
  x = "<?xml version=\"1.0\"?>\n<VTKFile type=\"";
  x += type;
  x += "\" version=\"1.0\" byte_order=\"";
  x += std::endian::native == std::endian::big ? "BigEndian" : "LittleEndian";
  x += "\" header_type=\"UInt64\">\n  <";
  x += type;
  x += ">\n    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TimeValue\" "
       "NumberOfTuples=\"1\" format=\"ascii\">";
  append_number(x, time);
  x += "</DataArray>\n    </FieldData>\n";
  return body;
}

void connectivity(VtkBody& x, std::size_t n) {
  x.array<std::int64_t>("Int64", "connectivity", 1, n, [](std::size_t i, int) { return i; });
  x.array<std::int64_t>("Int64", "offsets", 1, n, [](std::size_t i, int) { return i + 1; });
}

}  // namespace

void write_vtu(const std::filesystem::path& path, double time, const ParticleState& p,
               std::span<const SpeciesColumn> species, VtkEncoding encoding) {
  check_columns(p, species);
  const std::size_t n = p.size();
  VtkBody x = header("UnstructuredGrid", time, encoding);
  x.xml += "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" +
           std::to_string(n) + "\">\n";
  point_sections(x, p, species);
  x.xml += "      <Cells>\n";
  connectivity(x, n);
  x.array<std::uint8_t>("UInt8", "types", 1, n, [](std::size_t, int) { return 1; });  // VERTEX
  x.xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
  write_file_atomic(path, x.finish());
}

void write_vtp(const std::filesystem::path& path, double time, const ParticleState& p,
               std::span<const SpeciesColumn> species, VtkEncoding encoding) {
  check_columns(p, species);
  const std::size_t n = p.size();
  VtkBody x = header("PolyData", time, encoding);
  x.xml += "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfVerts=\"" +
           std::to_string(n) + "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  point_sections(x, p, species);
  x.xml += "      <Verts>\n";
  connectivity(x, n);
  x.xml += "      </Verts>\n    </Piece>\n  </PolyData>\n";
  write_file_atomic(path, x.finish());
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
