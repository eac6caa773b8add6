// SPDX-License-Identifier: MIT
/// \file rng.hpp
/// Reproducible random numbers.
///
/// Two generators, one per use:
///  - Philox4x32-10 (Salmon et al., SC'11), a counter-based generator: the
///    numbers are a pure function of (key, counter), so pair noise keyed by
///    (seed, purpose, step, min(i,j), max(i,j)) does not depend on thread count
///    or neighbour order, and a checkpoint needs only (seed, step).
///  - Xoshiro256** (Blackman & Vigna 2018), a fast sequential stream for event
///    driven code (the SSA). Streams are seeded from (seed, stream_id) through
///    SplitMix64, so realizations and services get independent streams, and the
///    whole state is four 64-bit words that a checkpoint stores.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace sadr::rng {

/// SplitMix64 step (Steele et al. 2014): a good 64-bit mixer for seeding.
constexpr std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// Mixes two 64-bit words into one (used to derive seeds: realization seeds,
/// per-service streams). Deterministic and platform independent.
constexpr std::uint64_t mix_seed(std::uint64_t a, std::uint64_t b) {
  std::uint64_t s = a ^ (b * 0xD1B54A32D192ED03ULL);
  splitmix64(s);
  return splitmix64(s);
}

/// Uniform double in (0, 1) from 64 random bits (53-bit mantissa, never 0 or 1).
constexpr double to_open01(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

/// Xoshiro256**: sequential stream with a 256-bit serialisable state.
class Xoshiro256 {
 public:
  using State = std::array<std::uint64_t, 4>;

  /// Stream `stream_id` of the realization seeded with `seed`.
  explicit Xoshiro256(std::uint64_t seed = 0, std::uint64_t stream_id = 0) {
    std::uint64_t sm = mix_seed(seed, stream_id);
    for (auto& w : s_) w = splitmix64(sm);
  }

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  /// Uniform in the open interval (0, 1).
  double uniform() { return to_open01(next()); }
  /// Exponential with rate 1 (mean 1), always finite and > 0.
  double exponential() { return -std::log(uniform()); }

  [[nodiscard]] const State& state() const { return s_; }
  void set_state(const State& s) { s_ = s; }
  bool operator==(const Xoshiro256&) const = default;

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  State s_{};
};

/// Philox4x32-10 counter-based generator.
class Philox4x32 {
 public:
  using Counter = std::array<std::uint32_t, 4>;
  using Key = std::array<std::uint32_t, 2>;

  /// The 4 x 32 random bits for (key, counter).
  static constexpr Counter generate(Counter ctr, Key key) {
    for (int round = 0; round < 10; ++round) {
      if (round > 0) {
        key[0] += 0x9E3779B9U;
        key[1] += 0xBB67AE85U;
      }
      const std::uint64_t p0 = std::uint64_t{0xD2511F53U} * ctr[0];
      const std::uint64_t p1 = std::uint64_t{0xCD9E8D57U} * ctr[2];
      ctr = Counter{
          static_cast<std::uint32_t>(p1 >> 32) ^ ctr[1] ^ key[0], static_cast<std::uint32_t>(p1),
          static_cast<std::uint32_t>(p0 >> 32) ^ ctr[3] ^ key[1], static_cast<std::uint32_t>(p0)};
    }
    return ctr;
  }
};

/// Purposes that key counter-based draws, so different uses never share numbers.
enum class Purpose : std::uint32_t {
  kPairNoise = 1,
  kPairNoiseScalar = 2,
  kWallNoise = 3,
  kInitialCondition = 4,
  kTest = 99,
};

/// Counter-based draws keyed by (seed, purpose, step, i, j).
/// Pass i <= j for pair quantities (the caller orders them).
struct CounterRng {
  std::uint64_t seed = 0;

  /// Two independent standard normals (Box-Muller) for the key.
  [[nodiscard]] std::array<double, 2> normal2(Purpose purpose, std::uint64_t step, std::uint32_t i,
                                              std::uint32_t j, std::uint32_t sub = 0) const {
    const auto u = uniform2(purpose, step, i, j, sub);
    const double r = std::sqrt(-2.0 * std::log(u[0]));
    constexpr double two_pi = 6.283185307179586476925;
    return {r * std::cos(two_pi * u[1]), r * std::sin(two_pi * u[1])};
  }

  /// Two uniforms in (0, 1) with 53-bit resolution for the key.
  /// Counter layout: [i, j, step bits 0-31, purpose (8 bits) | sub (8 bits) |
  /// step bits 32-47]; steps up to 2^48 and sub-draws up to 255 never collide.
  [[nodiscard]] std::array<double, 2> uniform2(Purpose purpose, std::uint64_t step, std::uint32_t i,
                                               std::uint32_t j, std::uint32_t sub = 0) const {
    const Philox4x32::Key key{static_cast<std::uint32_t>(seed),
                              static_cast<std::uint32_t>(seed >> 32)};
    const Philox4x32::Counter ctr{i, j, static_cast<std::uint32_t>(step),
                                  (static_cast<std::uint32_t>(purpose) << 24) |
                                      ((sub & 0xFFU) << 16) |
                                      static_cast<std::uint32_t>((step >> 32) & 0xFFFFU)};
    const auto r = Philox4x32::generate(ctr, key);
    const std::uint64_t a = (std::uint64_t{r[0]} << 32) | r[1];
    const std::uint64_t b = (std::uint64_t{r[2]} << 32) | r[3];
    return {to_open01(a), to_open01(b)};
  }
};

}  // namespace sadr::rng
