// GPS-compass navigation against the simulated receiver (sim::GpsCompass): fixes and heading back to the local
// pose, lever arm removed, velocity from fixes or from the receiver's Doppler velocity.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/navigation/gps_navigator.h"
#include "offshore_gnc/sim/sensors.h"

using namespace offshore_gnc;
using namespace offshore_gnc::sim;
using namespace offshore_gnc::navigation;

TEST(GpsNavigator, RecoversTheSimulatedPoseAndVelocity) {
  const geo::LocalNed frame(geo::kPyhajarviOrigin);
  GpsCompassConfig gc;
  gc.position_sigma = gc.position_white_sigma = gc.altitude_sigma = gc.heading_sigma = 0.0;
  gc.antenna = {2.0, 0.5, -2.5};
  GpsCompass gps(gc, frame, 1);
  GpsNavigatorConfig nc;
  nc.antenna = gc.antenna;
  nc.velocity_filter = 0.0;
  GpsNavigator nav(geo::kPyhajarviOrigin, nc);
  VehicleState s;
  s.yaw = deg2rad(30.0);
  std::optional<VehicleState> est;
  for (int i = 0; i < 20; ++i) {  // 2 m/s along the heading, fixes at 10 Hz
    s.t = 0.1 * i;
    s.position = {2.0 * s.t * std::cos(s.yaw) + 10.0, 2.0 * s.t * std::sin(s.yaw) - 5.0, 0.0};
    const auto r = gps.measure(s);
    ASSERT_TRUE(nav.heading(r.t, r.heading));
    est = nav.fix(r.t, r.fix);
    ASSERT_TRUE(est);
  }
  EXPECT_NEAR(est->position.x(), s.position.x(), 1e-6);
  EXPECT_NEAR(est->position.y(), s.position.y(), 1e-6);
  EXPECT_NEAR(est->yaw, s.yaw, 1e-12);
  EXPECT_NEAR(est->velocity.x(), 2.0, 1e-6);  // body surge
  EXPECT_NEAR(est->velocity.y(), 0.0, 1e-6);
}

TEST(GpsNavigator, UsesTheReceiversDopplerVelocityAndRateOfTurn) {
  const geo::LocalNed frame(geo::kPyhajarviOrigin);
  GpsCompassConfig gc;
  gc.position_sigma = gc.position_white_sigma = gc.altitude_sigma = gc.heading_sigma = 0.0;
  gc.velocity_sigma = gc.rate_sigma = 0.0;
  gc.antenna = {2.0, 0.5, -2.5};
  GpsCompass gps(gc, frame, 1);
  GpsNavigatorConfig nc;
  nc.antenna = gc.antenna;
  GpsNavigator nav(geo::kPyhajarviOrigin, nc);
  VehicleState s;
  s.t = 3.0;
  s.yaw = deg2rad(-120.0);
  s.velocity = {1.5, -0.2, 0.0};
  s.angular_rate.z() = -0.05;
  const auto r = gps.measure(s);
  ASSERT_TRUE(nav.heading(r.t, r.heading));
  ASSERT_TRUE(nav.velocity(r.t, r.velocity_ned, r.rate_of_turn));
  const auto est = nav.fix(r.t, r.fix);  // the very first fix: no differences needed
  ASSERT_TRUE(est);
  EXPECT_NEAR(est->velocity.x(), 1.5, 1e-9);  // lever arm removed
  EXPECT_NEAR(est->velocity.y(), -0.2, 1e-9);
  EXPECT_NEAR(est->angular_rate.z(), -0.05, 1e-12);
  EXPECT_FALSE(nav.velocity(3.1, Eigen::Vector2d(NAN, 0.0), 0.0));
  EXPECT_EQ(nav.counters().get("bad_velocity"), 1u);
}

