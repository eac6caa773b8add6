// SPDX-License-Identifier: MIT
/// \file hash.hpp
/// FNV-1a 64-bit hash used to identify scene files and checkpoint blobs.
/// Not cryptographic: it detects accidental mismatches, not tampering.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace sadr::orchestrator {

/// FNV-1a 64 of the bytes (offset basis 0xcbf29ce484222325, prime 0x100000001b3).
constexpr std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

/// "fnv1a64:" followed by 16 lower-case hex digits.
std::string content_hash(std::string_view bytes);

/// content_hash() of a file's bytes. @throws sadr::InvalidArgument if unreadable.
std::string file_hash(const std::filesystem::path& path);

/// The whole file as bytes. @throws sadr::InvalidArgument naming the path (and `what`) when it
/// cannot be read, is not a regular file, or holds more than max_bytes (input_file.hpp).
std::string read_file_bytes(const std::filesystem::path& path,
                            std::uintmax_t max_bytes = UINTMAX_MAX, std::string_view what = "file");

}  // namespace sadr::orchestrator
