// SPDX-License-Identifier: MIT
#include "sadr/wire/shared_geometry.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "sadr/common/status.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::wire {

struct SharedGeometry::Header {
  char magic[8];              ///< "SADRGEO"
  std::uint32_t version;      ///< kVersion
  std::uint32_t reserved0;    ///< 0
  std::uint64_t capacity;     ///< particles one slot holds
  std::uint64_t latest;       ///< last generation written (0 = never written)
  std::uint64_t reserved[4];  ///< pads the header to 64 bytes
};

/// One slot of the double buffer: generation g lives in slot g % 2.
struct SharedGeometry::Slot {
  std::uint64_t generation;  ///< held by the slot; 0 = never written or being written
  std::uint64_t count;       ///< particles of that write
  std::uint32_t dimension;   ///< of that write
  std::uint32_t has_kinds;   ///< 1: the slot's kinds bytes hold that write's kinds
  double time;               ///< simulated time of that write
};

namespace {

constexpr char kMagic[8] = {'S', 'A', 'D', 'R', 'G', 'E', 'O', '\0'};
constexpr std::uint32_t kVersion = 3;  // 2: two slots (double buffer); 3: + kinds
constexpr std::size_t kHeaderBytes = 64;
constexpr std::size_t kSlotHeaderBytes = 32;
constexpr std::size_t kSlots = 2;
constexpr std::size_t kMetaBytes = kHeaderBytes + kSlots * kSlotHeaderBytes;

/// Bytes of one slot's kinds (one byte per particle), padded to 8.
std::size_t kind_bytes(std::size_t capacity) {
  return (capacity + 7) / 8 * 8;
}

std::size_t bytes_for(std::size_t capacity) {
  // per slot: 3N positions, N densities, N masses (doubles), then per slot N kinds (bytes)
  return kMetaBytes + kSlots * (5 * capacity * sizeof(double) + kind_bytes(capacity));
}

std::string system_error(const std::string& what, const std::string& name) {
  return what + " '" + name + "': " + std::strerror(errno);
}

}  // namespace

namespace {
constexpr std::string_view kSegmentPrefix = "sadr-geometry-";

/// Calls f(name, pid) for every /dev/shm/sadr-geometry-<pid>-<k> of this user.
template <typename F>
std::size_t for_each_segment(F&& f) {
  std::size_t n = 0;
  DIR* dir = ::opendir("/dev/shm");
  if (dir == nullptr) return 0;
  while (const dirent* e = ::readdir(dir)) {
    const std::string_view name(e->d_name);
    if (name.substr(0, kSegmentPrefix.size()) != kSegmentPrefix) continue;
    const std::string rest(name.substr(kSegmentPrefix.size()));
    char* end = nullptr;
    const long pid = std::strtol(rest.c_str(), &end, 10);
    if (pid <= 0 || *end != '-') continue;
    struct stat st {};
    std::string path = "/dev/shm/";
    path.append(name);
    if (::stat(path.c_str(), &st) != 0 || st.st_uid != ::getuid()) continue;
    if (f(pid) && ::shm_unlink(path.c_str() + 8) == 0) ++n;  // the name: "/sadr-geometry-..."
  }
  ::closedir(dir);
  return n;
}
}  // namespace

std::size_t remove_segments_of(long pid) {
  return for_each_segment([pid](long owner) { return owner == pid; });
}

std::size_t remove_segments_of_dead_processes() {
  return for_each_segment(
      [](long owner) { return ::kill(static_cast<pid_t>(owner), 0) != 0 && errno == ESRCH; });
}

SharedGeometry SharedGeometry::create(std::size_t capacity) {
  static_assert(sizeof(Header) == kHeaderBytes);
  static_assert(sizeof(Slot) == kSlotHeaderBytes);
  static std::atomic<unsigned> counter{0};
  SharedGeometry g;
  g.name_ = "/sadr-geometry-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  const int fd = ::shm_open(g.name_.c_str(), O_RDWR | O_CREAT | O_EXCL, 0600);
  if (fd < 0) throw Error(StatusCode::kInternal, system_error("shm_open", g.name_));
  g.owner_ = true;  // from here on the destructor unlinks the name
  g.bytes_ = bytes_for(capacity);
  // Reserve the memory now: a size-limited /dev/shm (e.g. 64 MiB in a container)
  // then fails here, cleanly, instead of with SIGBUS at the first write.
  if (const int err = ::posix_fallocate(fd, 0, static_cast<off_t>(g.bytes_)); err != 0) {
    ::close(fd);
    errno = err;
    throw Error(StatusCode::kInternal, system_error("cannot reserve " + std::to_string(g.bytes_) +
                                                        " bytes for shared-memory segment",
                                                    g.name_));
  }
  void* p = ::mmap(nullptr, g.bytes_, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  ::close(fd);
  if (p == MAP_FAILED) throw Error(StatusCode::kInternal, system_error("mmap", g.name_));
  g.base_ = p;
  Header* h = g.header();
  std::memset(h, 0, kMetaBytes);
  std::memcpy(h->magic, kMagic, sizeof kMagic);
  h->version = kVersion;
  h->capacity = capacity;
  return g;
}

SharedGeometry SharedGeometry::open(const std::string& name, std::string_view where) {
  auto fail = [&](const std::string& why) {
    return InvalidArgument(std::string(where) + " = '" + name + "': " + why,
                           {{"field", std::string(where)}, {"value", name}});
  };
  // A POSIX shm name: one leading '/', no other '/', and ours start with /sadr-.
  if (name.rfind("/sadr-", 0) != 0 || name.find('/', 1) != std::string::npos || name.size() > 200) {
    throw fail("not a sadr shared-memory segment name (allowed: /sadr-...)");
  }
  const int fd = ::shm_open(name.c_str(), O_RDWR, 0);
  if (fd < 0) {
    throw fail(std::string("cannot open the shared-memory segment (") + std::strerror(errno) +
               "; the geometry segment only works for services on the orchestrator's host)");
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || static_cast<std::size_t>(st.st_size) < kMetaBytes) {
    ::close(fd);
    throw fail("segment too small for its header");
  }
  SharedGeometry g;
  g.name_ = name;
  g.bytes_ = static_cast<std::size_t>(st.st_size);
  void* p = ::mmap(nullptr, g.bytes_, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  ::close(fd);
  if (p == MAP_FAILED) throw fail(std::string("mmap failed: ") + std::strerror(errno));
  g.base_ = p;
  const Header* h = g.header();
  if (std::memcmp(h->magic, kMagic, sizeof kMagic) != 0 || h->version != kVersion) {
    throw fail("not a sadr geometry segment of version " + std::to_string(kVersion));
  }
  if (h->capacity > (g.bytes_ - kMetaBytes) / (kSlots * 5 * sizeof(double)) ||
      bytes_for(static_cast<std::size_t>(h->capacity)) > g.bytes_) {
    throw fail("header capacity " + std::to_string(h->capacity) + " exceeds the segment size " +
               std::to_string(g.bytes_));
  }
  return g;
}

SharedGeometry::SharedGeometry(SharedGeometry&& o) noexcept
    : name_(std::move(o.name_)),
      base_(std::exchange(o.base_, nullptr)),
      bytes_(std::exchange(o.bytes_, 0)),
      owner_(std::exchange(o.owner_, false)) {}

SharedGeometry& SharedGeometry::operator=(SharedGeometry&& o) noexcept {
  if (this != &o) {
    this->~SharedGeometry();
    new (this) SharedGeometry(std::move(o));
  }
  return *this;
}

SharedGeometry::~SharedGeometry() {
  if (owner_) unlink();
  if (base_ != nullptr) ::munmap(base_, bytes_);
  base_ = nullptr;
}

void SharedGeometry::unlink() {
  if (!owner_) return;
  ::shm_unlink(name_.c_str());  // ENOENT (already gone) is fine
  owner_ = false;
}

std::size_t SharedGeometry::capacity() const {
  return valid() ? static_cast<std::size_t>(header()->capacity) : 0;
}

SharedGeometry::Header* SharedGeometry::header() const {
  return static_cast<Header*>(base_);
}
SharedGeometry::Slot* SharedGeometry::slot(std::uint64_t generation) const {
  return reinterpret_cast<Slot*>(static_cast<char*>(base_) + kHeaderBytes +
                                 (generation % kSlots) * kSlotHeaderBytes);
}
double* SharedGeometry::data(std::uint64_t generation) const {
  const std::size_t cap = static_cast<std::size_t>(header()->capacity);
  return reinterpret_cast<double*>(static_cast<char*>(base_) + kMetaBytes) +
         (generation % kSlots) * 5 * cap;
}

std::uint8_t* SharedGeometry::kinds(std::uint64_t generation) const {
  const std::size_t cap = static_cast<std::size_t>(header()->capacity);
  return static_cast<std::uint8_t*>(base_) + kMetaBytes + kSlots * 5 * cap * sizeof(double) +
         (generation % kSlots) * kind_bytes(cap);
}

std::uint64_t SharedGeometry::write(const ParticleState& p, double time) {
  Header* h = header();
  const std::size_t n = p.size(), cap = static_cast<std::size_t>(h->capacity);
  if (n > cap || p.positions.size() != 3 * n || p.densities.size() != n || p.masses.size() != n) {
    throw InvalidArgument("shared geometry '" + name_ + "': " + std::to_string(n) +
                          " particles do not fit its capacity " + std::to_string(cap));
  }
  const std::uint64_t g = h->latest + 1;
  Slot* s = slot(g);
  // Sequence lock: the slot holds no generation while it is written, so a
  // reader of the generation it held before (g - 2) fails instead of mixing.
  std::atomic_ref<std::uint64_t>(s->generation).store(0, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);
  double* d = data(g);
  std::memcpy(d, p.positions.data(), 3 * n * sizeof(double));
  std::memcpy(d + 3 * cap, p.densities.data(), n * sizeof(double));
  std::memcpy(d + 4 * cap, p.masses.data(), n * sizeof(double));
  s->has_kinds = p.kinds.size() == n ? 1 : 0;
  if (s->has_kinds) std::memcpy(kinds(g), p.kinds.data(), n);
  s->dimension = static_cast<std::uint32_t>(p.dimension);
  s->count = n;
  s->time = time;
  std::atomic_ref<std::uint64_t>(s->generation).store(g, std::memory_order_release);
  std::atomic_ref<std::uint64_t>(h->latest).store(g, std::memory_order_release);
  return g;
}

void SharedGeometry::read(std::uint64_t generation, const ParticleState& previous,
                          ParticleState& out, std::string_view where) const {
  const std::size_t cap = static_cast<std::size_t>(header()->capacity);
  const Slot* s = slot(generation);
  auto stale = [&](std::uint64_t held, const char* when) {
    return InvalidArgument(std::string(where) + ": shared geometry '" + name_ +
                               "' holds generation " + std::to_string(held) +
                               " in the slot of generation " + std::to_string(generation) + when +
                               ", the request names " + std::to_string(generation) +
                               " (stale, overwritten or foreign segment)",
                           {{"field", std::string(where)}, {"value", std::to_string(generation)}});
  };
  const auto gen_ref = std::atomic_ref<std::uint64_t>(const_cast<std::uint64_t&>(s->generation));
  if (const std::uint64_t held = gen_ref.load(std::memory_order_acquire);
      generation == 0 || held != generation) {
    throw stale(held, "");
  }
  const std::size_t n = static_cast<std::size_t>(s->count);
  if (n != previous.size() || n > cap) {
    throw InvalidArgument(std::string(where) + ": shared geometry '" + name_ + "' holds " +
                          std::to_string(n) + " particles, expected " +
                          std::to_string(previous.size()) +
                          " (the particle set cannot change after Init)");
  }
  const double* d = data(generation);
  out.dimension = static_cast<int>(s->dimension);
  out.positions.assign(d, d + 3 * n);
  out.densities.assign(d + 3 * cap, d + 3 * cap + n);
  out.masses.assign(d + 4 * cap, d + 4 * cap + n);
  const bool with_kinds = s->has_kinds == 1;
  if (with_kinds) {
    const std::uint8_t* k = kinds(generation);
    out.kinds.resize(n);
    std::memcpy(out.kinds.data(), k, n);
  }
  std::atomic_thread_fence(std::memory_order_acquire);
  if (const std::uint64_t held = gen_ref.load(std::memory_order_relaxed); held != generation) {
    throw stale(held, " after the copy (overwritten while reading)");
  }
  out.velocities.clear();
  if (!with_kinds) out.kinds.clear();
  finish_geometry(previous, out, where);
}

}  // namespace sadr::wire
