// The Guidance form (cfg/Guidance.cfg, generated from the table) through the table: it starts from the loaded
// struct and a change goes back into it.
#include <gtest/gtest.h>
#include <offshore_gnc/GuidanceConfig.h>

#include "offshore_gnc/guidance/pipeline.h"
#include "offshore_gnc/ros/reconfigure.h"

using namespace offshore_gnc;

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
