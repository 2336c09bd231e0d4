// Control.cfg against the vehicles' parameter tables: every .cfg parameter is an entry of at least one
// vehicle's table (its name with '/' as '_') with the same range.
#include <gtest/gtest.h>
#include <offshore_gnc/ControlConfig.h>

#include "offshore_gnc/control/vehicle_control.h"
#include "offshore_gnc/ros/reconfigure.h"

using namespace offshore_gnc;

TEST(Reconfigure, ControlCfgMatchesTheVehicleTables) {
  const auto ranges = ros_util::cfgRanges<ControlConfig>();
  ASSERT_FALSE(ranges.empty());
  for (const auto& [name, range] : ranges) {
    bool found = false;
    EXPECT_EQ(ros_util::cfgMismatch(name, range, control::UsvControlParams::table(), found), "");
    EXPECT_EQ(ros_util::cfgMismatch(name, range, control::Girona500ControlParams::table(), found), "");
    EXPECT_EQ(ros_util::cfgMismatch(name, range, control::AcolorControlParams::table(), found), "");
    EXPECT_TRUE(found) << "Control.cfg parameter '" << name << "' is in no vehicle's table";
  }
}
