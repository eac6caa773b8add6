// SPDX-License-Identifier: MIT
/// \file blob.hpp
/// Internal: a minimal binary writer/reader for snapshots (native byte order,
/// which is little-endian on every supported platform; checked at compile time).
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "sadr/common/status.hpp"

namespace sadr::ssa::detail {

static_assert(std::endian::native == std::endian::little, "snapshots assume little-endian");

class BlobWriter {
 public:
  template <typename T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <typename T>
  void vec(std::span<const T> v) {
    static_assert(std::is_trivially_copyable_v<T>);
    pod(static_cast<std::uint64_t>(v.size()));
    if (!v.empty()) out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  template <typename T>
  void vec(const std::vector<T>& v) {
    vec(std::span<const T>(v));
  }
  void bytes(std::string_view s) { out_.append(s); }
  [[nodiscard]] const std::string& str() const { return out_; }

 private:
  std::string out_;
};

class BlobReader {
 public:
  explicit BlobReader(std::string_view in) : in_(in) {}
  template <typename T>
  T pod(const char* what) {
    T v;
    need(sizeof v, what);
    std::memcpy(&v, in_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  template <typename T>
  std::vector<T> vec(const char* what, std::uint64_t max_len) {
    const auto n = pod<std::uint64_t>(what);
    if (n > max_len) {
      throw InvalidArgument(std::string("snapshot: field '") + what + "' has length " +
                            std::to_string(n) + " (expected at most " + std::to_string(max_len) +
                            ")");
    }
    need(n * sizeof(T), what);
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), in_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return v;
  }
  std::string_view bytes(std::size_t n, const char* what) {
    need(n, what);
    auto s = in_.substr(at_, n);
    at_ += n;
    return s;
  }
  [[nodiscard]] std::size_t offset() const { return at_; }
  [[nodiscard]] std::size_t remaining() const { return in_.size() - at_; }

 private:
  void need(std::size_t n, const char* what) const {
    if (in_.size() - at_ < n) {
      throw InvalidArgument(std::string("snapshot truncated while reading '") + what + "'");
    }
  }
  std::string_view in_;
  std::size_t at_ = 0;
};

/// FNV-1a 64 over a byte range (snapshot checksum).
inline std::uint64_t fnv1a(std::string_view s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ULL;
  return h;
}

}  // namespace sadr::ssa::detail
