// The Control form (cfg/Control.cfg, generated from the vehicles' tables) through the tables: the form starts from
// the running vehicle's values, and a change reaches every vehicle's struct that has the field, no other.
#include <gtest/gtest.h>
#include <offshore_gnc/ControlConfig.h>

#include "offshore_gnc/control/vehicle_control.h"
#include "offshore_gnc/ros/reconfigure.h"

using namespace offshore_gnc;

TEST(Reconfigure, ControlRoundTripsThroughTheVehicleTables) {
  control::Girona500ControlParams g500;
  g500.yaw.kp = 7.0;
  ControlConfig c = ros_util::toReconfigure<ControlConfig>(control::Girona500ControlParams::table(), g500);
  EXPECT_DOUBLE_EQ(c.yaw_kp, 7.0);  // the running vehicle's value, not the form's default
  EXPECT_DOUBLE_EQ(c.north_kd, g500.north.kd);
  c.yaw_kp = 4.0;
  c.filter_tf = 0.5;  // the USV's field: the Girona500 has no filter
  const auto g = ros_util::fromReconfigure(c, control::Girona500ControlParams::table(), g500);
  EXPECT_DOUBLE_EQ(g.yaw.kp, 4.0);
  EXPECT_DOUBLE_EQ(g.north.kd, g500.north.kd);
  control::UsvControlParams usv0;
  usv0.surge.out_limit = 123.0;
  const control::UsvControlParams usv = ros_util::fromReconfigure(c, control::UsvControlParams::table(), usv0);
  EXPECT_DOUBLE_EQ(usv.yaw.kp, 4.0);
  EXPECT_DOUBLE_EQ(usv.filter.tf, 0.5);
  EXPECT_DOUBLE_EQ(usv.surge.out_limit, 123.0);  // not on the form: untouched
}
