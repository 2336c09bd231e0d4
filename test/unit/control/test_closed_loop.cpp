// Closed loop on the simulator's plants with a 0.2 m/s cross current (the harness `./scripts/bench tracking`
// also runs). Goals from issue 3: USV RMSE <= 0.5 m, Girona500 <= 0.15 m.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/control/closed_loop.h"
#include "offshore_gnc/control/scenarios.h"

using namespace offshore_gnc;
using namespace offshore_gnc::control;

TEST(ClosedLoop, UsvFiveWaypointStraightPathWithCrossCurrent) {
  const auto cfg = scenarios::usvStraight(true);
  const auto r = runUsv(cfg);
  EXPECT_TRUE(r.finished) << r.status;
  EXPECT_EQ(r.nan_outputs, 0u);
  EXPECT_LE(r.metrics.rmse, 0.5) << "RMSE " << r.metrics.rmse;
  // Waterjet DP against a 0.2 m/s current is coarse (docs/guidance-control.md): measured 11.9 m (9.5 m without
  // the turning thrust, which the hold from rest needs); before the final radius, the slowdown and
  // turn-then-drive it was 16-27 m.
  EXPECT_LT(r.hold_error, 14.0);
  // Without the crab-angle estimate the standing error is larger (the thesis' main error source).
  const auto n = runUsv(scenarios::usvStraight(false));
  EXPECT_GT(n.metrics.rmse, r.metrics.rmse);
}

TEST(ClosedLoop, UsvBuoyAvoidanceNeverInsideTheSafetyBox) {
  const auto cfg = scenarios::usvBuoy(true);
  const auto r = runUsv(cfg);
  EXPECT_TRUE(r.finished) << r.status;
  EXPECT_EQ(r.inside_box_samples, 0u);
  EXPECT_GT(r.min_clearance, 3.0);
  int detour = 0;  // waypoints off the original straight line: the SBB corners
  for (const auto& w : r.planned_path) detour += std::abs(w.y()) > 5.0;
  EXPECT_GE(detour, 2);
  EXPECT_EQ(r.nan_outputs, 0u);
}

TEST(ClosedLoop, UsvBuoy25mAheadOfABoatAtRest) {
  // The simulator rostest's route: detour corners reached, the side kept; never inside the box.
  const auto r = runUsv(scenarios::usvNearBuoy(true));
  EXPECT_TRUE(r.finished) << r.status;
  EXPECT_EQ(r.inside_box_samples, 0u);
  EXPECT_LT(r.metrics.rmse, 3.5);  // 2.7 m: the waterjet boat overshoots the corners
}

TEST(ClosedLoop, UsvHoldsFromRestWithTheHoldPointAbeam) {
  // The mission's USV waits at its start while the current sets it off: without thrust the nozzles cannot
  // turn the boat and it drifted 55 m in 300 s; with the turning thrust it stays within 21 m.
  const auto r = runUsv(scenarios::usvHoldFromRest());
  EXPECT_TRUE(r.finished);
  EXPECT_LT(r.hold_error, 25.0);
  UsvControlParams no_thrust;
  no_thrust.dp_turn_thrust = 0.0;
  EXPECT_GT(runUsv(scenarios::usvHoldFromRest(), no_thrust).hold_error, 40.0);
}

TEST(ClosedLoop, ControllerAloneOnTheTrueState) {
  auto cfg = scenarios::usvStraight(true);
  cfg.navigation = false;
  EXPECT_LE(runUsv(cfg).metrics.rmse, 0.5);
}

TEST(ClosedLoop, Girona500CoveragePattern) {
  const auto r = runGirona500(scenarios::auvCoverage(true));
  EXPECT_TRUE(r.finished) << r.status;
  EXPECT_LE(r.metrics.rmse, 0.15) << "RMSE " << r.metrics.rmse;
  EXPECT_EQ(r.nan_outputs, 0u);
  EXPECT_LT(r.hold_error, 1.0);
}
