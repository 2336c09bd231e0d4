// guidance::GuidancePipeline: the policy that only the nodelet knew before (replanning, kept sides, stale
// navigation, rejected paths, expired obstacles), fed plain structs and the time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "offshore_gnc/guidance/paths.h"
#include "offshore_gnc/guidance/pipeline.h"

using namespace offshore_gnc;
using namespace offshore_gnc::guidance;

namespace {
VehicleState at(double n, double e, double yaw = 0.0) {
  VehicleState s;
  s.position = {n, e, 0.0};
  s.yaw = yaw;
  return s;
}
SbbObstacle buoy(double n, double e) {
  SbbObstacle o;
  o.id = 7;
  o.origin = {n, e};
  o.length = o.width = 1.2;
  return o;
}
std::vector<Eigen::Vector3d> route() { return straightLine({0, 0, 0}, {100, 0, 0}, 10.0); }
// The detour side of the plan (the box cuts several 10 m legs: one box per leg, all on one side).
SbbSide sideOf(const SbbPlan& plan) {
  SbbSide side = SbbSide::kNone;
  for (const auto& b : plan.boxes) {
    if (!b.cuts_path) continue;
    if (side != SbbSide::kNone && b.side != side) return SbbSide::kBlocked;  // sides disagree: a failure
    side = b.side;
  }
  return side;
}
}  // namespace

TEST(GuidancePipeline, NothingBeforeTheFirstPoseThenFollows) {
  GuidancePipeline g(GuidanceParams::preset("usv"));
  GuidanceOutput o;
  EXPECT_FALSE(g.update(0.1, 0.1, o));
  g.setPath(route());
  g.setState(at(0, 2), 0.1);
  ASSERT_TRUE(g.update(0.2, 0.1, o));
  EXPECT_EQ(o.los.mode, Mode::kFollowPath);
  EXPECT_TRUE(o.planned_changed);
  EXPECT_EQ(o.reference.mode, ReferenceMode::kFollow);
  EXPECT_NEAR(o.reference.point.y(), 0.0, 1e-9);  // the projection on the leg
  ASSERT_TRUE(g.update(0.3, 0.1, o));
  EXPECT_FALSE(o.planned_changed);
}

TEST(GuidancePipeline, ReplansWhileAnObstacleMovesAndResumesOnTheNearestLeg) {
  GuidancePipeline g(GuidanceParams::preset("usv"));
  GuidanceOutput o;
  g.setPath(route());
  g.setState(at(20, 0), 0.0);
  g.setObstacles({buoy(50, 0.5)}, 0.0);
  ASSERT_TRUE(g.update(0.1, 0.1, o));
  ASSERT_TRUE(o.boxes_changed);
  const SbbSide side = sideOf(g.plan());
  ASSERT_TRUE(side == SbbSide::kPort || side == SbbSide::kStarboard);
  int off = 0;  // detour corners in the path followed
  for (const auto& w : g.plannedPath()) off += std::abs(w.y()) > 5.0;
  EXPECT_GE(off, 2);
  // the buoy drifts 3 m north: the plan follows it; LOS resumes on the leg nearest the boat, not at the start
  g.setState(at(21, 0), 1.0);
  g.setObstacles({buoy(53, 0.5)}, 1.0);
  ASSERT_TRUE(g.update(1.1, 0.1, o));
  EXPECT_TRUE(o.planned_changed);
  EXPECT_EQ(sideOf(g.plan()), side);
  EXPECT_GE(o.los.active_leg, 2u);
  // 0.2 m is below the replan distance: the boxes are refreshed, the path followed is not re-set
  g.setState(at(22, 0), 2.0);
  g.setObstacles({buoy(53.2, 0.5)}, 2.0);
  ASSERT_TRUE(g.update(2.1, 0.1, o));
  EXPECT_TRUE(o.boxes_changed);
  EXPECT_FALSE(o.planned_changed);
}

TEST(GuidancePipeline, KeepsTheChosenSideWhileTheBoatDriftsAcrossTheCentreLine) {
  GuidancePipeline g(GuidanceParams::preset("usv"));
  GuidanceOutput o;
  g.setPath(route());
  g.setState(at(10, 0.4), 0.0);  // a little east of the buoy's line: starboard is closer
  g.setObstacles({buoy(50, 0.0)}, 0.0);
  ASSERT_TRUE(g.update(0.1, 0.1, o));
  const SbbSide side = sideOf(g.plan());
  ASSERT_TRUE(side == SbbSide::kPort || side == SbbSide::kStarboard);
  g.setState(at(12, -0.4), 1.0);  // the current sets it across the line
  g.setObstacles({buoy(50, 0.0)}, 1.0);
  ASSERT_TRUE(g.update(1.1, 0.1, o));
  EXPECT_EQ(sideOf(g.plan()), side);
  // a new route chooses afresh
  g.setPath(straightLine({12, -0.4, 0}, {100, -0.4, 0}, 10.0));
  ASSERT_TRUE(g.update(1.2, 0.1, o));
  EXPECT_TRUE(o.planned_changed);
}

TEST(GuidancePipeline, StaleNavigationHoldsTheLastGoodPosition) {
  GuidancePipeline g(GuidanceParams::preset("usv"));
  GuidanceOutput o;
  g.setPath(route());
  g.setState(at(5, 1), 0.0);
  ASSERT_TRUE(g.update(0.1, 0.1, o));
  EXPECT_EQ(o.los.mode, Mode::kFollowPath);
  ASSERT_TRUE(g.update(1.5, 0.1, o));  // 1.5 s without odometry (timeout 1 s)
  EXPECT_EQ(o.los.mode, Mode::kHoldFault);
  EXPECT_NE(o.los.status_text.find("stale"), std::string::npos);
  EXPECT_EQ(o.reference.mode, ReferenceMode::kHold);
  EXPECT_NEAR(o.reference.point.x(), 5.0, 1e-9);
  EXPECT_NEAR(o.reference.point.y(), 1.0, 1e-9);
  EXPECT_GE(g.counters().get("stale_odom"), 1u);
  g.setState(at(5.5, 1), 1.6);  // navigation back: following again
  ASSERT_TRUE(g.update(1.7, 0.1, o));
  EXPECT_EQ(o.los.mode, Mode::kFollowPath);
}

TEST(GuidancePipeline, ObstaclesNotRefreshedExpireAtTheNextReplan) {
  GuidancePipeline g(GuidanceParams::preset("usv"));
  GuidanceOutput o;
  g.setPath(route());
  g.setState(at(10, 0), 0.0);
  g.setObstacles({buoy(50, 0.5)}, 0.0);
  ASSERT_TRUE(g.update(0.1, 0.1, o));
  ASSERT_FALSE(g.plan().boxes.empty());
  g.setPath(route());  // a replan 10 s later: the LiDAR has not seen the buoy since (timeout 5 s)
  ASSERT_TRUE(g.update(10.0, 0.1, o));
  EXPECT_TRUE(g.plan().boxes.empty());
  EXPECT_EQ(g.plannedPath().size(), route().size());
}

// What the mission knows of and the LiDAR may not see (the surfaced AUV the USV recovers): planned round like a seen
// obstacle, kept without refreshing until the mission says otherwise, merged with what the LiDAR sees.
TEST(GuidancePipeline, KnownObstaclesArePlannedRoundUntilWithdrawn) {
  GuidancePipeline g(GuidanceParams::preset("usv"));
  GuidanceOutput o;
  g.setPath(route());
  g.setState(at(10, 0), 0.0);
  SbbObstacle auv = buoy(50, 0.3);
  auv.id = 99;
  g.setKnownObstacles({auv});
  ASSERT_TRUE(g.update(0.1, 0.1, o));
  const SbbSide side = sideOf(g.plan());
  ASSERT_TRUE(side == SbbSide::kPort || side == SbbSide::kStarboard);
  auto clearOf = [&](const Eigen::Vector2d& c) {  // the least distance of the path followed from c
    double d = 1e9;
    const auto& p = g.plannedPath();
    for (std::size_t i = 1; i < p.size(); ++i) {
      const Eigen::Vector2d a = p[i - 1].head<2>(), b = p[i].head<2>();
      const double k = std::clamp((c - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      d = std::min(d, (a + k * (b - a) - c).norm());
    }
    return d;
  };
  EXPECT_GT(clearOf({50, 0.3}), 5.0);  // the box's half width, 0.6 + safety_y 5, plus the corridor
  // 60 s on, never refreshed (a seen obstacle expires after 5 s) and a buoy seen beside the route: both planned round
  g.setPath(route());
  g.setState(at(10, 0), 60.0);
  g.setObstacles({buoy(80, -0.2)}, 60.0);
  ASSERT_TRUE(g.update(60.1, 0.1, o));
  EXPECT_GT(clearOf({50, 0.3}), 5.0);
  EXPECT_GT(clearOf({80, -0.2}), 5.0);
  // withdrawn (the USV closes in along its own axis): the route is straight again where the AUV was (and the buoy,
  // seen in one frame only, is gone once it has been missed for sbb/clear_time)
  g.setKnownObstacles({});
  g.setObstacles({}, 60.2);
  g.setObstacles({}, 62.2);
  g.setState(at(10, 0), 62.2);
  ASSERT_TRUE(g.update(62.3, 0.1, o));
  EXPECT_TRUE(o.planned_changed);
  EXPECT_LT(clearOf({50, 0.3}), 0.5);
  // bad geometry is dropped and counted, as a seen obstacle's
  SbbObstacle bad = auv;
  bad.origin.x() = std::nan("");
  g.setKnownObstacles({bad});
  EXPECT_EQ(g.counters().get("bad_obstacles"), 1u);
}

// Control may hold the boat on station while it turns onto the path only where nothing guidance knows of lies within
// the hull's sweep (its longest reach) and sbb/hold_clearance: the surfaced AUV beside the recovery's first leg counts
// though no box is planned round it.
TEST(GuidancePipeline, RoomToTurnOnlyWhereTheHullsSweepIsClear) {
  GuidancePipeline g(GuidanceParams::preset("usv"));
  g.setHullReach({5.3, 2.7, 1.3});
  GuidanceOutput o;
  g.setPath(route());
  g.setState(at(10, 0, kPi), 0.0);
  ASSERT_TRUE(g.update(0.1, 0.1, o));
  ASSERT_EQ(o.reference.mode, ReferenceMode::kFollow);
  EXPECT_TRUE(o.reference.room_to_turn) << "open water";
  SbbObstacle auv = buoy(10, -8.0);  // abeam: 8 m off, its extent 0.6 m; the sweep 5.3 m + hold_clearance 3 m
  auv.id = 99;
  g.setKnownObstacles({auv});
  ASSERT_TRUE(g.update(0.2, 0.1, o));
  EXPECT_FALSE(o.reference.room_to_turn) << "the AUV within the sweep";
  auv.origin = {10, -9.5};
  g.setKnownObstacles({auv});
  ASSERT_TRUE(g.update(0.3, 0.1, o));
  EXPECT_TRUE(o.reference.room_to_turn) << "the AUV beyond the sweep";
}

TEST(GuidancePipeline, BadInputIsRefusedWithAReason) {
  GuidancePipeline g(GuidanceParams::preset("usv"));
  GuidanceOutput o;
  g.setState(at(0, 0), 0.0);
  SbbObstacle bad = buoy(30, 0);
  bad.length = NAN;
  g.setObstacles({bad}, 0.0);
  EXPECT_EQ(g.counters().get("bad_obstacles"), 1u);
  g.rejectPath("path rejected: frame 'odom', expected 'map_ned'");
  ASSERT_TRUE(g.update(0.1, 0.1, o));
  EXPECT_EQ(o.los.mode, Mode::kHoldFault);
  EXPECT_NE(o.los.status_text.find("frame 'odom'"), std::string::npos);
  EXPECT_EQ(o.reference.mode, ReferenceMode::kHold);
  g.setPath({});  // the AUV's stop: no path, neutral
  ASSERT_TRUE(g.update(0.2, 0.1, o));
  EXPECT_EQ(o.los.mode, Mode::kIdle);
  EXPECT_EQ(o.reference.mode, ReferenceMode::kIdle);
  GuidanceParams p = GuidanceParams::preset("usv");
  p.los.kp = -1.0;
  EXPECT_THROW(g.setParams(p), ConfigError);
  EXPECT_THROW(GuidanceParams::preset("submarine"), ConfigError);
}

TEST(GuidancePipeline, AHoldPointTooCloseToAnObstacleIsRefusedAndAClearOneHeld) {
  GuidanceParams p = GuidanceParams::preset("usv");
  p.obstacles.sensor_near = 0.0;  // a sensor that sees right up to its bow: a buoy it misses there is gone,
  p.obstacles.clear_time = 0.0;   // at its first miss
  GuidancePipeline g(p);
  g.setState(at(-10, 0), 0.0);
  g.setPath({{-12, 0, 0}, {-10, 0, 0}});  // a hold (the mission's lead-in to its station at N -10)
  GuidanceOutput out;
  ASSERT_TRUE(g.update(0.0, 0.1, out));
  ASSERT_EQ(out.reference.mode, ReferenceMode::kHold);
  EXPECT_NEAR((out.reference.point.head<2>() - Eigen::Vector2d(-10, 0)).norm(), 0.0, 1e-9);
  // a buoy turns up 1 m from the station: keep-out 0.6 m + hold_clearance 3 m about it
  g.setObstacles({buoy(-9, 0)}, 0.1);
  ASSERT_TRUE(g.update(0.2, 0.1, out));
  const Eigen::Vector2d held = out.reference.point.head<2>();
  EXPECT_GE((held - Eigen::Vector2d(-9, 0)).cwiseAbs().maxCoeff(), 3.6 - 1e-6);
  EXPECT_NEAR(held.x(), -12.6, 0.01);  // the nearest clear point: straight back out of the square
  EXPECT_NE(out.los.status_text.find("too close to obstacle 7"), std::string::npos) << out.los.status_text;
  EXPECT_EQ(g.counters().get("hold_point_in_box"), 1u);
  // the obstacle flickers in the next scans: the moved point stays where it was (no wandering), counted once
  for (int i = 0; i < 5; ++i) {
    g.setObstacles({buoy(-9 + 0.1 * i, 0.05 * i)}, 0.3 + 0.1 * i);
    ASSERT_TRUE(g.update(0.3 + 0.1 * i, 0.1, out));
    EXPECT_NEAR((out.reference.point.head<2>() - held).norm(), 0.0, 1e-9);
  }
  EXPECT_EQ(g.counters().get("hold_point_in_box"), 1u);
  // the hold (a path shorter than the corridor) is not turned into a detour round the box
  EXPECT_EQ(g.plannedPath().size(), 2u);
  // gone: the station itself again
  g.setObstacles({}, 1.0);
  ASSERT_TRUE(g.update(1.0, 0.1, out));
  EXPECT_NEAR((out.reference.point.head<2>() - Eigen::Vector2d(-10, 0)).norm(), 0.0, 1e-9);
  // a known obstacle given unboxed (the mission's surfaced AUV its recovery holds bow-on to) moves no hold point
  SbbObstacle auv = buoy(-9, 0);
  auv.boxed = false;
  g.setKnownObstacles({auv});
  ASSERT_TRUE(g.update(1.1, 0.1, out));
  EXPECT_NEAR((out.reference.point.head<2>() - Eigen::Vector2d(-10, 0)).norm(), 0.0, 1e-9);
}

TEST(GuidancePipeline, PresetsAreTheThesisTables) {
  EXPECT_DOUBLE_EQ(GuidanceParams::preset("usv").los.acceptance_radius, 16.0);  // 2 L_USV
  EXPECT_DOUBLE_EQ(GuidanceParams::preset("girona500").los.kp, 0.0333);         // Table 4.3
  EXPECT_DOUBLE_EQ(GuidanceParams::preset("acolor").los.kp, 0.333);             // Table 4.2
  EXPECT_TRUE(GuidanceParams::preset("acolor").los.sphere);
  EXPECT_FALSE(GuidanceParams::preset("girona500").sbb_enabled);
}

TEST(SafeHoldPoint, AMovedHoldStaysOnItsSideWhenTheBoxTakesItIn) {
  // A hold point on a buoy: four ways out, equally near. Once moved to one side, a jitter of the LiDAR's box that
  // takes that side in moves it out on the same side, not across to the other (6.7 m here; 10 m in
  // two_obstacles.yaml, where the flips put the hull on a buoy).
  SbbParams p;
  p.hold_clearance = 3.0;
  const Eigen::Vector2d point(0, 0);
  const SafeHold first = safeHoldPoint(point, 0.0, {buoy(0, 0)}, p);
  ASSERT_TRUE(first.moved);
  EXPECT_NEAR(first.point.norm(), 3.6, 1e-2);
  const Eigen::Vector2d side = first.point;
  SbbObstacle jittered = buoy(0, 0);
  jittered.origin += 0.5 * side.normalized();  // the box now covers the side held
  const SafeHold fresh = safeHoldPoint(point, 0.0, {jittered}, p);
  const SafeHold kept = safeHoldPoint(point, 0.0, {jittered}, p, side);
  ASSERT_TRUE(kept.moved);
  EXPECT_NEAR((kept.point - side).norm(), 0.5, 1e-2);    // just out of the grown box, on the same side
  EXPECT_GT((fresh.point - side).norm(), 6.0);            // without the hint: the nearest way out, across
  EXPECT_NEAR(kept.point.norm(), 4.1, 1e-2);
}

// The LiDAR on the bow is blind astern and close beside the hull: a buoy seen for a while and then left astern or
// alongside is still planned round (and a hold kept clear of it), while one the sensor looks at and does not see is
// gone at once; a target seen once (spray) is not remembered; after obstacle_memory it is forgotten.
TEST(ObstacleMemory, KeepsWhatTheSensorCannotSeeAndDropsWhatItLooksAtAndMisses) {
  ObstacleMemoryParams p;  // the USV's: 275 degrees from 1.5 m ahead, blind nearer than 12 m
  p.clear_time = 0.0;      // dropped at the first miss in view (clear_time: the next test)
  ObstacleMemory m(p);
  const Eigen::Vector2d here(0, 0);
  for (int i = 0; i < 5; ++i) m.update({buoy(20, 0)}, here, 0.0, 0.1 * i);  // ahead, 5 frames
  ASSERT_EQ(m.active(0.5).size(), 1u);
  // the boat went past it: 12 m astern, outside the aperture
  m.update({}, {32, 0}, 0.0, 10.0);
  EXPECT_EQ(m.active(10.0).size(), 1u);
  EXPECT_EQ(m.remembered(), 1);
  // turned round, 30 m off and looking at it, it is not there: gone
  m.update({}, {50, 0}, kPi, 11.0);
  EXPECT_TRUE(m.active(11.0).empty());
  // alongside (3 m abeam, inside the aperture but nearer than sensor_near): kept; after obstacle_memory: forgotten
  for (int i = 0; i < 5; ++i) m.update({buoy(20, 0)}, here, 0.0, 20.0 + 0.1 * i);
  m.update({}, {20, -3}, 0.0, 30.0);
  EXPECT_EQ(m.active(30.0).size(), 1u);
  m.update({}, {20, -3}, 0.0, 20.4 + p.memory + 1.0);
  EXPECT_TRUE(m.active(20.4 + p.memory + 1.0).empty());
  // seen once (spray), then astern: not kept (clear_time 0 here)
  m.update({buoy(20, 0)}, here, 0.0, 400.0);
  m.update({}, {32, 0}, 0.0, 401.0);
  EXPECT_TRUE(m.active(401.0).empty());
  // a cluster seen again a little off (it splits, it swings) is the same obstacle: its count goes on
  for (int i = 0; i < 5; ++i) m.update({buoy(20, 0.4 * (i % 2))}, here, 0.0, 500.0 + 0.1 * i);
  m.update({}, {32, 0}, 0.0, 501.0);
  EXPECT_EQ(m.active(501.0).size(), 1u);
  // no frame for obstacle_timeout (the sensor is gone): nothing is planned round
  EXPECT_TRUE(m.active(501.0 + p.timeout + 0.1).empty());
}

// A low buoy drops out of the lowest layer's frames now and then as the boat pitches, in full view: with
// clear_time it is dropped only when missed that long, and seen again in between it starts over.
TEST(ObstacleMemory, AnObstacleInViewIsDroppedOnlyWhenMissedForClearTime) {
  ObstacleMemoryParams p;
  p.clear_time = 2.0;
  ObstacleMemory m(p);
  const Eigen::Vector2d here(0, 0);
  for (int i = 0; i < 5; ++i) m.update({buoy(20, 0)}, here, 0.0, 0.1 * i);  // ahead, 5 frames: confirmed
  m.update({}, here, 0.0, 1.0);                                            // missed, in view
  EXPECT_EQ(m.active(1.0).size(), 1u);
  m.update({}, here, 0.0, 2.9);
  EXPECT_EQ(m.active(2.9).size(), 1u);
  m.update({buoy(20, 0)}, here, 0.0, 3.0);  // seen again: the misses start over
  m.update({}, here, 0.0, 4.0);
  m.update({}, here, 0.0, 5.9);
  EXPECT_EQ(m.active(5.9).size(), 1u);
  m.update({}, here, 0.0, 6.0);  // missed in view for 2 s: gone
  EXPECT_TRUE(m.active(6.0).empty());
  // a target seen once (spray), then out of view: kept only for clear_time, not for obstacle_memory
  m.update({buoy(30, 0)}, here, 0.0, 7.0);
  m.update({}, here, kPi, 7.1);
  EXPECT_EQ(m.active(7.1).size(), 1u);
  m.update({}, here, kPi, 9.1);
  EXPECT_TRUE(m.active(9.1).empty());
}

// A low buoy 25 m off comes in one frame of three as the boat pitches at rest: it is planned round in every frame
// between (the detour came and went 32 times in 14 s when each miss dropped it before it was confirmed), and its
// count goes on through the misses, so it is confirmed and kept when the boat has passed it.
TEST(ObstacleMemory, AFlickeringTargetIsKeptThroughItsMissesAndConfirmed) {
  ObstacleMemoryParams p;  // clear_time 2 s, confirm_frames 5
  ObstacleMemory m(p);
  const Eigen::Vector2d here(0, 0);
  for (int i = 0; i < 15; ++i) {
    const double t = 0.08 * i;  // 12.5 Hz
    m.update(i % 3 == 0 ? std::vector<SbbObstacle>{buoy(25, 0)} : std::vector<SbbObstacle>{}, here, 0.0, t);
    EXPECT_EQ(m.active(t).size(), 1u) << "frame " << i;
  }
  m.update({}, {40, 0}, 0.0, 5.0);  // passed it: astern, kept as a confirmed obstacle
  EXPECT_EQ(m.active(5.0).size(), 1u);
}

// A vessel's cluster shrinks to the edge the LiDAR sees for a few frames: it keeps its largest extent for
// extent_hold, then takes what it is seen as.
TEST(ObstacleMemory, ATargetKeepsItsLargestRecentExtent) {
  ObstacleMemoryParams p;
  p.extent_hold = 10.0;
  ObstacleMemory m(p);
  const Eigen::Vector2d here(0, 0);
  SbbObstacle vessel = buoy(20, 0);
  vessel.length = 4.0;
  vessel.width = 3.0;
  m.update({vessel}, here, 0.0, 0.0);
  SbbObstacle edge = buoy(20.5, 0.5);
  edge.length = edge.width = 0.1;
  m.update({edge}, here, 0.0, 0.1);
  ASSERT_EQ(m.active(0.1).size(), 1u);
  EXPECT_DOUBLE_EQ(m.active(0.1)[0].length, 4.0);
  EXPECT_DOUBLE_EQ(m.active(0.1)[0].width, 4.0);
  EXPECT_LT((m.active(0.1)[0].origin - edge.origin).norm(), 1e-12);  // where it is seen now
  for (double t = 0.2; t < p.extent_hold; t += 0.1) m.update({edge}, here, 0.0, t);
  EXPECT_DOUBLE_EQ(m.active(p.extent_hold - 0.05)[0].length, 4.0);
  m.update({edge}, here, 0.0, p.extent_hold + 0.1);
  EXPECT_DOUBLE_EQ(m.active(p.extent_hold + 0.1)[0].length, 0.1);
  // 0: each frame's own
  p.extent_hold = 0.0;
  ObstacleMemory own(p);
  own.update({vessel}, here, 0.0, 0.0);
  own.update({edge}, here, 0.0, 0.1);
  EXPECT_DOUBLE_EQ(own.active(0.1)[0].length, 0.1);
}

// In the pipeline: the hold point stays clear of a buoy the boat has come alongside and no longer sees.
TEST(GuidancePipeline, KeepsAHoldClearOfAnObstacleLeftOutOfTheLidarsView) {
  GuidancePipeline g(GuidanceParams::preset("usv"));
  g.setHullReach({5.3, 2.7, 1.3});
  GuidanceOutput o;
  g.setPath({{0, 0, 0}, {2, 0, 0}});  // a hold at (2, 0), heading north
  g.setState(at(-20, 0), 0.0);
  for (int i = 0; i < 10; ++i) g.setObstacles({buoy(-2, 1)}, 0.1 * i);  // seen on the way in
  g.setState(at(2, 0), 60.0);
  g.setObstacles({}, 60.0);  // the buoy is under the stern now: astern of the sensor
  ASSERT_TRUE(g.update(60.1, 0.1, o));
  ASSERT_EQ(g.obstacles(60.1).size(), 1u);
  // the hull (2.7 m astern of the point, 1.3 m abeam) keeps hold_clearance (3 m) from the buoy's extent
  EXPECT_GT((o.reference.point.head<2>() - Eigen::Vector2d(2, 0)).norm(), 0.5);
  EXPECT_NE(o.los.status_text.find("too close to obstacle 7"), std::string::npos) << o.los.status_text;
}

// Dynamic positioning runs straight to its point and plans round nothing: inside final_radius of the path's end with
// an obstacle between (off the path, so no detour is planned), the boat keeps following the leg until it is clear.
TEST(GuidancePipeline, TheEndIsHeldOnlyWhenTheStraightRunThereIsClear) {
  GuidanceParams p = GuidanceParams::preset("usv");
  ASSERT_DOUBLE_EQ(p.los.final_radius, 10.0);
  GuidancePipeline g(p);
  GuidanceOutput o;
  g.setPath(straightLine({0, 0, 0}, {50, 0, 0}, 10.0));
  g.setHullReach({5.3, 2.7, 1.3});
  SbbObstacle b = buoy(45, 13);  // 13 m off the path: no safety box cuts it
  g.setState(at(45, 8, -1.2), 0.0);  // 9.4 m from the end, 8 m off the leg, the buoy 5 m abeam
  g.setObstacles({b}, 0.0);
  ASSERT_TRUE(g.update(0.1, 0.1, o));
  EXPECT_EQ(g.plan().status, "path clear");
  EXPECT_EQ(o.los.mode, Mode::kFollowPath);
  EXPECT_EQ(g.counters().get("final_run_blocked"), 1u);
  g.setState(at(48, 4, -1.2), 0.2);  // the run from here keeps 5.3 m + the buoy's half extent clear of it
  g.setObstacles({b}, 0.2);
  ASSERT_TRUE(g.update(0.3, 0.1, o));
  EXPECT_EQ(o.los.mode, Mode::kStationKeeping);
  GuidancePipeline unhindered(p);  // without the buoy: held at once
  unhindered.setPath(straightLine({0, 0, 0}, {50, 0, 0}, 10.0));
  unhindered.setState(at(45, 8, -1.2), 0.0);
  ASSERT_TRUE(unhindered.update(0.1, 0.1, o));
  EXPECT_EQ(o.los.mode, Mode::kStationKeeping);
}
