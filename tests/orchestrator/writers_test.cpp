// SPDX-License-Identifier: MIT
// VTU / VTP / PVD / CSV frame writers and the run manifest: files parse back
// to exactly the values written.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "sadr/common/status.hpp"
#include "sadr/common/version.hpp"
#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "xml_reader.hpp"

namespace sadr::orchestrator {
namespace {

namespace fs = std::filesystem;
using test::data_array;
using test::numbers;
using test::parse_xml;
using test::values;

fs::path fresh_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("sadr_orch_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

ParticleState sample_particles() {
  ParticleState p;
  p.dimension = 2;
  p.resize(3);
  p.positions = {0.1, 0.2, 0.0, 1.0 / 3.0, 0.5, 0.0, 0.9, 1e-300, 0.0};
  p.velocities = {1.0, -2.0, 0.0, 0.0, 0.0, 0.0, 1e-17, 3.0, 0.0};
  p.densities = {1.0, 1.5, 0.999999999999};
  p.masses = {0.01, 0.02, 0.03};
  p.kinds = {ParticleKind::kFluid, ParticleKind::kWall, ParticleKind::kOutlet};
  p.ids = {7, 8, 9};
  return p;
}

std::vector<SpeciesColumn> sample_species() {
  return {{"A", {0, 5, 12}}, {"C", {0.1, 2.0 / 3.0, 1e10}}};
}

std::string slurp(const fs::path& p) {
  return read_file_bytes(p);
}

void check_point_data(const test::VtkDoc& d, const ParticleState& p,
                      const std::vector<SpeciesColumn>& sp) {
  EXPECT_EQ(values(d, "id"), (std::vector<double>{7, 8, 9}));
  EXPECT_EQ(values(d, "kind"), (std::vector<double>{0, 1, 3}));
  EXPECT_EQ(values(d, "velocity"), p.velocities);
  EXPECT_EQ(data_array(d.xml, "velocity").attributes.at("NumberOfComponents"), "3");
  EXPECT_EQ(values(d, "density"), p.densities);
  EXPECT_EQ(values(d, "mass"), p.masses);
  EXPECT_EQ(values(d, "Points"), p.positions);  // bit-exact: raw bytes or shortest decimals
  for (const auto& s : sp) EXPECT_EQ(values(d, s.name), s.values);
  EXPECT_EQ(values(d, "TimeValue"), std::vector<double>{0.7});
}

/// Both encodings: binary arrays are all appended (raw data present), ASCII ones inline.
void check_encoding(const test::VtkDoc& d, VtkEncoding enc) {
  EXPECT_EQ(d.raw.empty(), enc == VtkEncoding::kAscii);
  for (const auto& e : d.xml) {
    if (e.name == "VTKFile") {
      EXPECT_EQ(e.attributes.at("header_type"), "UInt64");
      EXPECT_EQ(e.attributes.at("byte_order"),
                std::endian::native == std::endian::big ? "BigEndian" : "LittleEndian");
    }
    if (e.name != "DataArray" || e.attributes.at("Name") == "TimeValue") continue;
    EXPECT_EQ(e.attributes.at("format"), enc == VtkEncoding::kBinary ? "appended" : "ascii")
        << e.attributes.at("Name");
  }
}

class WritersEnc : public ::testing::TestWithParam<VtkEncoding> {};

TEST_P(WritersEnc, VtuParsesBackBitExact) {
  const fs::path dir = fresh_dir("vtu");
  const auto p = sample_particles();
  const auto sp = sample_species();
  write_vtu(dir / "f.vtu", 0.7, p, sp, GetParam());
  const auto d = test::read_vtk(slurp(dir / "f.vtu"));
  check_encoding(d, GetParam());
  check_point_data(d, p, sp);
  bool piece = false;
  for (const auto& e : d.xml) {
    if (e.name == "Piece") {
      piece = true;
      EXPECT_EQ(e.attributes.at("NumberOfPoints"), "3");
      EXPECT_EQ(e.attributes.at("NumberOfCells"), "3");
    }
    if (e.name == "VTKFile") {
      EXPECT_EQ(e.attributes.at("type"), "UnstructuredGrid");
    }
  }
  EXPECT_TRUE(piece);
  EXPECT_EQ(values(d, "types"), (std::vector<double>{1, 1, 1}));  // VTK_VERTEX
  EXPECT_EQ(values(d, "connectivity"), (std::vector<double>{0, 1, 2}));
  EXPECT_EQ(values(d, "offsets"), (std::vector<double>{1, 2, 3}));
  fs::remove_all(dir);
}

TEST_P(WritersEnc, VtpParsesBack) {
  const fs::path dir = fresh_dir("vtp");
  const auto p = sample_particles();
  const auto sp = sample_species();
  write_vtp(dir / "f.vtp", 0.7, p, sp, GetParam());
  const auto d = test::read_vtk(slurp(dir / "f.vtp"));
  check_encoding(d, GetParam());
  check_point_data(d, p, sp);
  bool verts = false;
  for (const auto& e : d.xml) {
    if (e.name == "Piece") {
      EXPECT_EQ(e.attributes.at("NumberOfVerts"), "3");
    }
    verts = verts || e.name == "Verts";
  }
  EXPECT_TRUE(verts);
  EXPECT_EQ(values(d, "connectivity"), (std::vector<double>{0, 1, 2}));
  fs::remove_all(dir);
}

std::string encoding_name(const ::testing::TestParamInfo<VtkEncoding>& p) {
  return p.param == VtkEncoding::kBinary ? "Binary" : "Ascii";
}

INSTANTIATE_TEST_SUITE_P(Encodings, WritersEnc,
                         ::testing::Values(VtkEncoding::kBinary, VtkEncoding::kAscii),
                         encoding_name);

TEST(Writers, WrongSpeciesLengthIsRefused) {
  const fs::path dir = fresh_dir("bad");
  const std::vector<SpeciesColumn> sp{{"A", {1, 2}}};
  EXPECT_THROW(write_vtu(dir / "f.vtu", 0, sample_particles(), sp), InvalidArgument);
  EXPECT_FALSE(fs::exists(dir / "f.vtu"));
  fs::remove_all(dir);
}

TEST(Writers, PvdIsValidAfterEveryFrame) {
  const fs::path dir = fresh_dir("pvd");
  fs::create_directories(dir / "frames");
  PvdCollection pvd(dir / "run.pvd");
  const auto p = sample_particles();
  for (int k = 0; k < 3; ++k) {
    const fs::path frame = dir / "frames" / ("f" + std::to_string(k) + ".vtu");
    write_vtu(frame, 0.1 * k, p, {});
    pvd.add(0.1 * k, frame);
    // After each frame the collection on disk is complete and lists k+1 frames.
    const auto xml = parse_xml(slurp(dir / "run.pvd"));
    std::vector<std::string> files;
    std::vector<double> times;
    for (const auto& e : xml) {
      if (e.name != "DataSet") continue;
      files.push_back(e.attributes.at("file"));
      times.push_back(std::stod(e.attributes.at("timestep")));
    }
    ASSERT_EQ(files.size(), static_cast<std::size_t>(k + 1));
    EXPECT_EQ(files.back(), "frames/f" + std::to_string(k) + ".vtu");
    EXPECT_EQ(times.back(), 0.1 * k);
    EXPECT_TRUE(fs::exists(dir / files.back()));
  }
  fs::remove_all(dir);
}

TEST(Writers, CsvHasDocumentedColumnsAndFullPrecision) {
  const fs::path dir = fresh_dir("csv");
  const auto p = sample_particles();
  const auto sp = sample_species();
  write_frame_csv(dir / "f.csv", 0.7, p, sp);
  std::istringstream in(slurp(dir / "f.csv"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "time,id,kind,x,y,z,vx,vy,vz,density,mass,A,C");
  std::size_t row = 0;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 13U);
    EXPECT_EQ(v[0], 0.7);
    EXPECT_EQ(v[1], static_cast<double>(p.ids[row]));
    EXPECT_EQ(v[2], static_cast<double>(static_cast<int>(p.kinds[row])));
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(v[3 + a], p.positions[3 * row + a]);
      EXPECT_EQ(v[6 + a], p.velocities[3 * row + a]);
    }
    EXPECT_EQ(v[9], p.densities[row]);
    EXPECT_EQ(v[10], p.masses[row]);
    EXPECT_EQ(v[11], sp[0].values[row]);
    EXPECT_EQ(v[12], sp[1].values[row]);
    ++row;
  }
  EXPECT_EQ(row, 3U);
  fs::remove_all(dir);
}

TEST(Writers, RunManifestJson) {
  const fs::path dir = fresh_dir("manifest");
  RunManifest m;
  m.scene_path = "examples/x.yaml";
  m.scene_hash = content_hash("abc");
  m.seed = 42;
  m.timings_s["ssa"] = 1.5;
  m.plan = nlohmann::json{{"ssa_service", true}};
  m.status = "ok";
  m.write(dir / "run.json");
  const auto j = nlohmann::json::parse(slurp(dir / "run.json"));
  EXPECT_EQ(j.at("scene_hash"), content_hash("abc"));
  EXPECT_EQ(j.at("seed"), 42U);
  EXPECT_EQ(j.at("timings_s").at("ssa"), 1.5);
  EXPECT_EQ(j.at("plan").at("ssa_service"), true);
  EXPECT_FALSE(j.at("sadr_version").get<std::string>().empty());
  EXPECT_EQ(j.at("protocol_version"), kProtocolVersion);
  EXPECT_EQ(utc_now_iso8601().size(), 20U);
  fs::remove_all(dir);
}

TEST(Hash, Fnv1a64KnownValues) {
  // Reference values of FNV-1a 64 (Fowler, Noll, Vo test vectors).
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ULL);
  EXPECT_EQ(content_hash("a"), "fnv1a64:af63dc4c8601ec8c");
}

}  // namespace
}  // namespace sadr::orchestrator
