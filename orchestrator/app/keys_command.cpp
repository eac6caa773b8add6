// SPDX-License-Identifier: MIT
// `sadr keygen` and the CURVE keys of --fluid/--ssa (docs/cli.md, "Security").
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "cli.hpp"
#include "commands.hpp"
#include "sadr/common/log.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/wire/curve_keys.hpp"
#include "sadr/wire/rpc.hpp"

namespace sadr::orchestrator {
namespace {

/// Creates `path` with `mode` (never replacing an existing file) and writes `text`.
void write_new_file(const std::string& path, const std::string& text, mode_t mode) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
  if (fd < 0) {
    throw IoError(
        "cannot create '" + path + "': " + std::strerror(errno) +
        (errno == EEXIST ? " (sadr keygen never overwrites a key; remove it first)" : ""));
  }
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) &&
                  ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) throw IoError("cannot write '" + path + "': " + std::strerror(errno));
}

int cmd_keygen(const std::string& file, bool show) {
  if (show) {
    std::printf("%s\n", wire::read_public_key(file).c_str());
    return kExitOk;
  }
  const wire::CurveKeyPair keys = wire::make_curve_keypair();
  const std::string pub = file + ".pub";
  if (::access(pub.c_str(), F_OK) == 0) {
    throw IoError("'" + pub + "' exists: sadr keygen never overwrites a key; remove it first");
  }
  write_new_file(file, wire::key_file_text(keys, true), 0600);
  write_new_file(pub, wire::key_file_text(keys, false), 0644);
  std::printf("public key: %s\nkey pair: %s (mode 0600, keep it private)\npublic key file: %s\n",
              keys.public_key.c_str(), file.c_str(), pub.c_str());
  return kExitOk;
}

}  // namespace

Subcommand add_keygen_command(CLI::App& app) {
  struct KeygenOptions {
    std::string file;
    bool show = false;
  };
  auto o = std::make_shared<KeygenOptions>();
  auto* keygen = app.add_subcommand(
      "keygen",
      "write a CURVE key pair for tcp between sadr and services started by hand: FILE "
      "(mode 0600) and FILE.pub (docs/cli.md, \"Security\")");
  keygen->add_option("file", o->file, "the key pair file to create (never overwritten)")
      ->required();
  keygen->add_flag("--show", o->show, "print the public key of an existing FILE instead");

  return {keygen, [o] { return cmd_keygen(o->file, o->show); }};
}

void use_remote_keys(const ServiceOptions& o) {
  const RemoteKeys& k = o.remote_keys;
  const bool any_server_key =
      !k.server_key.empty() || !k.fluid_server_key.empty() || !k.ssa_server_key.empty();
  if (o.mode != ServiceMode::kRemote) {
    if (!k.key.empty() || any_server_key) {
      throw Error(StatusCode::kFailedPrecondition,
                  "--key and --server-key are for services started by hand (--fluid/--ssa "
                  "ENDPOINT); the services sadr launches use a per-run secret");
    }
    return;
  }
  const std::pair<const std::string*, const std::string*> services[] = {
      {&o.remote.fluid, &k.fluid_server_key}, {&o.remote.ssa, &k.ssa_server_key}};
  if (k.key.empty() != !any_server_key) {
    throw Error(StatusCode::kFailedPrecondition,
                "CURVE needs both --key FILE (this side's key pair) and --server-key KEY "
                "(the services' public key; or --fluid-server-key/--ssa-server-key)");
  }
  if (k.key.empty()) {
    for (const auto& [endpoint, unused] : services) {
      if (!endpoint->empty() && !wire::is_local_endpoint(*endpoint)) {
        log::warn("the connection to '", wire::shorten(*endpoint),
                  "' is neither encrypted nor authenticated: give --key and --server-key "
                  "(sadr keygen; docs/cli.md, \"Security\")");
      }
    }
    return;
  }
  wire::ClientCredentials c;
  c.keys = wire::read_key_file(k.key);
  for (const auto& [endpoint, own_key] : services) {
    if (endpoint->empty()) continue;
    const std::string& server_key = own_key->empty() ? k.server_key : *own_key;
    if (server_key.empty()) {
      throw Error(StatusCode::kFailedPrecondition,
                  "no server key for '" + wire::shorten(*endpoint) +
                      "': give --server-key (or --fluid-server-key/--ssa-server-key)");
    }
    c.server_public_key = wire::read_public_key(server_key);
    wire::set_client_credentials(*endpoint, c);
  }
}

}  // namespace sadr::orchestrator
