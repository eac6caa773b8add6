// SPDX-License-Identifier: MIT
/// \file atomic_file.hpp
/// Crash-safe file replacement: write a temporary file in the same directory,
/// fsync it, rename it over the target, fsync the directory. Readers see the
/// old content or the new content, never a mix; the old file stays in place
/// until the new one is durable.
#pragma once

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>

#include "sadr/common/status.hpp"

namespace sadr::orchestrator {

/// A file-system operation failed (message names the path and the OS error).
class IoError : public Error {
 public:
  explicit IoError(const std::string& message) : Error(StatusCode::kUnavailable, message) {}
};

/// Test hook that simulates a crash during write_file_atomic(): the write
/// stops (an IoError is thrown) after `fail_after_bytes` bytes of the
/// temporary file, or just before the rename. The temporary file is left
/// behind as a real crash would leave it.
struct AtomicWriteFault {
  std::size_t fail_after_bytes = std::numeric_limits<std::size_t>::max();
  bool fail_before_rename = false;
};

/// Replaces `path` with `bytes` atomically and durably (see the file comment).
/// The parent directory must exist.
/// @throws IoError naming the path and the failing system call.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes,
                       const AtomicWriteFault* fault = nullptr);

/// Creates `dir` and its parents if needed. @throws IoError.
void ensure_directory(const std::filesystem::path& dir);

}  // namespace sadr::orchestrator
