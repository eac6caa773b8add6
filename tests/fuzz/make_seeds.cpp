// SPDX-License-Identifier: MIT
// Writes the binary part of the seed corpus (tests/fuzz/corpus/<target>/):
// message sequences of both services, snapshot blobs, RPC frames, a checkpoint
// manifest and a CSV frame, all made by the real code from kSmallScene, so the
// seeds follow the wire protocol and the blob layouts of this build.
//   make_seeds tests/fuzz/corpus      (tests/fuzz/README.md)
// Text seeds (scenes, particle CSV files) are kept by hand in the corpus.
#include <cstdio>
#include <filesystem>
#include <map>

#include "fuzz_messages.hpp"
#include "sadr/common/v1/frame.pb.h"
#include "sadr/common/version.hpp"
#include "sadr/fluid/fluid_service.hpp"
#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/seeds.hpp"
#include "sadr/ssa/ssa_service.hpp"

namespace fs = std::filesystem;
using sadr::fuzz::join_chunks;

namespace {

fs::path g_root;

void seed(const std::string& target, const std::string& name, const std::string& bytes) {
  const fs::path dir = g_root / target;
  fs::create_directories(dir);
  sadr::fuzz::write_file(dir / name, bytes);
}

/// Runs `requests` through a fresh handler and returns the replies.
template <class Handler, class Reply, class Request>
std::vector<Reply> run(const std::vector<Request>& requests) {
  Handler h;
  bool shutdown = false;
  std::vector<Reply> out;
  for (const auto& r : requests) {
    Reply rep;
    rep.ParseFromString(h.handle(r.SerializeAsString(), shutdown));
    if (rep.status().code() != 0) {
      std::fprintf(stderr, "make_seeds: request %zu failed: %s\n", out.size(),
                   rep.status().message().c_str());
      std::exit(1);
    }
    out.push_back(rep);
  }
  return out;
}

template <class Request>
std::string chunks(const std::vector<Request>& requests) {
  std::vector<std::string> c;
  for (const auto& r : requests) c.push_back(r.SerializeAsString());
  return join_chunks(c);
}

void ssa_seeds() {
  using sadr::ssa::v1::SsaReply;
  using sadr::ssa::v1::SsaRequest;
  const auto& inits = sadr::fuzz::small_inits(0);
  SsaRequest init;
  *init.mutable_init() = inits.ssa;
  SsaRequest adv;
  adv.mutable_advance()->set_run_id("seed");
  adv.mutable_advance()->set_step_index(0);
  adv.mutable_advance()->set_t_end(0.05);
  SsaRequest counts;
  counts.mutable_get_counts();
  SsaRequest snap;
  snap.mutable_snapshot()->set_step_index(1);
  const auto replies =
      run<sadr::ssa::SsaServiceHandler, SsaReply>(std::vector{init, adv, counts, snap});
  SsaRequest restore;
  *restore.mutable_restore()->mutable_snapshot() = replies[3].snapshot().snapshot();
  SsaRequest adv2 = adv;
  adv2.mutable_advance()->set_step_index(1);
  adv2.mutable_advance()->set_t_end(0.1);
  *adv2.mutable_advance()->mutable_particles() = inits.fluid.particles();  // a moved geometry
  adv2.mutable_advance()->mutable_particles()->clear_ids();
  adv2.mutable_advance()->add_return_counts("A");
  SsaRequest shutdown;
  shutdown.mutable_shutdown();
  seed("ssa_requests", "init", chunks(std::vector{init}));
  seed("ssa_requests", "init_advance_counts_snapshot",
       chunks(std::vector{init, adv, counts, snap}));
  seed("ssa_requests", "restore_advance_particles",
       chunks(std::vector{init, restore, adv2, counts, shutdown}));
  seed("ssa_requests", "advance_before_init", chunks(std::vector{adv, snap, restore}));
  seed("ssa_restore", "after_one_step", replies[3].snapshot().snapshot().blob());
}

void fluid_seeds(std::size_t b) {
  using sadr::fluid::v1::FluidReply;
  using sadr::fluid::v1::FluidRequest;
  const std::string backend(sadr::fuzz::kBackends[b]);
  const auto& inits = sadr::fuzz::small_inits(b);
  FluidRequest init;
  *init.mutable_init() = inits.fluid;
  FluidRequest adv;
  adv.mutable_advance()->set_run_id("seed");
  adv.mutable_advance()->set_step_index(0);
  adv.mutable_advance()->set_time_step(0.05);
  adv.mutable_advance()->set_return_state(true);
  FluidRequest state;
  state.mutable_get_state()->set_velocities(true);
  state.mutable_get_state()->add_species("B");
  FluidRequest snap;
  snap.mutable_snapshot()->set_step_index(1);
  const auto replies =
      run<sadr::fluid::FluidServiceHandler, FluidReply>(std::vector{init, adv, state, snap});
  FluidRequest set;
  *set.mutable_set_species()->mutable_concentrations() = replies[2].get_state().concentrations();
  FluidRequest restore;
  *restore.mutable_restore()->mutable_snapshot() = replies[3].snapshot().snapshot();
  FluidRequest adv2 = adv;
  adv2.mutable_advance()->set_step_index(1);
  FluidRequest shutdown;
  shutdown.mutable_shutdown();
  seed("fluid_requests", backend + "_init", chunks(std::vector{init}));
  seed("fluid_requests", backend + "_init_advance_state_snapshot",
       chunks(std::vector{init, adv, state, snap}));
  seed("fluid_requests", backend + "_set_restore_advance",
       chunks(std::vector{init, set, restore, adv2, state, shutdown}));
  seed("fluid_requests", backend + "_before_init", chunks(std::vector{adv, state, set, restore}));
  seed("fluid_restore", backend + "_after_one_step",
       std::string(1, static_cast<char>(b)) + replies[3].snapshot().snapshot().blob());
}

std::string header(const std::string& type, unsigned version = sadr::kProtocolVersion) {
  sadr::common::v1::FrameHeader h;
  h.set_protocol_version(version);
  h.set_message_type(type);
  h.set_sequence(1);
  return h.SerializeAsString();
}

void frame_seeds() {
  sadr::common::v1::HandshakeRequest hs;
  hs.set_protocol_version(sadr::kProtocolVersion);
  hs.set_expected_kind(sadr::common::v1::SERVICE_KIND_SSA);
  hs.set_client_name("seed");
  const std::string hsh = header("sadr.common.v1.HandshakeRequest");
  const std::string req = header("sadr.fuzz.Request");
  seed("frame", "handshake_request", join_chunks({hsh, hs.SerializeAsString(), req, "body"}));
  seed("frame", "request_before_handshake", join_chunks({req, "body", hsh, ""}));
  seed("frame", "wrong_version",
       join_chunks({header("sadr.fuzz.Request", sadr::kProtocolVersion + 1), "x"}));
  auto fluid = hs;
  fluid.set_expected_kind(sadr::common::v1::SERVICE_KIND_FLUID);
  seed("frame", "wrong_kind_then_type",
       join_chunks({hsh, fluid.SerializeAsString(), header("sadr.other.Request"), "x"}));
  seed("frame", "garbage_header", join_chunks({"\xff\xff\xff", "x"}));
}

void file_seeds() {
  namespace o = sadr::orchestrator;
  const auto scene = o::parse_scene(sadr::fuzz::kSmallScene, "fuzz.yaml");
  const fs::path tmp = sadr::fuzz::scratch_dir();
  std::vector<o::SpeciesColumn> species{{"A", std::vector<double>(scene.particles.size(), 3.0)},
                                        {"B", std::vector<double>(scene.particles.size(), 0.5)}};
  o::write_frame_csv(tmp / "frame.csv", 0.1, scene.particles, species);
  std::ifstream f(tmp / "frame.csv");
  seed("ensemble_csv", "frame_25_particles",
       std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>()));
  o::CheckpointManifest m;
  m.sadr_version = "seed";
  m.scene_hash = "0123456789abcdef";
  m.seed = sadr::orchestrator::realization_seed(7, 0);
  m.step_index = 2;
  m.time = 0.2;
  o::write_checkpoint(tmp / "ckpt", m, {{"ssa", {"nsm", "blob"}}});
  std::ifstream c(tmp / "ckpt" / "checkpoint.json");
  seed("checkpoint_manifest", "two_steps",
       std::string((std::istreambuf_iterator<char>(c)), std::istreambuf_iterator<char>()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_seeds CORPUS_DIR\n");
    return 2;
  }
  g_root = argv[1];
  ssa_seeds();
  fluid_seeds(0);
  fluid_seeds(1);
  frame_seeds();
  file_seeds();
  std::printf("make_seeds: wrote the binary seeds under %s\n", g_root.c_str());
  return 0;
}
