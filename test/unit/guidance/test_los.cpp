#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/guidance/los.h"
#include "offshore_gnc/guidance/metrics.h"
#include "offshore_gnc/guidance/paths.h"
#include "offshore_gnc/guidance/pipeline.h"

using namespace offshore_gnc;
using namespace offshore_gnc::guidance;
using V3 = Eigen::Vector3d;

namespace {
VehicleState at(double n, double e, double d = 0.0, double yaw = 0.0) {
  VehicleState s;
  s.position = V3(n, e, d);
  s.yaw = yaw;
  return s;
}
LosParams plain() {
  LosParams p;
  p.ki = 0.0;
  p.adaptive_crab = false;
  return p;
}
}  // namespace

TEST(LosGeometry, HandComputedCases) {
  double e, s;
  // Leg north from the origin; vehicle 3 m east (starboard) and 4 m along.
  EXPECT_NEAR(legGeometry({0, 0}, {10, 0}, {4, 3}, &e, &s), 0.0, 1e-12);
  EXPECT_NEAR(e, 3.0, 1e-12);
  EXPECT_NEAR(s, 4.0, 1e-12);
  // Leg east: chi_p = 90 deg; a point north of it is to port (negative e).
  EXPECT_NEAR(legGeometry({0, 0}, {0, 10}, {2, 5}, &e, &s), kPi / 2, 1e-12);
  EXPECT_NEAR(e, -2.0, 1e-12);
  EXPECT_NEAR(s, 5.0, 1e-12);
  // Leg south-west (225 deg): point (0, -sqrt 2): e = -(0)(sin) + (-sqrt2)(cos(-135deg)) = 1.
  EXPECT_NEAR(legGeometry({0, 0}, {-10, -10}, {0, -std::sqrt(2.0)}, &e, &s), -3 * kPi / 4, 1e-12);
  EXPECT_NEAR(e, 1.0, 1e-12);
  EXPECT_NEAR(s, 1.0, 1e-12);
}

TEST(Los, SteeringLawEq49to412) {
  LosGuidance g(plain());
  ASSERT_TRUE(g.setPath({V3(0, 0, 0), V3(100, 0, 0)}));
  const auto o = g.update(at(10, 5), 0.1);
  EXPECT_EQ(o.mode, Mode::kFollowPath);
  EXPECT_NEAR(o.cross_track_error, 5.0, 1e-12);
  // psi_d = chi_p + atan(-Kp e) = atan(-0.5)
  EXPECT_NEAR(o.desired_heading, std::atan(-0.5), 1e-12);
  EXPECT_NEAR(o.distance_to_go, std::hypot(90.0, 5.0), 1e-9);
  EXPECT_NEAR(o.path_point.x(), 10.0, 1e-12);
}

TEST(Los, IntegralAntiWindupBoundsSteering) {
  LosParams p = plain();
  p.ki = 0.01;
  p.integral_limit = 0.2;
  LosGuidance g(p);
  g.setPath({V3(0, 0, 0), V3(1000, 0, 0)});
  LosOutput o;
  for (int i = 0; i < 10000; ++i) o = g.update(at(10, 20), 0.1);
  // Kp e = 2, integral term at most 0.2 -> psi_d = atan(-2.2)
  EXPECT_NEAR(o.desired_heading, std::atan(-2.2), 1e-9);
}

TEST(Los, AdaptiveCrabGrowsWithStandingError) {
  LosParams p = plain();
  p.adaptive_crab = true;
  LosGuidance g(p);
  g.setPath({V3(0, 0, 0), V3(1000, 0, 0)});
  LosOutput o;
  auto moving = [](double n, double e, double speed) {
    VehicleState s = at(n, e);
    s.velocity.x() = speed;
    return s;
  };
  for (int i = 0; i < 100; ++i) o = g.update(moving(10, 1.0, 1.5), 0.1);
  EXPECT_GT(o.crab_angle, 0.0);  // drift to starboard -> beta_hat > 0 -> heading further to port
  EXPECT_LT(o.desired_heading, std::atan(-0.1));
  const double after_moving = o.crab_angle;
  // The update scales with the speed (Fossen's ALOS): a boat at rest learns nothing from its standing error.
  for (int i = 0; i < 100; ++i) o = g.update(moving(10, 1.0, 0.0), 0.1);
  EXPECT_DOUBLE_EQ(o.crab_angle, after_moving);
  for (int i = 0; i < 100000; ++i) o = g.update(moving(10, 50.0, 1.5), 0.1);
  EXPECT_NEAR(o.crab_angle, p.crab_limit, 1e-12);
}

// crab_band: 8 m off the path (an approach) the estimate learns nothing; within the band it learns as before.
TEST(Los, CrabLearnsOnlyWithinItsBand) {
  LosParams p = plain();
  p.adaptive_crab = true;
  p.crab_band = 2.0;
  LosGuidance g(p);
  g.setPath({V3(0, 0, 0), V3(1000, 0, 0)});
  LosOutput o;
  VehicleState s = at(10, 8.0);
  s.velocity.x() = 0.3;
  for (int i = 0; i < 400; ++i) o = g.update(s, 0.1);
  EXPECT_EQ(o.crab_angle, 0.0);
  s.position.y() = 1.0;
  for (int i = 0; i < 400; ++i) o = g.update(s, 0.1);
  EXPECT_GT(o.crab_angle, 0.0);
  EXPECT_EQ(GuidanceParams::preset("girona500").los.crab_band, 2.0);  // the Girona500's (docs/parameters.md)
}

TEST(Los, MeasuredCrabAngleIsTheSideslipOverGroundOnEveryLeg) {
  // The GPS-compass gives course and heading: beta = atan2(v, u), low-passed, known on a new leg at once.
  LosParams p = plain();
  p.measured_crab = true;
  p.crab_tf = 1.0;
  LosGuidance g(p);
  g.setPath({V3(0, 0, 0), V3(1000, 0, 0)});
  VehicleState s = at(10, 0.0);
  s.velocity = V3(1.0, 0.2, 0.0);  // slipping to starboard
  LosOutput o;
  for (int i = 0; i < 100; ++i) o = g.update(s, 0.1);
  EXPECT_NEAR(o.crab_angle, std::atan2(0.2, 1.0), 1e-3);
  EXPECT_NEAR(o.desired_heading, -std::atan2(0.2, 1.0), 1e-3);  // on the line: the bow up-current by beta
  // below crab_min_speed the sideslip means nothing: the last value is kept
  s.velocity = V3(0.05, 0.1, 0.0);
  for (int i = 0; i < 100; ++i) o = g.update(s, 0.1);
  EXPECT_NEAR(o.crab_angle, std::atan2(0.2, 1.0), 1e-3);
}

namespace {
// RMS cross-track error on each leg of a lawnmower (north, south, north, 40 m long, 5 m apart) flown by a
// kinematic vehicle that turns at once to the desired heading, at 0.7 m/s through the water in a 0.2 m/s current
// from the west: the crab needed is +-asin(0.2 / 0.7) = +-16.6 deg, of opposite signs on the two directions.
std::vector<double> lawnmowerLegErrors(bool crab_ned) {
  LosParams p = plain();
  p.kp = 0.333;  // the aColor's look-ahead (Table 4.2)
  p.adaptive_crab = true;
  p.crab_gain = 0.1;  // the aColor's, per m/s of speed
  p.crab_ned = crab_ned;
  p.sphere = true;
  p.acceptance_radius = 1.4;
  LosGuidance g(p);
  g.setPath(lawnmower({0, 0}, 0.0, 40.0, 10.0, 5.0, 0.0));
  VehicleState s = at(0, 0);
  const Eigen::Vector2d current(0.0, 0.2);
  const double dt = 0.1, u = 0.7;
  std::vector<double> sq(g.path().size(), 0.0), n(g.path().size(), 0.0);
  for (int i = 0; i < 6000; ++i) {
    const LosOutput o = g.update(s, dt);
    if (o.mode != Mode::kFollowPath) break;
    sq[o.active_leg] += o.cross_track_error * o.cross_track_error;
    n[o.active_leg] += 1.0;
    s.yaw = o.desired_heading;
    const Eigen::Vector2d ground = u * Eigen::Vector2d(std::cos(s.yaw), std::sin(s.yaw)) + current;
    s.position.head<2>() += dt * ground;
    s.velocity.head<2>() = Eigen::Vector2d(std::cos(s.yaw) * ground.x() + std::sin(s.yaw) * ground.y(),
                                           -std::sin(s.yaw) * ground.x() + std::cos(s.yaw) * ground.y());
  }
  for (std::size_t k = 0; k < sq.size(); ++k) sq[k] = n[k] > 0 ? std::sqrt(sq[k] / n[k]) : 0.0;
  return sq;
}
}  // namespace

TEST(Los, CrabInNedCarriesTheCurrentToLegsOfOtherDirections) {
  // The path-frame estimate enters each return leg with the crab of the opposite sign; the NED one with the crab
  // the current asks of that leg. Legs 1 and 5 north, 3 south, 2 and 4 (5 m, with the current) east.
  const std::vector<double> path_frame = lawnmowerLegErrors(false), ned = lawnmowerLegErrors(true);
  ASSERT_EQ(ned.size(), 6u);
  for (std::size_t leg = 1; leg < ned.size(); ++leg)
    std::printf("leg %zu: RMS cross-track %.3f m path frame, %.3f m NED\n", leg, path_frame[leg], ned[leg]);
  for (std::size_t leg : {3u, 5u}) {  // the long legs after the first, each after two turns
    EXPECT_LT(ned[leg], 0.35) << "leg " << leg;
    EXPECT_GT(path_frame[leg], 2.0 * ned[leg]) << "leg " << leg;
  }
}

TEST(Los, CrabInNedOnOneStraightLegIsThePathFrameEstimate) {
  for (bool ned : {false, true}) {
    LosParams p = plain();
    p.adaptive_crab = true;
    p.crab_ned = ned;
    LosGuidance g(p);
    g.setPath({V3(0, 0, 0), V3(700, 700, 0)});  // north-east: both NED components move
    LosOutput o;
    VehicleState s = at(10, 11.0);
    s.velocity.x() = 1.0;  // the update scales with the speed
    for (int i = 0; i < 100; ++i) o = g.update(s, 0.1);
    EXPECT_NEAR(o.crab_angle, 100 * 0.1 * p.crab_gain * 10.0 / std::hypot(10.0, 1.0 / std::sqrt(2.0)) /
                                  std::sqrt(2.0), 1e-9) << ned;
  }
}

TEST(Los, CircleOfAcceptanceSwitches) {
  LosParams p = plain();
  p.acceptance_radius = 5.0;
  LosGuidance g(p);
  g.setPath({V3(0, 0, 0), V3(50, 0, 0), V3(50, 50, 0)});
  EXPECT_EQ(g.update(at(44, 2), 0.1).active_leg, 1u);  // 6.3 m from wp 1
  EXPECT_EQ(g.update(at(46, 2), 0.1).active_leg, 2u);  // 4.5 m: inside the circle
}

TEST(Los, SafetyBoxCornersUseTheDetourRadius) {
  LosParams p = plain();
  p.acceptance_radius = 16.0;
  p.detour_radius = 2.0;
  LosGuidance g(p);
  // wp 1 is a safety-box corner: 4 m away is inside the 16 m circle but not within the detour radius
  ASSERT_TRUE(g.setPath({V3(0, 0, 0), V3(20, -9, 0), V3(40, -9, 0), V3(80, 0, 0)}, false, {false, true, true, false}));
  EXPECT_EQ(g.update(at(16.5, -7.3), 0.1).active_leg, 1u);
  EXPECT_EQ(g.update(at(18.5, -8.2), 0.1).active_leg, 2u);  // 1.7 m from the corner
  // without the flag, the same waypoint is switched on the 16 m circle
  LosGuidance plain_route(p);
  ASSERT_TRUE(plain_route.setPath({V3(0, 0, 0), V3(20, -9, 0), V3(40, -9, 0), V3(80, 0, 0)}));
  EXPECT_EQ(plain_route.update(at(16.5, -7.3), 0.1).active_leg, 2u);
  // flags that do not match the waypoints: a clear refusal (hold), not a guess
  EXPECT_FALSE(g.setPath({V3(0, 0, 0), V3(20, 0, 0)}, false, {true}));
  EXPECT_EQ(g.update(at(0, 0), 0.1).mode, Mode::kHoldFault);
  // merged duplicates keep the corner flag
  ASSERT_TRUE(g.setPath({V3(0, 0, 0), V3(20, -9, 0), V3(20, -9, 0), V3(80, 0, 0)}, false, {false, false, true, false}));
  EXPECT_EQ(g.update(at(16.5, -7.3), 0.1).active_leg, 1u);
}

TEST(Los, SphereOfAcceptanceUsesDepth) {
  LosParams p = plain();
  p.acceptance_radius = 3.0;
  p.sphere = true;
  LosGuidance g(p);
  g.setPath({V3(0, 0, 5), V3(50, 0, 5), V3(50, 50, 5)});
  // Horizontally 1 m short but 4 m too shallow: outside the sphere, and not yet passed.
  EXPECT_EQ(g.update(at(49, 0, 1), 0.1).active_leg, 1u);
  EXPECT_EQ(g.update(at(49, 0, 4), 0.1).active_leg, 2u);
  EXPECT_NEAR(g.update(at(49, 0, 4), 0.1).desired_depth, 5.0, 1e-12);
}

TEST(Los, PassedWaypointRuleNeverLoopsBack) {
  LosParams p = plain();
  p.acceptance_radius = 2.0;
  LosGuidance g(p);
  g.setPath({V3(0, 0, 0), V3(50, 0, 0), V3(100, 0, 0)});
  // Missed the circle by 10 m laterally but is beyond the waypoint along the leg.
  const auto o = g.update(at(51, 10), 0.1);
  EXPECT_EQ(o.active_leg, 2u);
  EXPECT_NEAR(std::abs(o.desired_heading), std::atan(1.0), 1e-9);  // steers back to the path, not to wp 1
}

TEST(Los, LastWaypointNeedsTheFinalRadiusAndSlowsDown) {
  LosParams p = plain();
  p.acceptance_radius = 16.0;  // 2 L_USV: intermediate waypoints every 10 m switch early
  p.final_radius = 2.0;
  p.approach_distance = 20.0;
  p.approach_speed = 0.3;
  p.surge_speed = 1.5;
  LosGuidance g(p);
  g.setPath({V3(0, 0, 0), V3(10, 0, 0), V3(20, 0, 0), V3(50, 0, 0)});
  auto o = g.update(at(5, 0), 0.1);  // 5 m from wp 1 (inside 16 m) -> switches on, 15 m from wp 2 too
  EXPECT_EQ(o.active_leg, 3u);
  EXPECT_DOUBLE_EQ(o.desired_surge, 1.5);  // 45 m to go: cruise
  o = g.update(at(40, 0), 0.1);            // 10 m short of the end: inside R but not the final radius
  EXPECT_EQ(o.mode, Mode::kFollowPath);
  EXPECT_NEAR(o.desired_surge, 0.3 + 0.5 * 1.2, 1e-9);  // halfway through the slowdown
  o = g.update(at(48.5, 0.5), 0.1);
  EXPECT_EQ(o.mode, Mode::kStationKeeping);
  EXPECT_NEAR(o.hold_position.x(), 50.0, 1e-12);
  LosParams bad = p;
  bad.final_radius = -1.0;
  EXPECT_THROW(LosGuidance{bad}, ConfigError);
}

// The pipeline's word that dynamic positioning's straight run to the end passes an obstacle: the last waypoint is
// then reached as a detour corner is (detour_radius), the leg leading to it.
TEST(Los, ABlockedFinalRunTakesTheLastWaypointOnTheDetourRadius) {
  LosParams p = plain();
  p.final_radius = 10.0;
  p.detour_radius = 3.0;
  LosGuidance blocked(p), free(p);
  for (LosGuidance* g : {&blocked, &free}) g->setPath({V3(0, 0, 0), V3(50, 0, 0)});
  blocked.setFinalRunBlocked(true);
  EXPECT_EQ(free.update(at(42, 1), 0.1).mode, Mode::kStationKeeping);  // 8 m short: inside final_radius
  EXPECT_EQ(blocked.update(at(42, 1), 0.1).mode, Mode::kFollowPath);
  EXPECT_EQ(blocked.update(at(47.5, 1), 0.1).mode, Mode::kStationKeeping);
}

TEST(Los, EndOfPathStationKeeping) {
  LosGuidance g(plain());
  g.setPath({V3(0, 0, 0), V3(50, 0, 0)});
  const auto o = g.update(at(60, 1), 0.1);
  EXPECT_EQ(o.mode, Mode::kStationKeeping);
  EXPECT_EQ(o.desired_surge, 0.0);
  EXPECT_NEAR(o.hold_position.x(), 50.0, 1e-12);
  EXPECT_FALSE(o.status_text.empty());
  EXPECT_EQ(g.update(at(0, 0), 0.1).mode, Mode::kStationKeeping);  // stays finished
}

TEST(Los, StationKeepingHoldsTheLastLegsAngleOnEveryStep) {
  // The hold's heading (dynamic positioning's, until it learns a current) is the last leg's, not only on the
  // step that finishes the path: the ROS controller may first see the hold a step later.
  LosGuidance g(plain());
  g.setPath({V3(0, 0, 0), V3(30, 0, 0), V3(30, -30, 0)});
  g.update(at(30, -2), 0.1);
  for (int i = 0; i < 3; ++i) {
    const auto o = g.update(at(31, -31), 0.1);
    ASSERT_EQ(o.mode, Mode::kStationKeeping);
    EXPECT_NEAR(o.path_angle, -kPi / 2, 1e-9) << "step " << i;
    EXPECT_NEAR(o.desired_heading, -kPi / 2, 1e-9) << "step " << i;
  }
}

TEST(Los, BadInputHoldsWithoutNaN) {
  LosGuidance g(plain());
  auto finite = [](const LosOutput& o) {
    return std::isfinite(o.desired_heading) && std::isfinite(o.desired_surge) && std::isfinite(o.desired_depth) &&
           o.hold_position.allFinite() && std::isfinite(o.cross_track_error) && std::isfinite(o.crab_angle);
  };
  // no path
  auto o = g.update(at(1, 2), 0.1);
  EXPECT_EQ(o.mode, Mode::kIdle);
  EXPECT_TRUE(finite(o));
  // one-point path
  EXPECT_FALSE(g.setPath({V3(5, 5, 0)}));
  o = g.update(at(1, 2), 0.1);
  EXPECT_EQ(o.mode, Mode::kHoldFault);
  EXPECT_NE(o.status_text.find("single waypoint"), std::string::npos);
  EXPECT_EQ(o.desired_surge, 0.0);
  EXPECT_TRUE(finite(o));
  // duplicates only
  EXPECT_FALSE(g.setPath({V3(5, 5, 0), V3(5, 5, 0), V3(5, 5, 0)}));
  EXPECT_EQ(g.update(at(1, 2), 0.1).mode, Mode::kHoldFault);
  // duplicates merged in an otherwise good path
  EXPECT_TRUE(g.setPath({V3(0, 0, 0), V3(0, 0, 0), V3(20, 0, 0), V3(20, 0, 0), V3(40, 0, 0)}));
  EXPECT_EQ(g.path().size(), 3u);
  EXPECT_GT(g.counters().get("duplicate_waypoints"), 0u);
  // NaN waypoint
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(g.setPath({V3(0, 0, 0), V3(nan, 0, 0)}));
  EXPECT_EQ(g.update(at(1, 2), 0.1).mode, Mode::kHoldFault);
  // NaN pose on a good path: hold the last good position
  g.setPath({V3(0, 0, 0), V3(100, 0, 0)});
  g.update(at(3, 4), 0.1);
  o = g.update(at(nan, 0), 0.1);
  EXPECT_EQ(o.mode, Mode::kHoldFault);
  EXPECT_TRUE(finite(o));
  EXPECT_NEAR(o.hold_position.x(), 3.0, 1e-12);
  EXPECT_EQ(g.counters().get("nan_pose"), 1u);
  // NaN dt does not poison the integrators
  o = g.update(at(3, 4), nan);
  EXPECT_TRUE(finite(o));
}

TEST(Los, ResumeKeepsProgressOnReplan) {
  LosGuidance g(plain());
  g.setPath({V3(0, 0, 0), V3(10, 0, 0), V3(20, 0, 0), V3(30, 0, 0)});
  g.update(at(25, 0.5), 0.1);
  ASSERT_TRUE(g.setPath({V3(0, 0, 0), V3(10, 0, 0), V3(20, 0, 0), V3(30, 0, 0), V3(40, 0, 0)}, true));
  EXPECT_EQ(g.activeLeg(), 3u);
}

TEST(Paths, StraightLineEvery10m) {
  const auto p = straightLine(V3(0, 0, 0), V3(35, 0, 0));
  ASSERT_EQ(p.size(), 5u);
  EXPECT_NEAR(p[1].x(), 10.0, 1e-12);
  EXPECT_NEAR(p[3].x(), 30.0, 1e-12);
  EXPECT_NEAR(p[4].x(), 35.0, 1e-12);
  EXPECT_EQ(straightLine(V3(0, 0, 0), V3(40, 0, 0)).size(), 5u);
  // target at the vehicle's own position: empty (guidance reports "no path" and holds)
  EXPECT_TRUE(straightLine(V3(3, 4, 0), V3(3, 4, 0)).empty());
  EXPECT_TRUE(straightLine(V3(std::nan(""), 4, 0), V3(3, 4, 0)).empty());
}

TEST(Paths, Lawnmower) {
  const auto p = lawnmower({0, 0}, 0.0, 40.0, 20.0, 10.0, 5.0);
  ASSERT_EQ(p.size(), 6u);  // three tracks
  EXPECT_NEAR(p[1].x(), 40.0, 1e-12);
  EXPECT_NEAR(p[2].y(), 10.0, 1e-12);
  EXPECT_NEAR(p[2].x(), 40.0, 1e-12);
  EXPECT_NEAR(p[3].x(), 0.0, 1e-12);
  EXPECT_NEAR(p[5].y(), 20.0, 1e-12);
  for (const auto& w : p) EXPECT_EQ(w.z(), 5.0);
  EXPECT_TRUE(lawnmower({0, 0}, 0.0, -1.0, 20.0, 10.0, 5.0).empty());
}

TEST(Metrics, RmseSdMae) {
  const auto m = computeMetrics({1.0, -1.0, 3.0, -3.0, std::nan("")});
  EXPECT_EQ(m.samples, 4u);
  EXPECT_NEAR(m.rmse, std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(m.mae, 2.0, 1e-12);
  EXPECT_NEAR(m.sd, std::sqrt(5.0), 1e-12);
  const auto b = computeMetrics({2.0, 2.0});
  EXPECT_NEAR(b.sd, 0.0, 1e-12);
  EXPECT_NEAR(b.rmse, 2.0, 1e-12);
}

TEST(Metrics, CsvColumnWithModeFilter) {
  std::istringstream in("t,mode,cross_track_error\n0,1,1.0\n0.1,2,9.0\n0.2,1,-1.0\n");
  const auto v = readCsvColumn(in, "cross_track_error", 1);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[1], -1.0);
  std::istringstream bad("t,x\n0,1\n");
  EXPECT_THROW(readCsvColumn(bad, "cross_track_error"), std::runtime_error);
}

TEST(Los, ANewPathEndingWhereItHoldsKeepsHolding) {
  // The AUV mission's ascent sends the hold at a new depth every half second: no restart on the lead-in leg (it
  // turned the hold into path following for a moment), the new depth held at once. A path ending elsewhere restarts.
  LosParams p = plain();
  p.acceptance_radius = 0.5;  // the Girona500's sphere
  p.sphere = true;
  LosGuidance g(p);
  g.setPath({V3(0, 0, 3), V3(2, 0, 3)});
  ASSERT_EQ(g.update(at(2.2, 0.3, 3), 0.1).mode, Mode::kStationKeeping);
  g.setPath({V3(0, 0, 2.9), V3(2, 0, 2.9)});
  const auto o = g.update(at(1.0, 0.6, 3), 0.1);  // 1.2 m off: a fresh path would follow the lead-in again
  EXPECT_EQ(o.mode, Mode::kStationKeeping);
  EXPECT_NEAR(o.desired_depth, 2.9, 1e-12);
  EXPECT_NEAR(o.path_angle, 0.0, 1e-12);
  g.setPath({V3(0, 0, 2.9), V3(5, 0, 2.9)});
  EXPECT_EQ(g.update(at(1.0, 0.6, 3), 0.1).mode, Mode::kFollowPath);
}
