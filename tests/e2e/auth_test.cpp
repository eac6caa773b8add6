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

TEST(ServiceAuth, OnlyClientsWithTheRunSecretGetIn) {
  const std::string secret = "0123456789abcdef0123456789abcdef";
  const std::string ipc = "ipc:///tmp/sadr-auth-" + std::to_string(getpid());
  ServiceProcess proc(bin("fluid_service"), {"--endpoint", ipc, "--log-level", "error"},
                      "fluid_service", 20s, {"SADR_RUN_SECRET=" + secret});
  wire::set_client_secret(proc.endpoint(), secret);
  wire::RpcClient good(proc.endpoint(), "fluid_service", 20s);
  wire::set_client_secret(proc.endpoint(), "");
  ASSERT_NO_THROW(good.handshake(common::v1::SERVICE_KIND_FLUID, kProtocolVersion));
  // Without the secret, or with another one, the ZeroMQ handshake fails: no
  // reply ever comes (and no request reaches the service).
  EXPECT_EQ(handshake_code(proc.endpoint(), "", 1500ms), StatusCode::kDeadlineExceeded);
  EXPECT_EQ(handshake_code(proc.endpoint(), "fedcba9876543210fedcba9876543210", 1500ms),
            StatusCode::kDeadlineExceeded);
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
  const std::string scene_text =
      "name: live\ndimension: 2\n"
      "box: {lower: [0.0, 0.0], upper: [40.0, 40.0], periodic: [true, true]}\n"
      "particles: {spacing: 1.0}\n"
      "fluid: {backend: sdpd, h_over_dx: 3.0, sound_speed: 10.0, shear_viscosity: 1.0, "
      "temperature: 0.01}\n"
      "species:\n  - {name: A, diffusivity: 0.5, initial: [{count: 2}]}\n"
      "time: {coupling_step: 0.5, end: 4.0}\noutput: {every: 2.0, formats: [csv]}\nseed: 3\n";
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
  EXPECT_EQ(handshake_code(endpoint, "", 1000ms), StatusCode::kDeadlineExceeded);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(e2e::frames(d / "out").size(), 3u);  // t = 0, 2, 4
}

}  // namespace
}  // namespace sadr::orchestrator
