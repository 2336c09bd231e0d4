// Each vehicle's stack (simulator, navigation, LiDAR targets, guidance pipeline, control loop: the nodelets'
// classes, configured from config/) on a route with a 0.2 m/s cross current, as `./scripts/bench tracking`
// runs them. Goals from issue 3: USV RMSE <= 0.5 m, Girona500 <= 0.15 m.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/closed_loop/closed_loop.h"
#include "offshore_gnc/closed_loop/scenarios.h"

using namespace offshore_gnc;
using namespace offshore_gnc::closed_loop;
using namespace offshore_gnc::control;

TEST(ClosedLoop, UsvFiveWaypointStraightPathWithCrossCurrent) {
  const auto cfg = scenarios::usvStraight(true);
  const auto r = runUsv(cfg);
  EXPECT_TRUE(r.finished) << r.status;
  EXPECT_EQ(r.rejected_commands, 0u);
  EXPECT_LE(r.metrics.rmse, 0.5) << "RMSE " << r.metrics.rmse;
  // Twin-jet DP against a 0.2 m/s current (docs/guidance-control.md): measured 3.8 m; with the lumped jet and
  // no side force it was 9.5 m, before the final radius, the slowdown and turn-then-drive 16-27 m.
  EXPECT_LT(r.hold_error, 6.0);
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
  EXPECT_EQ(r.rejected_commands, 0u);
}

TEST(ClosedLoop, UsvBuoy25mAheadOfABoatAtRest) {
  // The simulator rostest's route: detour corners reached, the side kept; never inside the box.
  const auto r = runUsv(scenarios::usvNearBuoy(true));
  EXPECT_TRUE(r.finished) << r.status;
  EXPECT_EQ(r.inside_box_samples, 0u);
  EXPECT_LT(r.metrics.rmse, 3.5);  // 2.7 m: the waterjet boat overshoots the corners
}

TEST(ClosedLoop, UsvKeepsSteeringInTheSlowdownOfAShortTransit) {
  // The mission's transit lies wholly in the slowdown before the stand-off point: at 0.2 m/s in a 0.2 m/s
  // current, without the least turning thrust the jets lost their steering. The twin-jet allocation keeps the
  // engines at yaw_rpm_share x |yaw| and the controller's turn_thrust adds surge off course: without both, worse.
  const auto r = runUsv(scenarios::usvShortTransit());
  EXPECT_TRUE(r.finished);
  EXPECT_LT(r.metrics.rmse, 3.0);
  auto no_thrust = scenarios::usvShortTransit();
  no_thrust.usv = [](UsvStackConfig& u) {
    u.control.usv.turn_thrust = 0.0;
    u.sim.usv.yaw_rpm_share = 0.0;
  };
  EXPECT_GT(runUsv(no_thrust).metrics.rmse, r.metrics.rmse);
}

TEST(ClosedLoop, ControllerAloneOnTheTrueState) {
  auto cfg = scenarios::usvStraight(true);
  cfg.navigation = false;
  EXPECT_LE(runUsv(cfg).metrics.rmse, 0.5);
}

TEST(ClosedLoop, Girona500CoveragePattern) {
  const auto r = runAuv(scenarios::auvCoverage(true));
  EXPECT_TRUE(r.finished) << r.status;
  EXPECT_LE(r.metrics.rmse, 0.15) << "RMSE " << r.metrics.rmse;
  EXPECT_EQ(r.rejected_commands, 0u);
  EXPECT_LT(r.hold_error, 1.0);
}

TEST(ClosedLoop, Girona500CrabsAcrossAStrongCurrent) {
  // strong_current.yaml's 0.5 m/s across the lawnmower's legs: the lateral thruster alone cannot hold the leg
  // (the AUV was carried off its pattern), the crab turns the surge thrusters into the current.
  auto cfg = scenarios::auvCoverage(true);
  cfg.current = Eigen::Vector2d(0.0, 0.5);
  cfg.max_time = 1500.0;
  const auto base = cfg.auv;
  cfg.auv = [base](AuvStackConfig& a) { base(a); a.control.girona500.max_crab = 1.2; };
  const auto crab = runAuv(cfg);
  EXPECT_TRUE(crab.finished) << crab.status;
  EXPECT_LE(crab.metrics.rmse, 1.0) << "RMSE " << crab.metrics.rmse;
  cfg.auv = [base](AuvStackConfig& a) { base(a); a.control.girona500.max_crab = 0.0; };
  const auto fixed = runAuv(cfg);
  RecordProperty("rmse_crab_m", std::to_string(crab.metrics.rmse));
  RecordProperty("rmse_fixed_heading_m", std::to_string(fixed.metrics.rmse));
  EXPECT_GT(fixed.metrics.rmse, 2.0 * crab.metrics.rmse) << "without the crab: RMSE " << fixed.metrics.rmse;
}

TEST(ClosedLoop, UsvTurnsOntoAPathFromRestHeldOnStation) {
  // At rest with the bow the wrong way (south, the path north) in a 0.2 m/s cross current: turning unheld, the
  // current sets the boat off the path's start before it has way on; held (turn_hold_angle), it turns where it is.
  auto cfg = scenarios::usvStraight(true);
  cfg.start_yaw = kPi;
  cfg.max_time = 120.0;
  cfg.usv = [](UsvStackConfig& u) { u.control.usv.turn_hold_angle = 1.0; };  // off in the shipped configuration
  auto offTheStart = [](const ClosedLoopResult& r) {  // the largest set across the path while near its start
    double e = 0.0;
    for (const auto& x : r.track)
      if (x.x() < 10.0) e = std::max(e, std::abs(x.y()));
    return e;
  };
  const double held = offTheStart(runUsv(cfg));
  auto unheld_cfg = cfg;
  unheld_cfg.usv = [](UsvStackConfig& u) { u.control.usv.turn_hold_angle = 0.0; };
  const double unheld = offTheStart(runUsv(unheld_cfg));
  // 1.77 m held, 2.35 m unheld (2026-12-05): the turn itself keeps the jets' yaw at full deflection, which the
  // allocation serves first, so the hold has little authority until the bow is round; capping the turn's yaw to
  // leave it more (a fifth of full) held within 1 m here but took 100 s to turn the mission's boat in the wind.
  EXPECT_LT(held, 0.85 * unheld) << "held " << held << " m, unheld " << unheld << " m";
}
