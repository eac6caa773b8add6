// SPDX-License-Identifier: MIT
// Services launched by sadr accept only their run (issue #18): a per-run
// secret in the environment (SADR_RUN_SECRET), checked by ZeroMQ PLAIN + ZAP
// before any message reaches the service. Two processes: a service with a
// secret refuses clients without it or with a wrong one, while the client that
// has it goes on working; a live `sadr run` is unaffected by such a client.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <thread>

#include "cli_test_support.hpp"
#include "sadr/common/version.hpp"
#include "sadr/orchestrator/service_process.hpp"
#include "sadr/wire/curve_keys.hpp"
#include "sadr/wire/rpc.hpp"

namespace sadr::orchestrator {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;
using e2e::bin;

StatusCode handshake_code(const std::string& endpoint, const std::string& secret,
                          std::chrono::milliseconds timeout) {
  wire::set_client_secret(endpoint, secret);
  wire::RpcClient client(endpoint, "fluid_service", timeout);
  wire::set_client_secret(endpoint, "");
  try {
    client.handshake(common::v1::SERVICE_KIND_FLUID, kProtocolVersion);
    return StatusCode::kOk;
  } catch (const Error& e) {
    return e.code();
  }
}

/// A small moving scene: 3 frames (t = 0, 2, 4).
std::string live_scene(const std::string& name, int side) {
  const std::string l = std::to_string(side) + ".0";
  return "name: " + name + "\ndimension: 2\n" + "box: {lower: [0.0, 0.0], upper: [" + l + ", " + l +
         "], periodic: [true, true]}\n" + "particles: {spacing: 1.0}\n" +
         "fluid: {backend: sdpd, h_over_dx: 3.0, sound_speed: 10.0, shear_viscosity: 1.0, "
         "temperature: 0.01}\n" +
         "species:\n  - {name: A, diffusivity: 0.5, initial: [{count: 2}]}\n" +
         "time: {coupling_step: 0.5, end: 4.0}\noutput: {every: 2.0, formats: [csv]}\nseed: 3\n";
}

TEST(ServiceAuth, OnlyClientsWithTheRunSecretGetIn) {
  const std::string secret = "0123456789abcdef0123456789abcdef";
  const std::string ipc = "ipc:///tmp/sadr-auth-" + std::to_string(getpid());
  ServiceProcess proc(bin("fluid_service"), {"--endpoint", ipc, "--log-level", "error"},
                      "fluid_service", 20s, {"SADR_RUN_SECRET=" + secret});
  wire::set_client_secret(proc.endpoint(), secret);
  wire::RpcClient good(proc.endpoint(), "fluid_service", 20s);
  wire::set_client_secret(proc.endpoint(), "");
  ASSERT_NO_THROW(good.handshake(common::v1::SERVICE_KIND_FLUID, kProtocolVersion));
  // Without the secret, or with another one, the ZeroMQ handshake fails (no
  // request reaches the service) and the client is told at once: kUnavailable
  // within its 60 s timeout, not kDeadlineExceeded.
  EXPECT_EQ(handshake_code(proc.endpoint(), "", 60s), StatusCode::kUnavailable);
  EXPECT_EQ(handshake_code(proc.endpoint(), "fedcba9876543210fedcba9876543210", 60s),
            StatusCode::kUnavailable);
  // The client with the secret is unaffected, and so is the service.
  EXPECT_NO_THROW(good.handshake(common::v1::SERVICE_KIND_FLUID, kProtocolVersion));
  EXPECT_TRUE(proc.alive());
  EXPECT_EQ(handshake_code(proc.endpoint(), secret, 20s), StatusCode::kOk);
}

TEST(ServiceAuth, AServiceStartedWithoutASecretServesAnyLocalClient) {
  // Remote mode (`fluid_service --endpoint tcp://127.0.0.1:PORT` by hand): no
  // secret, as before.
  ServiceProcess proc(bin("fluid_service"),
                      {"--endpoint", "tcp://127.0.0.1:*", "--log-level", "error"}, "fluid_service");
  EXPECT_EQ(handshake_code(proc.endpoint(), "", 20s), StatusCode::kOk);
}

TEST(ServiceAuth, ALiveRunIsUnaffectedByAClientWithoutItsSecret) {
  const fs::path d = e2e::scratch("auth-live");
  const std::string scene_text = live_scene("live", 40);
  const fs::path scene = e2e::write_scene(d, scene_text);
  const std::string out = (d / "out").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(bin("sadr").c_str(), "sadr", "run", scene.c_str(), "-q", "-o", out.c_str(), nullptr);
    _exit(127);
  }
  // The run's fluid socket: <tmp>/sadr-run-<pid>-XXXXXX/fluid-0.
  std::string endpoint;
  for (int i = 0; i < 400 && endpoint.empty(); ++i) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(fs::temp_directory_path(), ec)) {
      const std::string name = e.path().filename().string();
      if (name.rfind("sadr-run-" + std::to_string(pid) + "-", 0) == 0 &&
          fs::exists(e.path() / "fluid-0")) {
        endpoint = "ipc://" + (e.path() / "fluid-0").string();
      }
    }
    std::this_thread::sleep_for(25ms);
  }
  ASSERT_FALSE(endpoint.empty()) << "no run directory of sadr pid " << pid;
  EXPECT_EQ(fs::status(fs::path(endpoint.substr(6)).parent_path()).permissions() & fs::perms::all,
            fs::perms::owner_all);  // 0700
  EXPECT_EQ(handshake_code(endpoint, "", 60s), StatusCode::kUnavailable);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(e2e::frames(d / "out").size(), 3u);  // t = 0, 2, 4
}

// ---- tcp with CURVE (sadr keygen; services started by hand) ----------------

TEST(ServiceAuth, ANonLoopbackBindNeedsKeysAndKeysMustBePrivate) {
  const fs::path d = e2e::scratch("auth-bind");
  EXPECT_EQ(e2e::run(bin("fluid_service") + " --endpoint 'tcp://0.0.0.0:*'", d / "a.log"), 2);
  EXPECT_NE(e2e::read_file(d / "a.log").find("needs CURVE keys (--key FILE --authorized-keys"),
            std::string::npos)
      << e2e::read_file(d / "a.log");
  ASSERT_EQ(e2e::run(bin("sadr") + " keygen " + (d / "svc.key").string(), d / "k.log"), 0);
  EXPECT_EQ(fs::status(d / "svc.key").permissions(),
            fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_NE(e2e::read_file(d / "k.log")
                .find("public key: " + wire::read_public_key((d / "svc.key.pub").string())),
            std::string::npos);
  // Never overwritten.
  EXPECT_EQ(e2e::run(bin("sadr") + " keygen " + (d / "svc.key").string(), d / "k2.log"), 5);
  ASSERT_EQ(e2e::run(bin("sadr") + " keygen " + (d / "cli.key").string(), d / "k.log"), 0);
  fs::copy_file(d / "cli.key.pub", d / "authorized");
  const std::string keys =
      " --key " + (d / "svc.key").string() + " --authorized-keys " + (d / "authorized").string();
  // With keys it binds every interface.
  ServiceProcess any(bin("fluid_service"),
                     {"--endpoint", "tcp://0.0.0.0:*", "--key", (d / "svc.key").string(),
                      "--authorized-keys", (d / "authorized").string(), "--log-level", "error"},
                     "fluid_service");
  EXPECT_TRUE(any.alive());
  // A key file others may read is refused.
  fs::permissions(d / "svc.key", fs::perms::group_read, fs::perm_options::add);
  EXPECT_EQ(e2e::run(bin("fluid_service") + " --endpoint 'tcp://127.0.0.1:*'" + keys, d / "p.log"),
            2);
  EXPECT_NE(e2e::read_file(d / "p.log").find("chmod 600"), std::string::npos);
}

TEST(ServiceAuth, OverTcpOnlyClientsWithAnAuthorizedKeyGetInAndALiveRunIsUnaffected) {
  const fs::path d = e2e::scratch("auth-curve");
  for (const char* k : {"svc", "cli", "intruder"}) {
    ASSERT_EQ(
        e2e::run(bin("sadr") + " keygen " + (d / (std::string(k) + ".key")).string(), d / "k.log"),
        0);
  }
  fs::copy_file(d / "cli.key.pub", d / "authorized");
  auto start = [&](const char* exe) {
    return std::make_unique<ServiceProcess>(
        bin(exe),
        std::vector<std::string>{"--endpoint", "tcp://127.0.0.1:*", "--key",
                                 (d / "svc.key").string(), "--authorized-keys",
                                 (d / "authorized").string(), "--log-level", "error"},
        exe);
  };
  auto fluid = start("fluid_service");
  auto ssa = start("ssa_service");
  const std::string svc_pub = wire::read_public_key((d / "svc.key.pub").string());
  auto code_with = [&](const std::string& key_file, const std::string& server_key) {
    wire::ClientCredentials c;
    if (!key_file.empty()) {
      c.keys = wire::read_key_file(d / key_file);
      c.server_public_key = server_key;
    }
    wire::set_client_credentials(fluid->endpoint(), c);
    wire::RpcClient client(fluid->endpoint(), "fluid_service", 60s);
    wire::set_client_credentials(fluid->endpoint(), {});
    try {
      client.handshake(common::v1::SERVICE_KIND_FLUID, kProtocolVersion);
      return StatusCode::kOk;
    } catch (const Error& e) {
      return e.code();
    }
  };
  // Refused at once (kUnavailable, within a 60 s timeout): no keys, a key
  // the service does not list, the wrong server key.
  EXPECT_EQ(code_with("", ""), StatusCode::kUnavailable);
  EXPECT_EQ(code_with("intruder.key", svc_pub), StatusCode::kUnavailable);
  EXPECT_EQ(code_with("cli.key", wire::read_public_key((d / "cli.key.pub").string())),
            StatusCode::kUnavailable);
  EXPECT_EQ(code_with("cli.key", svc_pub), StatusCode::kOk);

  // A live run over CURVE while an intruder knocks.
  const std::string scene_text = live_scene("curve", 30);
  const fs::path scene = e2e::write_scene(d, scene_text);
  const std::string remote = " --fluid " + fluid->endpoint() + " --ssa " + ssa->endpoint();
  const std::string out = (d / "out").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string cmd = bin("sadr") + " run " + scene.string() + " -q -o " + out + remote +
                            " --key " + (d / "cli.key").string() + " --server-key " +
                            (d / "svc.key.pub").string() + " > " + (d / "run.log").string() +
                            " 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), nullptr);
    _exit(127);
  }
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(code_with("intruder.key", svc_pub), StatusCode::kUnavailable);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << e2e::read_file(d / "run.log");
  EXPECT_EQ(e2e::frames(d / "out").size(), 3u);  // t = 0, 2, 4
  // Without keys, sadr is refused at once and says why (exit 3, not a timeout). --timeout 30
  // bounds the wait if the refusal were missed: this test twice ran past ctest's 300 s on a
  // loaded machine (2026-12-02, where it waited is not known), and the default 120 s per call
  // with a retry would pass 300 s here; bounded, it fails with its log instead.
  EXPECT_EQ(e2e::run(bin("sadr") + " run " + scene.string() + " -q --force --timeout 30 -o " + out +
                         remote,
                     d / "nokey.log"),
            3);
  EXPECT_NE(e2e::read_file(d / "nokey.log").find("security handshake failed (we offered NULL)"),
            std::string::npos)
      << e2e::read_file(d / "nokey.log");
  // A key without a server key is a usage mistake, named.
  EXPECT_EQ(e2e::run(bin("sadr") + " run " + scene.string() + " -q --force -o " + out + remote +
                         " --key " + (d / "cli.key").string(),
                     d / "half.log"),
            1);
  EXPECT_NE(e2e::read_file(d / "half.log").find("CURVE needs both --key FILE"), std::string::npos);
  EXPECT_TRUE(fluid->alive());
  EXPECT_TRUE(ssa->alive());
}

}  // namespace
}  // namespace sadr::orchestrator
