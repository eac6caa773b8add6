// SPDX-License-Identifier: MIT
#include "sadr/wire/curve_keys.hpp"

#include <sys/stat.h>
#include <zmq.h>

#include <cstdint>
#include <fstream>
#include <sstream>

#include "sadr/common/status.hpp"
#include "sadr/wire/rpc.hpp"

namespace sadr::wire {
namespace {

constexpr std::string_view kPublicTag = "public-key:";
constexpr std::string_view kSecretTag = "secret-key:";

std::string trim(std::string_view s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string_view::npos) return {};
  const auto b = s.find_last_not_of(" \t\r");
  return std::string(s.substr(a, b - a + 1));
}

struct KeyLines {
  std::vector<std::pair<int, std::string>> public_keys;  // (line, key)
  std::vector<std::pair<int, std::string>> secret_keys;
};

/// Reads `file` as key lines; a bare key counts as a public key. Throws
/// naming the file and line for anything else.
KeyLines read_key_lines(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InvalidArgument("cannot read key file '" + shorten(file.string()) + "'");
  KeyLines out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const auto where = [&] { return shorten(file.string()) + ":" + std::to_string(n); };
    if (t.size() > 200) throw InvalidArgument(where() + ": line too long for a key");
    std::string key = t;
    auto* list = &out.public_keys;
    if (t.rfind(kPublicTag, 0) == 0) {
      key = trim(t.substr(kPublicTag.size()));
    } else if (t.rfind(kSecretTag, 0) == 0) {
      key = trim(t.substr(kSecretTag.size()));
      list = &out.secret_keys;
    }
    if (!valid_z85_key(key)) {
      throw InvalidArgument(where() + ": '" + shorten(key, 48) +
                            "' is not a CURVE key (40 Z85 characters, as written by sadr keygen)");
    }
    list->emplace_back(n, key);
  }
  return out;
}

}  // namespace

bool curve_available() {
  return zmq_has("curve") != 0;
}

bool valid_z85_key(const std::string& key) {
  if (key.size() != 40) return false;
  std::uint8_t bytes[32];
  return zmq_z85_decode(bytes, key.c_str()) != nullptr;
}

CurveKeyPair make_curve_keypair() {
  if (!curve_available()) {
    throw Error(StatusCode::kUnavailable, "this libzmq has no CURVE support (zmq_has(\"curve\"))");
  }
  char pub[41], sec[41];
  if (zmq_curve_keypair(pub, sec) != 0) {
    throw Error(StatusCode::kInternal, "zmq_curve_keypair failed");
  }
  return {pub, sec};
}

std::string key_file_text(const CurveKeyPair& keys, bool with_secret) {
  std::ostringstream out;
  if (with_secret) {
    out << "# sadr CURVE key pair (sadr keygen). Keep this file private (mode 0600):\n"
           "# whoever has it can pose as its owner. Give others FILE.pub.\n";
  } else {
    out << "# sadr CURVE public key (sadr keygen): give it to the peers that must\n"
           "# reach or accept the owner of the key pair (docs/cli.md, \"Security\").\n";
  }
  out << kPublicTag << ' ' << keys.public_key << '\n';
  if (with_secret) out << kSecretTag << ' ' << keys.secret_key << '\n';
  return out.str();
}

CurveKeyPair read_key_file(const std::filesystem::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) {
    throw InvalidArgument("cannot read key file '" + shorten(file.string()) + "'");
  }
  if ((st.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    throw InvalidArgument(
        "key file '" + shorten(file.string()) + "' may be read or written by other users (mode " +
        std::to_string((st.st_mode >> 6) & 7) + std::to_string((st.st_mode >> 3) & 7) +
        std::to_string(st.st_mode & 7) + "): it holds a secret key; chmod 600 it");
  }
  const KeyLines lines = read_key_lines(file);
  if (lines.public_keys.size() != 1 || lines.secret_keys.size() != 1) {
    throw InvalidArgument("key file '" + shorten(file.string()) +
                          "' must hold one 'public-key:' and one 'secret-key:' line (it has " +
                          std::to_string(lines.public_keys.size()) + " and " +
                          std::to_string(lines.secret_keys.size()) +
                          "); make one with sadr keygen");
  }
  CurveKeyPair keys{lines.public_keys[0].second, lines.secret_keys[0].second};
  char derived[41];
  if (zmq_curve_public(derived, keys.secret_key.c_str()) != 0 ||
      keys.public_key != std::string(derived)) {
    throw InvalidArgument("key file '" + shorten(file.string()) + "' line " +
                          std::to_string(lines.public_keys[0].first) +
                          ": the public key does not belong to the secret key");
  }
  return keys;
}

std::string read_public_key(const std::string& text_or_file) {
  // A file first: a 40-character path such as "/tmp/sadr-cli-6311-a/svc.key.pub"
  // is also valid Z85.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(text_or_file, ec)) {
    if (valid_z85_key(text_or_file)) return text_or_file;
    throw InvalidArgument("'" + shorten(text_or_file, 48) +
                          "' is neither a CURVE public key (40 Z85 characters) nor a file");
  }
  const KeyLines lines = read_key_lines(text_or_file);
  if (lines.public_keys.size() != 1) {
    throw InvalidArgument("'" + shorten(text_or_file) + "' holds " +
                          std::to_string(lines.public_keys.size()) +
                          " public keys; expected one (a FILE.pub of sadr keygen)");
  }
  return lines.public_keys[0].second;
}

std::vector<std::string> read_authorized_keys(const std::filesystem::path& file) {
  const KeyLines lines = read_key_lines(file);
  if (!lines.secret_keys.empty()) {
    throw InvalidArgument(shorten(file.string()) + ":" +
                          std::to_string(lines.secret_keys[0].first) +
                          ": a secret key in an authorized-keys file; list public keys only "
                          "(the FILE.pub of each client's sadr keygen)");
  }
  if (lines.public_keys.empty()) {
    throw InvalidArgument("authorized-keys file '" + shorten(file.string()) +
                          "' lists no public key: no client could connect");
  }
  std::vector<std::string> out;
  for (const auto& [line, key] : lines.public_keys) out.push_back(key);
  return out;
}

}  // namespace sadr::wire
