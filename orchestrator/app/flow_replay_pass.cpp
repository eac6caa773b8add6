// SPDX-License-Identifier: MIT
// Flow replay (flow_replay.hpp): the fluid-only pass that writes an ensemble's
// OUTPUT/flow_replay.bin, the same file shared under a lock by the runs of a sweep
// or the tasks of an array, and which realizations replay it.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <thread>

#include "commands.hpp"
#include "sadr/common/log.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/flow_replay.hpp"
#include "sadr/orchestrator/scene_messages.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

fs::path flow_replay_path(const fs::path& dir) {
  return dir / std::string(kFlowTapeName);
}

namespace {

/// The fluid-only pass into `path` (flow_replay.hpp), its fluid_service started here.
/// `all_cores`: the pass runs alone, its fluid takes every core unless SADR_FLUID_THREADS
/// says otherwise (results do not depend on the thread count).
RecordedFlow record_flow_pass(const Scene& scene, const Plan& plan, const ServiceOptions& o,
                              const fs::path& path, bool all_cores) {
  const bool own_threads = all_cores && std::getenv("SADR_FLUID_THREADS") == nullptr;
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  if (own_threads) setenv("SADR_FLUID_THREADS", std::to_string(cores).c_str(), 1);
  struct Unset {
    bool on;
    ~Unset() {
      if (on) unsetenv("SADR_FLUID_THREADS");
    }
  } unset{own_threads};
  if (!o.quiet) {
    std::fprintf(stderr, "sadr: flow replay: computing the fluid once into %s\n",
                 path.string().c_str());
  }
  Plan fluid_only = plan;
  fluid_only.ssa_service = false;
  ServiceSet services(o.mode, fluid_only, o.remote, "flow");
  RecordFlowOptions ro;
  ro.path = path;
  ro.timeout = std::chrono::milliseconds(static_cast<long>(o.timeout_s * 1000));
  ro.liveness = [&services] { services.check_alive(); };
  ro.interrupt = &interrupt_flag();
  const RecordedFlow rec = record_flow(scene, plan, services.endpoints().fluid, ro);
  services.stop();
  if (rec.complete && !o.quiet) {
    std::fprintf(stderr,
                 "sadr: flow replay: %llu fluid calls recorded in %.1f s, %.1f MB in %s; "
                 "the runs replay them\n",
                 static_cast<unsigned long long>(rec.records), rec.seconds,
                 static_cast<double>(rec.bytes) / 1e6, path.string().c_str());
  }
  return rec;
}

/// An exclusive flock on `path` (created if missing), held until destruction; the kernel
/// releases it when the process ends, however it ends.
class FileLock {
 public:
  explicit FileLock(const fs::path& path)
      : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
    if (fd_ < 0) {
      throw IoError("cannot open the lock file '" + path.string() + "': " + std::strerror(errno));
    }
  }
  ~FileLock() { ::close(fd_); }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  /// Takes the lock: 0 when held, else the errno that refused it (EWOULDBLOCK: another
  /// process holds it).
  int try_lock() const {
    while (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      if (errno != EINTR) return errno;
    }
    return 0;
  }

 private:
  int fd_;
};

}  // namespace

fs::path prepare_flow_replay(const Scene& scene, const Plan& plan, const ServiceOptions& o,
                             const fs::path& dir) {
  const fs::path path = flow_replay_path(dir);
  if (fs::exists(path)) {  // an earlier pass (sadr resume): its header must match this fluid
    const FlowTapeReader existing(path, fluid_key(scene, plan));
    if (!o.quiet) {
      std::fprintf(stderr, "sadr: flow replay: the fluid's answers from %s (%llu records)\n",
                   path.string().c_str(),
                   static_cast<unsigned long long>(existing.header().records));
    }
    return path;
  }
  const RecordedFlow rec = record_flow_pass(scene, plan, o, path, true);
  return rec.complete ? path : fs::path();
}

SharedFlowTape shared_flow_tape(const Scene& scene, const Plan& plan, const ServiceOptions& o,
                                const fs::path& path) {
  SharedFlowTape out;
  const std::string key = fluid_key(scene, plan);
  const auto complete = [&] {
    if (!fs::exists(path)) return false;
    (void)FlowTapeReader(path, key);  // refuses a file of another fluid
    return true;
  };
  if (complete()) {
    out.path = path;
    return out;
  }
  ensure_directory(path.parent_path());
  fs::path lock_path = path;
  lock_path.replace_extension(".lock");
  const FileLock lock(lock_path);
  bool waiting = false;
  for (int e = lock.try_lock(); e != 0; e = lock.try_lock()) {
    if (e != EWOULDBLOCK) {
      out.reason = "no file lock on " + lock_path.string() + " (" + std::strerror(e) +
                   "): this run steps its own fluid";
      return out;
    }
    if (interrupt_requested()) {
      out.stopped = true;
      return out;
    }
    if (!waiting && !o.quiet) {
      std::fprintf(stderr, "sadr: flow replay: waiting for the run that records %s\n",
                   path.string().c_str());
    }
    waiting = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  // Ours until `lock` closes: another run finished the file while we waited, or we record it
  // (a partial file of a recorder that died is replaced).
  if (complete()) {
    out.path = path;
    return out;
  }
  const RecordedFlow rec = record_flow_pass(scene, plan, o, path, false);
  if (!rec.complete) {
    out.stopped = true;
    return out;
  }
  out.path = path;
  out.recorded = true;
  return out;
}

bool checkpoint_replays_flow(const fs::path& realization_dir) {
  const fs::path manifest = realization_dir / "checkpoint" / std::string(kCheckpointManifestName);
  if (!fs::exists(manifest)) return false;
  const LoadedCheckpoint cp = load_checkpoint(manifest, "");
  const auto blob = cp.blobs.find("fluid");
  return blob != cp.blobs.end() && is_flow_replay_snapshot(blob->second.bytes);
}

}  // namespace sadr::orchestrator
