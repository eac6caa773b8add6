// SPDX-License-Identifier: MIT
/// \file curve_keys.hpp
/// ZeroMQ CURVE key pairs for tcp between sadr and services started by hand
/// (`sadr keygen`, docs/cli.md "Security"). Keys are 40-character Z85 text.
///
/// Key file (written 0600; refused when group or others may read it):
///     # sadr CURVE key pair (sadr keygen) ...
///     public-key: <40 Z85 characters>
///     secret-key: <40 Z85 characters>
/// Public key file (FILE.pub) and authorized-keys files: lines
/// `public-key: KEY` or a bare KEY; blank lines and `#` comments are skipped.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sadr::wire {

struct CurveKeyPair {
  std::string public_key;  ///< Z85, 40 characters
  std::string secret_key;  ///< Z85, 40 characters
};

/// True when this libzmq was built with CURVE (zmq_has("curve")).
bool curve_available();
/// A new random key pair (libsodium/tweetnacl inside libzmq).
CurveKeyPair make_curve_keypair();
/// The text of a key file (with_secret) or of its FILE.pub (public key only).
std::string key_file_text(const CurveKeyPair& keys, bool with_secret);
/// Reads a key file written by write_key_files. Throws sadr::InvalidArgument
/// naming the file and line (bad key, missing key, readable by others).
CurveKeyPair read_key_file(const std::filesystem::path& file);
/// A public key given as Z85 text, or as a file holding one (FILE.pub or a
/// key file: its public key).
std::string read_public_key(const std::string& text_or_file);
/// Every public key in an authorized-keys file (at least one).
std::vector<std::string> read_authorized_keys(const std::filesystem::path& file);
/// True when `key` is 40 characters that decode as Z85 to 32 bytes.
bool valid_z85_key(const std::string& key);

}  // namespace sadr::wire
