// The twin-waterjet joystick allocation (models/joystick_allocation.h) and the jet-by-jet model against the
// thesis' lumped one (issue 15).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/joystick_allocation.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/models/usv.h"

using namespace offshore_gnc;
using namespace offshore_gnc::models;

namespace {
UsvParams params() { return loadUsvParams("config/models/usv.yaml"); }  // the tests run in the package
}  // namespace

TEST(JoystickAllocation, EachAxisPushesItsOwnWay) {
  const JoystickAllocation a(params());
  const Eigen::Vector3d ahead = a.staticForce(a.allocate({0.6, 0.0, 0.0}));
  EXPECT_GT(ahead.x(), 500.0);
  EXPECT_NEAR(ahead.y(), 0.0, 1e-6 * ahead.x());
  EXPECT_NEAR(ahead.z(), 0.0, 1e-6 * ahead.x());
  EXPECT_LT(a.staticForce(a.allocate({-0.6, 0.0, 0.0})).x(), -100.0);  // buckets astern
  // Sideways at the stern, its turning moment cancelled by the differential buckets.
  const Eigen::Vector3d side = a.staticForce(a.allocate({0.0, 0.5, 0.0}));
  EXPECT_GT(std::abs(side.y()), 20.0);
  EXPECT_GT(std::abs(a.staticForce(a.allocate({0.0, 1.0, 0.0})).y()), std::abs(side.y()));
  EXPECT_LT(std::abs(side.z()), 0.05 * std::abs(side.y()) * params().l_pivot);
  EXPECT_LT(std::abs(side.x()), 0.1 * std::abs(side.y()));
  // Turning on the spot: a moment with little surge.
  const Eigen::Vector3d turn = a.staticForce(a.allocate({0.0, 0.0, 0.5}));
  EXPECT_GT(std::abs(turn.z()), 100.0);
  EXPECT_LT(std::abs(turn.x()), 0.2 * std::abs(turn.z()));
  const Eigen::Vector3d other = a.staticForce(a.allocate({0.0, 0.0, -0.5}));
  EXPECT_LT(turn.z() * other.z(), 0.0);
}

TEST(JoystickAllocation, SwayIsLinearInSideForceAndSurgeForInvertsTheSurgeAxis) {
  // Dynamic positioning asks forces: sway is a share of sideForceFull() (engines at the least rpm that gives it),
  // and surgeFor() finds the joystick surge of a force through Table 2's rpm and the buckets.
  const JoystickAllocation a(params());
  EXPECT_GT(a.sideForceFull(), 300.0);
  for (double sway : {0.05, 0.2, 0.5, 0.9}) {
    const Eigen::Vector3d f = a.staticForce(a.allocate({0.0, sway, 0.0}));
    EXPECT_NEAR(f.y(), sway * a.sideForceFull(), 0.05 * sway * a.sideForceFull()) << sway;
    EXPECT_LT(std::abs(f.z()), 0.05 * std::abs(f.y()) * params().l_pivot) << sway;  // its moment balanced
  }
  for (double force : {-600.0, -40.0, 15.0, 150.0, 900.0, 3000.0}) {
    const double surge = a.surgeFor(force);
    EXPECT_NEAR(a.staticForce(a.allocate({surge, 0.0, 0.0})).x(), force, 0.01 * std::abs(force) + 0.5) << force;
  }
  EXPECT_DOUBLE_EQ(a.surgeFor(1e6), 1.0);  // beyond the jets: full
  EXPECT_DOUBLE_EQ(a.surgeFor(std::numeric_limits<double>::quiet_NaN()), 0.0);
}

TEST(JoystickAllocation, BadParametersAreRefusedBeforeAnythingIsBuiltFromThem) {
  UsvParams p = params();
  p.rpm_max = -1.0;
  EXPECT_THROW(JoystickAllocation a(p), ConfigError);
}

TEST(JoystickAllocation, SaturationKeepsTheDirection) {
  const JoystickAllocation a(params());
  int saturated = 0;
  for (double s = -1.0; s <= 1.0; s += 0.25)
    for (double w = -1.0; w <= 1.0; w += 0.5)
      for (double r = -1.0; r <= 1.0; r += 0.5) {
        const UsvCommand big{s, w, r};
        const JetCommands jets = a.allocate(big);
        const double k = a.lastScale();
        ASSERT_GT(k, 0.0);
        ASSERT_LE(k, 1.0);
        if (k == 1.0) continue;
        ++saturated;
        // The jets do what the scaled-down request asks: the same as asking for k times it directly.
        const JetCommands scaled = a.allocate({k * big.surge, k * big.sway, k * big.yaw});
        for (int i = 0; i < 2; ++i) {
          EXPECT_NEAR(jets[i].rpm, scaled[i].rpm, 1.0) << s << " " << w << " " << r;
          EXPECT_NEAR(jets[i].nozzle, scaled[i].nozzle, 10.0) << s << " " << w << " " << r;
          EXPECT_NEAR(jets[i].bucket, scaled[i].bucket, 1e-3) << s << " " << w << " " << r;
        }
      }
  EXPECT_GT(saturated, 0);  // the grid reaches the jets' limits
}

TEST(JoystickAllocation, BadAxesGiveNeutralJets) {
  const JoystickAllocation a(params());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const UsvCommand c : {UsvCommand{nan, 0, 0}, UsvCommand{0, nan, 0}, UsvCommand{0, 0, INFINITY}}) {
    const JetCommands j = a.allocate(c);
    for (const auto& jet : j) {
      EXPECT_TRUE(std::isfinite(jet.rpm));
      EXPECT_EQ(jet.nozzle, 0.0);
      EXPECT_EQ(jet.bucket, 0.0);
    }
  }
  // Out of range: clamped, so the same as full deflection.
  const JetCommands over = a.allocate({5.0, 0.0, 0.0}), full = a.allocate({1.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(over[0].rpm, full[0].rpm);
  EXPECT_DOUBLE_EQ(over[1].bucket, full[1].bucket);
}

TEST(TwinWaterjets, AgreeWithTheLumpedModelWhenBothJetsAreCommandedAlike) {
  UsvParams twin = params(), lumped = params();
  twin.propulsion = UsvPropulsion::Twin;
  lumped.propulsion = UsvPropulsion::Lumped;
  for (const UsvCommand c : {UsvCommand{0.6, 0.0, 0.0}, UsvCommand{0.8, 0.0, 0.3}}) {
    UsvModel a(twin), b(lumped);
    const Environment calm;
    for (int i = 0; i < 1200; ++i) {  // 60 s: steady speed and turn rate
      a.step(0.05, c, calm);
      b.step(0.05, c, calm);
    }
    const auto &sa = a.state(), &sb = b.state();
    EXPECT_NEAR(sa.velocity.x(), sb.velocity.x(), 0.05 * std::abs(sb.velocity.x()) + 0.02) << c.surge << " " << c.yaw;
    EXPECT_NEAR(sa.angular_rate.z(), sb.angular_rate.z(), 0.1 * std::abs(sb.angular_rate.z()) + 1e-3)
        << c.surge << " " << c.yaw;
  }
}
