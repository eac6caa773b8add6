// SPDX-License-Identifier: MIT
#include "sadr/common/input_file.hpp"

#include <cstdio>
#include <string>
#include <system_error>

#include "sadr/common/status.hpp"

namespace sadr {
namespace {

std::string kind_of(std::filesystem::file_type t) {
  using std::filesystem::file_type;
  switch (t) {
    case file_type::directory:
      return "a directory";
    case file_type::character:
      return "a character device";
    case file_type::block:
      return "a block device";
    case file_type::fifo:
      return "a named pipe";
    case file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}

std::string bytes_text(std::uintmax_t b) {
  char buf[48];
  if (b >= (1ull << 30)) {
    std::snprintf(buf, sizeof buf, "%.1f GiB", static_cast<double>(b) / (1ull << 30));
  } else if (b >= (1ull << 20)) {
    std::snprintf(buf, sizeof buf, "%.1f MiB", static_cast<double>(b) / (1ull << 20));
  } else {
    std::snprintf(buf, sizeof buf, "%ju bytes", b);
  }
  return buf;
}

}  // namespace

void require_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                          std::string_view what) {
  const std::string name = std::string(what) + " '" + path.string() + "'";
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec || st.type() == std::filesystem::file_type::not_found) {
    throw InvalidArgument("cannot open " + name + ": " +
                              (ec ? ec.message() : std::string("No such file or directory")),
                          {{"file", path.string()}});
  }
  if (st.type() != std::filesystem::file_type::regular) {
    throw InvalidArgument(name + " is " + kind_of(st.type()) + ", not a regular file",
                          {{"file", path.string()}});
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > max_bytes) {
    throw InvalidArgument(name + " holds " + bytes_text(size) + ", more than the " +
                              bytes_text(max_bytes) + " sadr reads as a " + std::string(what),
                          {{"file", path.string()}, {"allowed", "<= " + bytes_text(max_bytes)}});
  }
}

}  // namespace sadr
