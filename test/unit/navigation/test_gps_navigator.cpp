// GPS-compass navigation: bad or unsupported input refused and counted (the navigator against the simulated
// receiver: test/unit/closed_loop/test_navigation_on_sim.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/navigation/gps_navigator.h"

using namespace offshore_gnc;
using namespace offshore_gnc::navigation;

TEST(GpsNavigator, RefusesBadOrUnsupportedFixes) {
  GpsNavigator nav(geo::kPyhajarviOrigin, GpsNavigatorConfig{});
  EXPECT_FALSE(nav.fix(1.0, geo::kPyhajarviOrigin));  // no heading yet
  EXPECT_EQ(nav.counters().get("fix_without_heading"), 1u);
  EXPECT_FALSE(nav.heading(1.0, NAN));
  EXPECT_EQ(nav.counters().get("bad_heading"), 1u);
  ASSERT_TRUE(nav.heading(1.0, 0.0));
  EXPECT_FALSE(nav.fix(1.0, {NAN, 23.7, 0.0}));
  EXPECT_FALSE(nav.fix(1.0, {91.0, 23.7, 0.0}));
  EXPECT_EQ(nav.counters().get("bad_fix"), 2u);
  EXPECT_TRUE(nav.fix(1.0, geo::kPyhajarviOrigin));
  EXPECT_FALSE(nav.fix(0.5, geo::kPyhajarviOrigin));  // older than the last one
  EXPECT_EQ(nav.counters().get("stale_fix"), 1u);
  EXPECT_FALSE(nav.fix(3.0, geo::kPyhajarviOrigin));  // heading 2 s old
}
