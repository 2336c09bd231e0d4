// Guidance.cfg against the parameter tables: every .cfg parameter is a table entry (its
// name with '/' as '_') with the same range, so a value the form accepts is one the core accepts, and the form
// starts from (and writes back to) the struct through the table.
#include <gtest/gtest.h>
#include <offshore_gnc/GuidanceConfig.h>

#include <string>

#include "offshore_gnc/guidance/pipeline.h"
#include "offshore_gnc/ros/reconfigure.h"

using namespace offshore_gnc;

TEST(Reconfigure, GuidanceCfgMatchesTheTable) {
  const auto ranges = ros_util::cfgRanges<GuidanceConfig>();
  ASSERT_FALSE(ranges.empty());
  for (const auto& [name, range] : ranges) {
    bool found = false;
    EXPECT_EQ(ros_util::cfgMismatch(name, range, guidance::GuidanceParams::table(), found), "");
    EXPECT_TRUE(found) << "Guidance.cfg parameter '" << name << "' is in no table";
  }
}

TEST(Reconfigure, GuidanceCfgDefaultsAreTheCodes) {
  const guidance::GuidanceParams code;  // the struct's defaults (los.h, sbb.h); a preset overrides them at start
  for (const auto& [name, value] : ros_util::cfgDefaults<GuidanceConfig>())
    EXPECT_EQ(ros_util::cfgDefaultMismatch(name, value, guidance::GuidanceParams::table(), code), "");
}

TEST(Reconfigure, RoundTripsThroughTheTable) {
  guidance::GuidanceParams p = guidance::GuidanceParams::preset("usv");
  p.los.kp = 0.25;
  p.sbb.safety_y = 7.5;
  GuidanceConfig c = ros_util::toReconfigure<GuidanceConfig>(guidance::GuidanceParams::table(), p);
  EXPECT_DOUBLE_EQ(c.los_kp, 0.25);
  EXPECT_DOUBLE_EQ(c.sbb_safety_y, 7.5);
  EXPECT_DOUBLE_EQ(c.los_crab_gain, p.los.crab_gain);  // loaded values, not the .cfg defaults
  c.los_acceptance_radius = 20.0;
  const guidance::GuidanceParams q = ros_util::fromReconfigure(c, guidance::GuidanceParams::table(), p);
  EXPECT_DOUBLE_EQ(q.los.acceptance_radius, 20.0);
  EXPECT_DOUBLE_EQ(q.los.kp, 0.25);
  EXPECT_EQ(q.vehicle, "usv");  // not in the .cfg: untouched
}
