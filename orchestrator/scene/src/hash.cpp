// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/hash.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "sadr/common/input_file.hpp"
#include "sadr/common/status.hpp"

namespace sadr::orchestrator {

std::string content_hash(std::string_view bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "fnv1a64:%016llx",
                static_cast<unsigned long long>(fnv1a64(bytes)));
  return buf;
}

std::string read_file_bytes(const std::filesystem::path& path, std::uintmax_t max_bytes,
                            std::string_view what) {
  require_regular_file(path, max_bytes, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InvalidArgument("cannot open '" + path.string() + "': " + std::strerror(errno));
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InvalidArgument("cannot read '" + path.string() + "'");
  return buffer.str();
}

std::string file_hash(const std::filesystem::path& path) {
  return content_hash(read_file_bytes(path));
}

}  // namespace sadr::orchestrator
