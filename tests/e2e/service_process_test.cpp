// SPDX-License-Identifier: MIT
// Starts the real ssa_service and fluid_service executables as child
// processes and talks to them over ipc and tcp loopback: handshake, version
// refusal, wrong-service refusal, a small run through the wire, snapshot /
// restore identity, bad input reported with the field, clean exit on
// shutdown and on SIGTERM.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <thread>

#include "sadr/common/version.hpp"
#include "sadr/orchestrator/service_clients.hpp"
#include "sadr/orchestrator/service_process.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::orchestrator {
namespace {

using namespace std::chrono_literals;

std::string bin(const char* name) {
  return std::string(SADR_BINARY_DIR) + "/bin/" + name;
}

/// "ipc" -> a unique ipc endpoint; "tcp" -> loopback with an ephemeral port.
std::vector<std::string> endpoint_args(const std::string& transport, const char* tag) {
  if (transport == "tcp") return {"--endpoint", "tcp://127.0.0.1:*", "--log-level", "warn"};
  return {"--endpoint",
          "ipc:///tmp/sadr-e2e-" + std::to_string(getpid()) + "-" + tag + "-" +
              std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()),
          "--log-level", "warn"};
}

/// A 1D chain of n voxels on [0, 1], unit cross-section.
ssa::v1::InitRequest chain_init(int n, std::uint64_t seed) {
  ssa::v1::InitRequest init;
  ParticleState p;
  p.dimension = 1;
  p.resize(static_cast<std::size_t>(n), false);
  const double dx = 1.0 / (n - 1);
  for (int i = 0; i < n; ++i) {
    p.positions[3 * static_cast<std::size_t>(i)] = i * dx;
    p.masses[static_cast<std::size_t>(i)] = dx;
  }
  wire::to_proto(p, *init.mutable_particles());
  auto* m = init.mutable_model();
  Box box;
  box.dimension = 1;
  wire::to_proto(box, *m->mutable_box());
  m->set_smoothing_length(1.8 * dx);
  m->set_seed(seed);
  auto* a = m->add_species();
  a->set_name("A");
  a->set_stochastic(true);
  a->set_diffusivity(0.1);
  auto* birth = m->add_reactions();  // 0 -> A at 2000 per unit length per time
  birth->set_name("birth");
  auto* prod = birth->add_products();
  prod->set_species("A");
  prod->set_count(1);
  birth->set_rate(2000.0);
  auto* death = m->add_reactions();  // A -> 0 at 1 per time
  death->set_name("death");
  auto* reac = death->add_reactants();
  reac->set_species("A");
  reac->set_count(1);
  death->set_rate(1.0);
  auto* counts = init.mutable_counts()->add_species();
  counts->set_name("A");
  for (int i = 0; i < n; ++i) counts->add_counts(i == n / 2 ? 500 : 0);
  return init;
}

class ServiceE2E : public ::testing::TestWithParam<std::string> {};

TEST_P(ServiceE2E, SsaHandshakeRunSnapshotRestore) {
  ServiceProcess proc(bin("ssa_service"), endpoint_args(GetParam(), "ssa"), "ssa_service");
  SsaClient ssa(proc.endpoint(), 20s);
  EXPECT_EQ(ssa.hello().kind(), common::v1::SERVICE_KIND_SSA);
  EXPECT_EQ(ssa.hello().pid(), static_cast<std::uint32_t>(proc.pid()));

  const auto init = ssa.init(chain_init(17, 7));
  EXPECT_GT(init.edges(), 0u);
  ssa.set_run_id("e2e");
  const SsaStep r0 = ssa.advance(0, 0.5, {}, {"A"}, {});
  EXPECT_GT(r0.events, 0u);
  EXPECT_DOUBLE_EQ(r0.time, 0.5);
  // The copy numbers asked for come back with the step (the back-transfer).
  ASSERT_EQ(r0.counts.names, std::vector<std::string>{"A"});
  EXPECT_EQ(r0.counts.values[0], ssa.counts({"A"}).values[0]);
  // A resent step is not stepped again (idempotent retry).
  const SsaStep again = ssa.advance(0, 0.5, {}, {"A"}, {});
  EXPECT_EQ(again.events, r0.events);
  EXPECT_EQ(again.counts.values, r0.counts.values);

  const std::string snap_bytes = ssa.snapshot(1);
  common::v1::Snapshot snap;
  ASSERT_TRUE(snap.ParseFromString(snap_bytes));
  EXPECT_EQ(snap.format(), "sadr.ssa.nsm");
  ssa.advance(1, 1.0, {}, {}, {});
  const SpeciesCounts first = ssa.counts({});
  ssa.restore(snap_bytes);
  ssa.advance(2, 1.0, {}, {}, {});  // a new step index: the restored run continues
  const SpeciesCounts second = ssa.counts({});
  ASSERT_EQ(first.names.size(), 1u);
  EXPECT_EQ(first.values[0].size(), 17u);
  EXPECT_EQ(first.values, second.values) << "restored run must continue bit-identically";
  try {
    ssa.advance(3, 1.5, {}, {"Q"}, {});
    FAIL() << "an unknown species in return_counts must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("advance.return_counts[0]: unknown stochastic species "
                                         "'Q'"),
              std::string::npos)
        << e.what();
  }

  ssa.shutdown();
  for (int i = 0; i < 200 && proc.alive(); ++i) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(proc.describe(), "exited with code 0");
}

TEST_P(ServiceE2E, WrongProtocolVersionIsRefusedWithAClearMessage) {
  ServiceProcess proc(bin("ssa_service"), endpoint_args(GetParam(), "ver"), "ssa_service");
  wire::RpcClient raw(proc.endpoint(), "ssa_service", 20s);
  try {
    raw.handshake(common::v1::SERVICE_KIND_SSA, kProtocolVersion + 1);
    FAIL() << "a handshake for the next protocol version must be refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kProtocolMismatch);
    const std::string msg = e.what();
    const std::string v = std::to_string(kProtocolVersion);
    EXPECT_NE(msg.find("this ssa_service speaks sadr wire protocol v" + v +
                       ", the client asked for v" + std::to_string(kProtocolVersion + 1)),
              std::string::npos)
        << msg;
  }
  // The service survives a refused handshake and still serves a good client.
  SsaClient ok(proc.endpoint(), 20s);
  EXPECT_EQ(ok.hello().protocol_version(), kProtocolVersion);
}

TEST_P(ServiceE2E, ConnectingToTheWrongServiceIsRefused) {
  ServiceProcess proc(bin("ssa_service"), endpoint_args(GetParam(), "kind"), "ssa_service");
  try {
    FluidClient wrong(proc.endpoint(), 20s);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("this endpoint is ssa_service, the client expected "
                                         "fluid_service"),
              std::string::npos)
        << e.what();
  }
}

TEST_P(ServiceE2E, BadInputIsReportedWithTheFieldAndTheServiceSurvives) {
  ServiceProcess proc(bin("ssa_service"), endpoint_args(GetParam(), "bad"), "ssa_service");
  SsaClient ssa(proc.endpoint(), 20s);
  auto init = chain_init(5, 1);
  init.mutable_particles()->set_masses(2, -1.0);
  try {
    ssa.init(init);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("init.particles: particle 2: mass = -1"),
              std::string::npos)
        << e.what();
  }
  try {
    ssa.advance(0, 1.0, {}, {}, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kFailedPrecondition);
    EXPECT_NE(std::string(e.what()).find("send Init first"), std::string::npos) << e.what();
  }
  init = chain_init(5, 1);
  init.mutable_model()->mutable_reactions(0)->mutable_products(0)->set_species("Q");
  try {
    ssa.init(init);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("init.model.reactions[0].products[0].species = 'Q'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(ssa.init(chain_init(5, 1)));
}

TEST_P(ServiceE2E, FluidServiceStaticBackendOverTheWire) {
  ServiceProcess proc(bin("fluid_service"), endpoint_args(GetParam(), "fluid"), "fluid_service");
  FluidClient fluid(proc.endpoint(), 20s);
  EXPECT_EQ(fluid.hello().kind(), common::v1::SERVICE_KIND_FLUID);
  fluid::v1::InitRequest init;
  ParticleState p;
  p.dimension = 2;
  const int nx = 8;
  p.resize(nx * nx);
  for (int i = 0; i < nx * nx; ++i) {
    p.positions[3 * static_cast<std::size_t>(i)] = (i % nx + 0.5) / nx;
    p.positions[3 * static_cast<std::size_t>(i) + 1] = (i / nx + 0.5) / nx;
    p.masses[static_cast<std::size_t>(i)] = 1.0 / (nx * nx);
  }
  wire::to_proto(p, *init.mutable_particles());
  auto* m = init.mutable_model();
  m->set_backend("static");
  Box box;
  box.dimension = 2;
  box.periodic = {true, true, false};
  wire::to_proto(box, *m->mutable_box());
  m->set_smoothing_length(3.0 / nx);
  m->set_reference_density(1.0);
  m->set_sound_speed(1.0);
  const auto rep = fluid.init(init);
  fluid.set_run_id("e2e");
  const FluidStep a = fluid.advance(0, 0.1, false, {}, {});
  EXPECT_FALSE(a.particles_moved);
  EXPECT_NEAR(a.time, 0.1, 1e-15);
  const FluidFrame st = fluid.frame({});
  EXPECT_EQ(st.particles.size(), static_cast<std::size_t>(nx * nx));
  EXPECT_EQ(st.particles.positions[3], p.positions[3]);

  // Unknown backend: the error lists the known ones.
  m->set_backend("lbm");
  try {
    fluid.init(init);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sdpd"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("lbm"), std::string::npos) << e.what();
  }
}

// Back-transfer: copy numbers ride on the fluid's Advance, and the service sets
// C_i = X_i / V_i with its own volumes V_i = m_i / rho_i before stepping.
TEST_P(ServiceE2E, FluidSetsBackTransferredCountsOverItsOwnVolumes) {
  ServiceProcess proc(bin("fluid_service"), endpoint_args(GetParam(), "btr"), "fluid_service");
  FluidClient fluid(proc.endpoint(), 20s);
  fluid::v1::InitRequest init;
  ParticleState p;
  p.dimension = 1;
  const int n = 8;
  p.resize(n);
  for (int i = 0; i < n; ++i) {
    p.positions[3 * static_cast<std::size_t>(i)] = (i + 0.5) / n;
    p.masses[static_cast<std::size_t>(i)] = (1.0 + 0.1 * i) / n;  // unequal volumes
  }
  wire::to_proto(p, *init.mutable_particles());
  auto* m = init.mutable_model();
  m->set_backend("static");
  Box box;
  box.dimension = 1;
  box.periodic = {true, false, false};
  wire::to_proto(box, *m->mutable_box());
  m->set_smoothing_length(3.0 / n);
  m->set_reference_density(1.0);
  auto* sp = m->add_species();
  sp->set_name("B");
  sp->set_stochastic(true);
  fluid.init(init);
  fluid.set_run_id("btr");
  SpeciesCounts counts;
  counts.names = {"B"};
  counts.values = {{0, 1, 2, 3, 5, 8, 13, 21}};
  fluid.advance(0, 0.1, false, counts, {});
  const FluidFrame f = fluid.frame({"B"});
  ASSERT_EQ(f.concentrations.size(), 1u);
  const auto& c = f.concentrations[0].second;
  ASSERT_EQ(c.size(), static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(c[i], static_cast<double>(counts.values[0][i]) / f.particles.volume(i)) << i;
  }
  EXPECT_NE(f.particles.volume(0), f.particles.volume(7));
  counts.values[0].pop_back();
  try {
    fluid.advance(1, 0.1, false, counts, {});
    FAIL() << "a count per particle is required";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("advance.counts.species[0] has 7 counts, expected 8"),
              std::string::npos)
        << e.what();
  }
}

TEST_P(ServiceE2E, SigtermStopsAServiceCleanly) {
  ServiceProcess proc(bin("ssa_service"), endpoint_args(GetParam(), "term"), "ssa_service");
  SsaClient ssa(proc.endpoint(), 20s);
  ASSERT_TRUE(proc.alive());
  kill(proc.pid(), SIGTERM);
  for (int i = 0; i < 300 && proc.alive(); ++i) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(proc.describe(), "exited with code 0");
}

INSTANTIATE_TEST_SUITE_P(Transports, ServiceE2E, ::testing::Values("ipc", "tcp"),
                         [](const auto& param_info) { return param_info.param; });

TEST(ServiceProcess, MissingExecutableIsNamed) {
  try {
    ServiceProcess p("/nonexistent/ssa_service", {}, "ssa_service");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot start ssa_service: '/nonexistent/ssa_service'"),
              std::string::npos)
        << e.what();
  }
}

TEST(ServiceProcess, BadCommandLineExitsWithCode2BeforeAnnouncing) {
  try {
    ServiceProcess p(bin("ssa_service"), {"--no-such-flag"}, "ssa_service", 10s);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("exited before announcing its endpoint: exited with "
                                         "code 2"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sadr::orchestrator
