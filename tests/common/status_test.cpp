// SPDX-License-Identifier: MIT
#include "sadr/common/status.hpp"

#include <gtest/gtest.h>

namespace sadr {
namespace {

TEST(Status, OkByDefaultAndFormatsDetails) {
  EXPECT_TRUE(Status{}.ok());
  Status s{
      StatusCode::kInvalidArgument, "mass must be > 0", {{"field", "masses[3]"}, {"value", "-1"}}};
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.to_string(), "INVALID_ARGUMENT: mass must be > 0 [field=masses[3], value=-1]");
}

TEST(Status, ExceptionsCarryTheirCode) {
  try {
    throw InvalidArgument("bad h", {{"field", "h"}});
  } catch (const std::exception& e) {
    const Status s = status_from_exception(e);
    EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
    EXPECT_EQ(s.message, "bad h");
    ASSERT_EQ(s.details.size(), 1u);
  }
  const Status plain = status_from_exception(std::runtime_error("boom"));
  EXPECT_EQ(plain.code, StatusCode::kInternal);
  EXPECT_NE(plain.message.find("boom"), std::string::npos);
}

TEST(Status, ThrowIfErrorRoundTrips) {
  EXPECT_NO_THROW(throw_if_error(Status::Ok()));
  try {
    throw_if_error(Status{StatusCode::kNumericalFailure, "NaN in rho", {}});
    FAIL() << "expected a throw";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kNumericalFailure);
  }
}

TEST(Status, EveryCodeHasAName) {
  for (int c = 0; c <= static_cast<int>(StatusCode::kAborted); ++c) {
    EXPECT_NE(to_string(static_cast<StatusCode>(c)), "UNKNOWN") << c;
  }
}

}  // namespace
}  // namespace sadr
