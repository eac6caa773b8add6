// SPDX-License-Identifier: MIT
#include "sadr/common/particle_state.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sadr/common/status.hpp"

namespace sadr {
namespace {

ParticleState make(std::size_t n) {
  ParticleState s;
  s.dimension = 2;
  s.resize(n);
  return s;
}

TEST(ParticleState, ValidStatePasses) {
  EXPECT_NO_THROW(make(4).validate());
}

TEST(ParticleState, VolumeIsMassOverDensity) {
  auto s = make(1);
  s.masses[0] = 2.0;
  s.densities[0] = 4.0;
  EXPECT_DOUBLE_EQ(s.volume(0), 0.5);
}

TEST(ParticleState, ErrorsNameFieldIndexAndValue) {
  auto s = make(3);
  s.masses[2] = -1.5;
  try {
    s.validate();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "particle 2: mass = -1.5 (must be finite and > 0)");
  }
  s = make(3);
  s.positions[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(s.validate(), InvalidArgument);
  s = make(3);
  s.densities.pop_back();
  EXPECT_THROW(s.validate(), InvalidArgument);
  s = make(3);
  s.dimension = 4;
  EXPECT_THROW(s.validate(), InvalidArgument);
}

TEST(Box, Validation) {
  Box b;
  b.dimension = 2;
  EXPECT_NO_THROW(b.validate());
  b.hi[1] = b.lo[1];
  EXPECT_THROW(b.validate(), InvalidArgument);
  b.hi[1] = 1;
  b.dimension = 0;
  EXPECT_THROW(b.validate(), InvalidArgument);
}

}  // namespace
}  // namespace sadr
