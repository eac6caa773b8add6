// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/flow_tape.hpp"

#include <bit>
#include <cstring>
#include <system_error>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/hash.hpp"

namespace sadr::orchestrator {
namespace {

static_assert(std::endian::native == std::endian::little, "flow_tape.cpp writes little-endian");

constexpr std::string_view kMagic = "SADRFLOW";
constexpr std::uint32_t kRecordMagic = 0x31434552;  // "REC1"
/// A record's fixed part: magic, ordinal, payload size (before the payload).
constexpr std::uint64_t kRecordHead = 4 + 8 + 8;

/// Appends plain values and arrays to a byte string.
struct Out {
  std::string bytes;
  template <class T>
  void put(T v) {
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void put_array(const std::vector<T>& v) {
    put<std::uint64_t>(v.size());
    bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put_string(const std::string& s) {
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    bytes.append(s);
  }
};

/// Reads what Out wrote; a read past the end throws (the caller names the record).
struct In {
  std::string_view bytes;
  std::size_t at = 0;
  void need(std::size_t n) {
    if (bytes.size() - at < n) throw InvalidArgument("payload ends early");
  }
  template <class T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  template <class T>
  void get_array(std::vector<T>& v) {
    const auto n = get<std::uint64_t>();
    if (n > (bytes.size() - at) / sizeof(T)) throw InvalidArgument("array longer than payload");
    v.resize(n);
    if (n != 0) std::memcpy(v.data(), bytes.data() + at, n * sizeof(T));  // data() may be null
    at += n * sizeof(T);
  }
  std::string get_string() {
    const auto n = get<std::uint32_t>();
    need(n);
    std::string s(bytes.substr(at, n));
    at += n;
    return s;
  }
};

std::string encode(const FlowRecord& r) {
  Out o;
  o.put<std::uint8_t>(static_cast<std::uint8_t>(r.call));
  o.put(r.step_index);
  o.put(r.dt);
  o.put<std::uint8_t>(r.want_geometry);
  o.put<std::uint32_t>(static_cast<std::uint32_t>(r.species.size()));
  for (const auto& s : r.species) o.put_string(s);
  o.put(r.time);
  o.put(r.substeps);
  o.put(r.stable_time_step);
  o.put_string(r.limiting_criterion);
  o.put<std::uint8_t>(r.moved);
  o.put<std::uint8_t>(r.has_particles);
  if (r.has_particles) {
    const ParticleState& p = r.particles;
    o.put<std::uint32_t>(static_cast<std::uint32_t>(p.dimension));
    o.put_array(p.positions);
    o.put_array(p.velocities);
    o.put_array(p.densities);
    o.put_array(p.masses);
    o.put_array(p.kinds);
    o.put_array(p.ids);
  }
  o.put<std::uint32_t>(static_cast<std::uint32_t>(r.concentrations.size()));
  for (const auto& [name, values] : r.concentrations) {
    o.put_string(name);
    o.put_array(values);
  }
  return std::move(o.bytes);
}

FlowRecord decode(std::string_view payload) {
  In in{payload};
  FlowRecord r;
  const auto call = in.get<std::uint8_t>();
  if (call < 1 || call > 3) throw InvalidArgument("unknown call " + std::to_string(call));
  r.call = static_cast<FlowCall>(call);
  r.step_index = in.get<std::uint64_t>();
  r.dt = in.get<double>();
  r.want_geometry = in.get<std::uint8_t>() != 0;
  r.species.resize(in.get<std::uint32_t>());
  for (auto& s : r.species) s = in.get_string();
  r.time = in.get<double>();
  r.substeps = in.get<std::uint32_t>();
  r.stable_time_step = in.get<double>();
  r.limiting_criterion = in.get_string();
  r.moved = in.get<std::uint8_t>() != 0;
  r.has_particles = in.get<std::uint8_t>() != 0;
  if (r.has_particles) {
    ParticleState& p = r.particles;
    p.dimension = static_cast<int>(in.get<std::uint32_t>());
    in.get_array(p.positions);
    in.get_array(p.velocities);
    in.get_array(p.densities);
    in.get_array(p.masses);
    in.get_array(p.kinds);
    in.get_array(p.ids);
  }
  r.concentrations.resize(in.get<std::uint32_t>());
  for (auto& [name, values] : r.concentrations) {
    name = in.get_string();
    in.get_array(values);
  }
  if (in.at != payload.size()) throw InvalidArgument("bytes left after the payload");
  return r;
}

std::string encode_header(const FlowTapeHeader& h) {
  Out o;
  o.bytes.append(kMagic);
  o.put(kFlowTapeVersion);
  o.put_string(h.fluid_key);
  o.put(h.particles);
  o.put(h.records);
  o.put(fnv1a64(o.bytes));
  return std::move(o.bytes);
}

template <class T>
std::string_view bytes_of(const T& v) {
  return {reinterpret_cast<const char*>(&v), sizeof v};
}

}  // namespace

const char* to_string(FlowCall call) {
  switch (call) {
    case FlowCall::kAdvance:
      return "advance";
    case FlowCall::kGeometry:
      return "geometry";
    case FlowCall::kFrame:
      return "frame";
  }
  return "?";
}

FlowTapeWriter::FlowTapeWriter(std::filesystem::path path, std::string fluid_key,
                               std::uint64_t particles)
    : path_(std::move(path)), partial_(path_.string() + ".partial") {
  header_.fluid_key = std::move(fluid_key);
  header_.particles = particles;
  out_.open(partial_, std::ios::binary | std::ios::trunc);
  if (!out_) throw IoError("cannot create '" + partial_.string() + "'");
  out_ << encode_header(header_);
}

FlowTapeWriter::~FlowTapeWriter() {
  if (finished_) return;
  out_.close();
  std::error_code ec;
  std::filesystem::remove(partial_, ec);
}

void FlowTapeWriter::append(const FlowRecord& record) {
  const std::string payload = encode(record);
  const std::uint64_t ordinal = header_.records, size = payload.size();
  std::string checked;
  checked.reserve(16 + payload.size());
  checked.append(bytes_of(ordinal)).append(bytes_of(size)).append(payload);
  const std::uint64_t sum = fnv1a64(checked);
  out_.write(reinterpret_cast<const char*>(&kRecordMagic), sizeof kRecordMagic);
  out_ << checked;
  out_.write(reinterpret_cast<const char*>(&sum), sizeof sum);
  if (!out_) throw IoError("cannot write '" + partial_.string() + "' (disk full?)");
  ++header_.records;
}

std::uint64_t FlowTapeWriter::finish() {
  out_.seekp(0);
  out_ << encode_header(header_);
  out_.flush();
  if (!out_) throw IoError("cannot write '" + partial_.string() + "'");
  out_.close();
  std::filesystem::rename(partial_, path_);
  finished_ = true;
  return std::filesystem::file_size(path_);
}

FlowTapeReader::FlowTapeReader(std::filesystem::path path, const std::string& expected_fluid_key)
    : path_(std::move(path)) {
  std::error_code ec;
  file_size_ = std::filesystem::file_size(path_, ec);
  in_.open(path_, std::ios::binary);
  if (ec || !in_) fail("cannot be read");
  std::string head(kMagic.size() + 8, '\0');
  in_.read(head.data(), static_cast<std::streamsize>(head.size()));
  if (!in_ || std::string_view(head).substr(0, kMagic.size()) != kMagic) {
    fail("is not a flow replay file (no SADRFLOW header)");
  }
  std::uint32_t version = 0, n = 0;
  std::memcpy(&version, head.data() + kMagic.size(), 4);
  std::memcpy(&n, head.data() + kMagic.size() + 4, 4);
  if (version != kFlowTapeVersion) {
    fail("has format version " + std::to_string(version) + ", this build reads " +
         std::to_string(kFlowTapeVersion));
  }
  if (n > 4096) fail("header: fluid key of " + std::to_string(n) + " bytes");
  std::string rest(n + 24, '\0');
  in_.read(rest.data(), static_cast<std::streamsize>(rest.size()));
  if (!in_) fail("is truncated in its header");
  header_.fluid_key = rest.substr(0, n);
  std::memcpy(&header_.particles, rest.data() + n, 8);
  std::memcpy(&header_.records, rest.data() + n + 8, 8);
  std::uint64_t sum = 0;
  std::memcpy(&sum, rest.data() + n + 16, 8);
  if (fnv1a64(head + rest.substr(0, n + 16)) != sum) fail("header checksum mismatch");
  if (!expected_fluid_key.empty() && header_.fluid_key != expected_fluid_key) {
    fail("was recorded for the fluid " + header_.fluid_key + ", this run's fluid is " +
         expected_fluid_key + " (another fluid: its answers are not this run's)");
  }
  first_offset_ = head.size() + rest.size();
  pos_ = {0, first_offset_};
}

void FlowTapeReader::fail(const std::string& what) const {
  throw InvalidArgument("flow replay file '" + path_.string() + "' " + what);
}

FlowRecord FlowTapeReader::next() {
  const std::string at = "record " + std::to_string(pos_.record) + " of " +
                         std::to_string(header_.records) + " (byte " + std::to_string(pos_.offset) +
                         ")";
  if (at_end()) fail("has no " + at + ": the run asks the fluid more than was recorded");
  if (file_size_ - pos_.offset < kRecordHead + 8) fail("is truncated at " + at);
  char head[kRecordHead];
  in_.read(head, sizeof head);
  std::uint32_t magic = 0;
  std::uint64_t ordinal = 0, size = 0;
  std::memcpy(&magic, head, 4);
  std::memcpy(&ordinal, head + 4, 8);
  std::memcpy(&size, head + 12, 8);
  if (!in_ || magic != kRecordMagic) fail("is corrupt at " + at + ": no record marker");
  if (ordinal != pos_.record)
    fail("is corrupt at " + at + ": it says record " + std::to_string(ordinal));
  if (size > file_size_ - pos_.offset - kRecordHead - 8) fail("is truncated at " + at);
  std::string checked(16 + size, '\0');
  std::memcpy(checked.data(), head + 4, 16);
  in_.read(checked.data() + 16, static_cast<std::streamsize>(size));
  std::uint64_t sum = 0;
  in_.read(reinterpret_cast<char*>(&sum), sizeof sum);
  if (!in_) fail("is truncated at " + at);
  if (fnv1a64(checked) != sum) fail("checksum mismatch at " + at + ": the file is corrupt");
  FlowRecord r;
  try {
    r = decode(std::string_view(checked).substr(16));
  } catch (const InvalidArgument& e) {
    fail("is corrupt at " + at + ": " + e.what());
  }
  pos_.record += 1;
  pos_.offset += kRecordHead + size + 8;
  return r;
}

void FlowTapeReader::seek(const FlowTapePosition& p) {
  if (p.offset < first_offset_ || p.offset > file_size_ || p.record > header_.records) {
    fail("has no record " + std::to_string(p.record) + " at byte " + std::to_string(p.offset));
  }
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(p.offset));
  pos_ = p;  // next() checks the ordinal found there
}

}  // namespace sadr::orchestrator
