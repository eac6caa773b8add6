// SPDX-License-Identifier: MIT
/// \file state_blob.hpp
/// Native-endian binary blobs for exact restarts: a header (backend_base.hpp), then
/// length-prefixed arrays. Readers check every length and throw
/// InvalidArgument on truncation or mismatch.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "sadr/common/status.hpp"

namespace sadr::fluid {

class BlobWriter {
 public:
  template <typename T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    buf_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <typename T>
  void put_vector(const std::vector<T>& v) {
    put<std::uint64_t>(v.size());
    if (!v.empty()) buf_.append(reinterpret_cast<const char*>(v.data()), sizeof(T) * v.size());
  }
  void put_string(std::string_view s) {
    put<std::uint64_t>(s.size());
    buf_.append(s);
  }
  [[nodiscard]] std::string take() { return std::move(buf_); }

 private:
  std::string buf_;
};

class BlobReader {
 public:
  explicit BlobReader(std::string_view blob) : blob_(blob) {}
  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, blob_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  /// Reads a vector that must have `expected` entries (any length if expected == SIZE_MAX).
  template <typename T>
  std::vector<T> get_vector(std::size_t expected = SIZE_MAX) {
    const auto n = get<std::uint64_t>();
    if (expected != SIZE_MAX && n != expected) {
      throw InvalidArgument("state blob: array has " + std::to_string(n) + " entries, expected " +
                            std::to_string(expected) + " (blob from a different model?)");
    }
    need(n * sizeof(T));
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), blob_.data() + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
    return v;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    need(n);
    std::string s(blob_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  /// The next n bytes (no length prefix).
  std::string get_chars(std::size_t n) {
    need(n);
    std::string s(blob_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  [[nodiscard]] bool at_end() const { return pos_ == blob_.size(); }
  /// InvalidArgument unless every byte was read (call before committing a restored state).
  void expect_end() const {
    if (!at_end()) throw InvalidArgument("restore: trailing bytes in state blob");
  }

 private:
  void need(std::size_t n) const {
    if (n > blob_.size() - pos_) throw InvalidArgument("state blob is truncated or corrupt");
  }
  std::string_view blob_;
  std::size_t pos_ = 0;
};

}  // namespace sadr::fluid
