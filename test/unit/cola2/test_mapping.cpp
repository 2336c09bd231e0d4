// COLA2 conventions: thruster order/sign mapping and NavSts -> our state across different origins.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/cola2/mapping.h"
#include "offshore_gnc/common/validate.h"

using namespace offshore_gnc;
using namespace offshore_gnc::cola2;

TEST(Cola2Mapping, ReordersSignsAndClamps) {
  ThrusterMapping m{{1, 0, 2}, {1, -1, 1}};
  m.validate(3);
  const auto out = m.apply({0.1, 0.2, 1.5});
  ASSERT_TRUE(out);
  EXPECT_EQ(*out, (std::vector<double>{0.2, -0.1, 1.0}));
  EXPECT_FALSE(m.apply({0.1, 0.2}));                  // wrong count
  EXPECT_FALSE(m.apply({0.1, std::nan(""), 0.0}));    // NaN never reaches a thruster
  EXPECT_THROW((ThrusterMapping{{0, 0, 2}, {1, 1, 1}}.validate(3)), ConfigError);
  EXPECT_THROW((ThrusterMapping{{0, 1, 2}, {1, 0.5, 1}}.validate(3)), ConfigError);
  EXPECT_THROW(ThrusterMapping::identity(5).validate(4), ConfigError);
}

TEST(Cola2Navigation, SameOriginIsTakenAsIs) {
  const geo::LatLonAlt o{61.4507, 23.7270, 0.0};
  geo::LocalNed ours(o);
  NavSts n;
  n.origin_latitude = o.lat_deg;
  n.origin_longitude = o.lon_deg;
  n.north = 12.0;
  n.east = -3.0;
  n.depth = 4.5;
  n.yaw = 0.7;
  n.u = 0.5;
  const auto s = toVehicleState(n, ours);
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->position.x(), 12.0, 1e-6);
  EXPECT_NEAR(s->position.y(), -3.0, 1e-6);
  EXPECT_NEAR(s->position.z(), 4.5, 1e-9);
  EXPECT_NEAR(s->yaw, 0.7, 1e-9);
  EXPECT_NEAR(s->velocity.x(), 0.5, 1e-9);
}

TEST(Cola2Navigation, ADifferentOriginIsShiftedIntoOurs) {
  geo::LocalNed ours({61.4507, 23.7270, 0.0});
  NavSts n;
  // COLA2's origin 100 m north and 50 m east of ours
  const geo::LatLonAlt theirs = ours.toGeodetic({100.0, 50.0, 0.0});
  n.origin_latitude = theirs.lat_deg;
  n.origin_longitude = theirs.lon_deg;
  n.north = 10.0;
  n.east = 5.0;
  n.depth = 2.0;
  const auto s = toVehicleState(n, ours);
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->position.x(), 110.0, 0.01);
  EXPECT_NEAR(s->position.y(), 55.0, 0.01);
  EXPECT_NEAR(s->position.z(), 2.0, 1e-9);
  n.yaw = std::nan("");
  EXPECT_FALSE(toVehicleState(n, ours));
  n.yaw = 0;
  n.origin_latitude = 123;
  EXPECT_FALSE(toVehicleState(n, ours));
}
