#include <gtest/gtest.h>

#include <limits>
#include <thread>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/validate.h"

using namespace offshore_gnc;

TEST(Angles, WrapIntoHalfOpenInterval) {
  EXPECT_NEAR(wrapAngle(kPi), kPi, 1e-12);
  EXPECT_NEAR(wrapAngle(-kPi), kPi, 1e-12);  // -pi is outside (-pi, pi]
  EXPECT_NEAR(wrapAngle(3 * kPi), kPi, 1e-9);
  EXPECT_NEAR(wrapAngle(0.1 + 4 * kPi), 0.1, 1e-9);
  EXPECT_NEAR(wrapAngle(-0.1 - 4 * kPi), -0.1, 1e-9);
  EXPECT_TRUE(std::isnan(wrapAngle(std::nan(""))));
}

TEST(Angles, TwoPiAndDiff) {
  EXPECT_NEAR(wrapTwoPi(-0.1), 2 * kPi - 0.1, 1e-12);
  EXPECT_NEAR(wrapTwoPi(2 * kPi), 0.0, 1e-12);
  // an angle a hair below 0 (one head unit less the same in degrees, say) wraps into [0, 2 pi), not onto 2 pi
  EXPECT_LT(wrapTwoPi(-1e-17), 2 * kPi);
  EXPECT_LT(wrapTwoPi(-std::numeric_limits<double>::denorm_min()), 2 * kPi);
  EXPECT_NEAR(angleDiff(deg2rad(359), deg2rad(1)), deg2rad(-2), 1e-12);
  EXPECT_NEAR(rad2deg(deg2rad(42.0)), 42.0, 1e-12);
}

TEST(Validate, MessagesNameTheParameter) {
  EXPECT_DOUBLE_EQ(requireRange("gain", 0.5, 0.0, 1.0), 0.5);
  try {
    requireRange("los.lookahead", -1.0, 0.1, 100.0);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("los.lookahead"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("[0.1, 100]"), std::string::npos);
  }
  EXPECT_THROW(requirePositive("rate", 0.0), ConfigError);
  EXPECT_THROW(requirePositive("rate", std::nan("")), ConfigError);
}

TEST(Counters, ConcurrentIncrements) {
  Counters c;
  std::vector<std::thread> ts;
  for (int i = 0; i < 4; ++i)
    ts.emplace_back([&c] {
      for (int k = 0; k < 1000; ++k) c.increment("bad_crc");
    });
  for (auto& t : ts) t.join();
  c.increment("nan_point", 5);
  EXPECT_EQ(c.get("bad_crc"), 4000u);
  EXPECT_EQ(c.get("missing"), 0u);
  EXPECT_EQ(c.total(), 4005u);
  EXPECT_EQ(c.snapshot().size(), 2u);
}
