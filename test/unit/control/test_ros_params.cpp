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

TEST(Reconfigure, ControlCfgDefaultsAreAVehiclesDefaults) {
  // One form for three vehicles (one runs per nodelet): each .cfg default is the default of a vehicle that has it.
  for (const auto& [name, value] : ros_util::cfgDefaults<ControlConfig>()) {
    std::string usv = ros_util::cfgDefaultMismatch(name, value, control::UsvControlParams::table(), {});
    std::string g500 = ros_util::cfgDefaultMismatch(name, value, control::Girona500ControlParams::table(), {});
    std::string acolor = ros_util::cfgDefaultMismatch(name, value, control::AcolorControlParams::table(), {});
    const bool usv_has = ros_util::specForCfg(control::UsvControlParams::table(), name) != nullptr;
    const bool g500_has = ros_util::specForCfg(control::Girona500ControlParams::table(), name) != nullptr;
    const bool acolor_has = ros_util::specForCfg(control::AcolorControlParams::table(), name) != nullptr;
    const bool some = (usv_has && usv.empty()) || (g500_has && g500.empty()) || (acolor_has && acolor.empty());
    EXPECT_TRUE(some) << usv << " | " << g500 << " | " << acolor;
  }
}
