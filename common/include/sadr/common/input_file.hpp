// SPDX-License-Identifier: MIT
/// \file input_file.hpp
/// The checks every file sadr reads passes first: it is a regular file (not a device, a pipe
/// or a directory, which could be read for ever) and not larger than a stated bound.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>

namespace sadr {

/// Size bounds of the files sadr reads [bytes].
inline constexpr std::uintmax_t kMaxSceneFileBytes = 16ull << 20;  ///< scenes and sweep files
inline constexpr std::uintmax_t kMaxDataFileBytes = 64ull << 30;   ///< particle and field CSV

/// Throws InvalidArgument naming `what` and the path when `path` does not exist, is not a
/// regular file (after symbolic links), or holds more than `max_bytes`.
/// @param what what the file is for the user, e.g. "scene file", "particle file".
void require_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                          std::string_view what);

}  // namespace sadr
