#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/mission/mission.h"

using namespace offshore_gnc;
using namespace offshore_gnc::mission;

namespace {
// A search area north of the start, as the default scenario's.
AuvMissionParams auvParams(int confirm = 2, double radius = 2.0, double max_age = 120.0) {
  AuvMissionParams p;
  p.confirm_detections = confirm;
  p.confirm_radius = radius;
  p.detection_max_age = max_age;
  p.coverage = {20.0, 60.0, -10.0, 10.0, 3.0, 5.0};
  return p;
}
}  // namespace

TEST(AuvMission, FirstConfirmedDetectionStopsTheSearch) {
  AuvMission m(auvParams(2, 2.0, 120.0));
  EXPECT_EQ(m.phase(), AuvPhase::Idle);
  EXPECT_FALSE(m.onDetection({1, 1, 5}, 0.0));  // not started yet
  m.start(10.0);
  EXPECT_FALSE(m.onDetection({40, 3, 5}, 20.0));   // first sighting
  EXPECT_FALSE(m.onDetection({10, -8, 5}, 21.0));  // clutter elsewhere
  EXPECT_TRUE(m.onDetection({41, 3.4, 5}, 25.0));  // same object again: confirmed
  EXPECT_EQ(m.phase(), AuvPhase::TargetFound);
  EXPECT_TRUE(m.thrustersOff());
  ASSERT_TRUE(m.target().has_value());
  EXPECT_NEAR(m.target()->x(), 40.5, 1e-9);
  EXPECT_NEAR(m.target()->y(), 3.2, 1e-9);
  EXPECT_NEAR(m.detectionTime(), 15.0, 1e-9);
  EXPECT_FALSE(m.onDetection({10, -8, 5}, 30.0));  // after the stop nothing changes
  EXPECT_NEAR(m.target()->x(), 40.5, 1e-9);
}

TEST(AuvMission, StaleCandidatesAreForgotten) {
  AuvMission m(auvParams(2, 2.0, 60.0));
  m.start(0.0);
  EXPECT_FALSE(m.onDetection({5, 5, 5}, 1.0));
  EXPECT_FALSE(m.onDetection({5, 5, 5}, 100.0));  // 99 s later: the first one has expired
  EXPECT_EQ(m.phase(), AuvPhase::Coverage);
  EXPECT_TRUE(m.onDetection({5.5, 5, 5}, 110.0));
}

TEST(AuvMission, NoTargetAndBadInput) {
  AuvMission m(auvParams());
  m.start(0.0);
  EXPECT_FALSE(m.onDetection({NAN, 0, 0}, 1.0));
  EXPECT_EQ(m.counters().get("detection_not_finite"), 1u);
  m.onCoverageFinished(300.0);
  EXPECT_EQ(m.phase(), AuvPhase::NoTarget);
  EXPECT_TRUE(m.finished());
  EXPECT_FALSE(m.target().has_value());
  EXPECT_NE(m.detail().find("without a confirmed detection"), std::string::npos);
  EXPECT_THROW(AuvMission(auvParams(0, 2.0, 60.0)), ConfigError);
  AuvMissionParams no_area = auvParams();
  no_area.coverage = {};  // nothing configured: refused, naming the rectangle
  try {
    AuvMission bad(no_area);
    FAIL() << "an empty coverage area was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("coverage"), std::string::npos) << e.what();
  }
}

TEST(UsvMission, TransitToStandoffThenArrive) {
  UsvMission m({10.0, 3.0, 1.0, 30.0});
  m.onPose({0, 0}, 0.0, 0.0);
  EXPECT_EQ(m.phase(), UsvPhase::StationKeeping);
  EXPECT_TRUE(m.path().empty());
  EXPECT_TRUE(m.onTarget({0, 48}, 5.0));
  EXPECT_EQ(m.phase(), UsvPhase::Transit);
  ASSERT_EQ(m.path().size(), 6u);  // 0 10 20 30 40 45
  EXPECT_NEAR(m.path().back().y(), 45.0, 1e-9);
  EXPECT_NEAR(m.stationPoint()->y(), 45.0, 1e-9);
  EXPECT_EQ(m.pathVersion(), 1);
  EXPECT_FALSE(m.onTarget({0, 48.2}, 6.0));  // the relay's repeat does not replan
  EXPECT_EQ(m.pathVersion(), 1);
  m.onPathFinished(60.0);
  EXPECT_EQ(m.phase(), UsvPhase::Arrived);
  EXPECT_TRUE(m.finished());
}

TEST(UsvMission, OnStationOnceWithinItsRadiusOfThePointGuidanceHolds) {
  UsvMission m;  // station_radius 1 m
  m.onPose({0, 0}, 0.0, 0.0);
  ASSERT_TRUE(m.onTarget({0, 48}, 5.0));
  m.onPathFinished(60.0);
  ASSERT_EQ(m.phase(), UsvPhase::Arrived);
  EXPECT_TRUE(std::isnan(m.onStationSince()));
  m.onPose({0, 43.5}, 1.5, 61.0);  // 1.5 m short of the station at E 45
  EXPECT_TRUE(std::isnan(m.onStationSince()));
  m.onPose({0, 44.3}, 1.5, 70.0);
  EXPECT_DOUBLE_EQ(m.onStationSince(), 70.0);
  m.onPose({0, 40.0}, 1.5, 80.0);  // later wandering does not move when the hold began
  EXPECT_DOUBLE_EQ(m.onStationSince(), 70.0);
  // guidance holding another point (the station was too close to an obstacle): measured against that one
  UsvMission n;
  n.onPose({0, 0}, 0.0, 0.0);
  ASSERT_TRUE(n.onTarget({0, 48}, 5.0));
  n.onGuidance(guidance::Mode::kStationKeeping, 0.0, 60.0, Eigen::Vector2d(4, 45));
  n.onPathFinished(60.0);
  n.onPose({0, 45}, 1.5, 61.0);
  EXPECT_TRUE(std::isnan(n.onStationSince()));
  n.onPose({3.5, 45}, 1.5, 65.0);
  EXPECT_DOUBLE_EQ(n.onStationSince(), 65.0);
  // a new target: the hold is measured afresh
  ASSERT_TRUE(n.onTarget({30, 48}, 70.0));
  EXPECT_TRUE(std::isnan(n.onStationSince()));
}

TEST(UsvMission, ManualAlwaysWins) {
  UsvMission m;
  m.onPose({0, 0}, 0.0, 0.0);
  m.onTarget({50, 0}, 1.0);
  m.onManual(true, 2.0);
  EXPECT_EQ(m.phase(), UsvPhase::Manual);
  EXPECT_NE(m.detail().find("manual"), std::string::npos);
  m.onManual(false, 3.0);
  EXPECT_EQ(m.phase(), UsvPhase::Transit);  // resumes
  EXPECT_EQ(m.counters().get("manual_takeovers"), 1u);
}

TEST(UsvMission, SilentPeerHoldsPosition) {
  UsvMission m({10.0, 3.0, 1.0, 30.0});
  m.onPose({1, 2}, 0.0, 0.0);
  m.tick(20.0);
  EXPECT_EQ(m.phase(), UsvPhase::StationKeeping);
  m.tick(31.0);
  EXPECT_EQ(m.phase(), UsvPhase::PeerLost);
  EXPECT_NEAR(m.stationPoint()->x(), 1.0, 1e-12);
  m.onPeerAlive(32.0);
  EXPECT_EQ(m.phase(), UsvPhase::StationKeeping);
}

TEST(UsvMission, BadTargets) {
  UsvMission m;
  EXPECT_FALSE(m.onTarget({10, 10}, 0.0));  // no pose yet
  EXPECT_EQ(m.counters().get("target_before_pose"), 1u);
  m.onPose({0, 0}, 0.0, 0.0);
  EXPECT_FALSE(m.onTarget({NAN, 10}, 1.0));
  EXPECT_EQ(m.counters().get("target_not_finite"), 1u);
  EXPECT_FALSE(m.onTarget({0, 2}, 2.0));  // at the vehicle: inside the stand-off, nothing to do
  EXPECT_EQ(m.phase(), UsvPhase::Arrived);
  EXPECT_TRUE(m.path().empty());
  m.onPose({NAN, 0}, 0.0, 3.0);
  EXPECT_EQ(m.counters().get("pose_not_finite"), 1u);
}

TEST(CoveragePath, Lawnmower) {
  auto p = coveragePath({20, 60, -10, 10, 3, 5});
  ASSERT_EQ(p.size(), 10u);  // five legs at east -10, -5, 0, 5, 10
  EXPECT_EQ(p[0], Eigen::Vector3d(20, -10, 3));
  EXPECT_EQ(p[1], Eigen::Vector3d(60, -10, 3));
  EXPECT_EQ(p[2], Eigen::Vector3d(60, -5, 3));  // turns at the far end
  EXPECT_EQ(p[3], Eigen::Vector3d(20, -5, 3));
  EXPECT_EQ(p.back(), Eigen::Vector3d(60, 10, 3));
  EXPECT_TRUE(coveragePath({60, 20, -10, 10, 3, 5}).empty());
  EXPECT_TRUE(coveragePath({20, 60, -10, 10, NAN, 5}).empty());
  EXPECT_TRUE(coveragePath({20, 60, 10, -10, 3, 5}).empty());
}

TEST(HoldPath, EndsAtThePointAlongTheHeading) {
  auto h = holdPath({10, 20}, kPi / 2, 2.0);  // heading east
  ASSERT_EQ(h.size(), 2u);
  EXPECT_NEAR(h[0].x(), 10.0, 1e-12);
  EXPECT_NEAR(h[0].y(), 18.0, 1e-12);
  EXPECT_EQ(h[1], Eigen::Vector2d(10, 20));
  EXPECT_TRUE(holdPath({NAN, 0}, 0.0).empty());
}

TEST(AuvMission, StartsAfterTheDelayAndSaysWhatGuidanceAndTheUsvMustBeTold) {
  AuvMissionParams p = auvParams();
  p.start_delay = 2.0;
  AuvMission m(p);
  m.tick(10.0);  // the first tick starts the clock
  EXPECT_EQ(m.phase(), AuvPhase::Idle);
  EXPECT_FALSE(m.takePath());
  m.tick(12.0);
  EXPECT_EQ(m.phase(), AuvPhase::Coverage);
  auto path = m.takePath();
  ASSERT_TRUE(path);
  EXPECT_EQ(*path, coveragePath(p.coverage));
  EXPECT_FALSE(m.takePath());  // once
  // following, then station keeping before a detection: the coverage ended without a target
  m.onGuidance(guidance::Mode::kStationKeeping, 13.0);  // not yet following: ignored
  EXPECT_EQ(m.phase(), AuvPhase::Coverage);
  m.onGuidance(guidance::Mode::kFollowPath, 14.0);
  EXPECT_FALSE(m.onDetection({40, 3, 3}, 20.0));
  EXPECT_TRUE(m.onDetection({40.2, 3, 3}, 30.0));
  auto stop = m.takePath();
  ASSERT_TRUE(stop);
  EXPECT_TRUE(stop->empty());  // thrusters off
  auto t = m.takeTarget();
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->x(), 40.1, 1e-9);
  EXPECT_FALSE(m.takeTarget());
  m.onGuidance(guidance::Mode::kStationKeeping, 40.0);
  EXPECT_EQ(m.phase(), AuvPhase::TargetFound);
}

TEST(AuvMission, EndOfCoverageWithoutATargetStops) {
  AuvMission m(auvParams());
  m.start(0.0);
  ASSERT_TRUE(m.takePath());
  m.onGuidance(guidance::Mode::kFollowPath, 1.0);
  m.onGuidance(guidance::Mode::kStationKeeping, 300.0);
  EXPECT_EQ(m.phase(), AuvPhase::NoTarget);
  auto stop = m.takePath();
  ASSERT_TRUE(stop);
  EXPECT_TRUE(stop->empty());
}

TEST(UsvMission, HoldsWhereItStartsThenFollowsTheTransitAndArrives) {
  UsvMission m;
  m.onPose({5, 7}, 0.5, 0.0);
  auto hold = m.takePath();
  ASSERT_TRUE(hold);
  ASSERT_EQ(hold->size(), 2u);
  EXPECT_NEAR((hold->back() - Eigen::Vector2d(5, 7)).norm(), 0.0, 1e-12);  // the hold path ends where it started
  m.onPose({6, 7}, 0.5, 1.0);
  EXPECT_FALSE(m.takePath());  // the start is fixed by the first pose
  ASSERT_TRUE(m.onTarget({6, 47}, 2.0));
  auto transit = m.takePath();
  ASSERT_TRUE(transit);
  EXPECT_EQ(*transit, m.path());
  m.onGuidance(guidance::Mode::kStationKeeping, 40.0, 2.1);  // the old hold path's end, not the transit's
  EXPECT_EQ(m.phase(), UsvPhase::Transit);
  m.onGuidance(guidance::Mode::kFollowPath, 30.0, 3.0);
  EXPECT_NEAR(m.distanceToGo(), 30.0, 1e-12);
  m.onGuidance(guidance::Mode::kStationKeeping, 0.0, 90.0);
  EXPECT_EQ(m.phase(), UsvPhase::Arrived);
  EXPECT_TRUE(std::isnan(m.distanceToGo()));
}

TEST(UsvMission, ManualCommandsHoldAutonomyOffUntilTheyStop) {
  UsvMissionParams p;
  p.manual_timeout = 1.0;
  UsvMission m(p);
  m.onPose({0, 0}, 0.0, 0.0);
  m.onManualCommand(5.0);
  m.tick(5.5);
  EXPECT_EQ(m.phase(), UsvPhase::Manual);
  m.onManualCommand(5.9);
  m.tick(6.5);
  EXPECT_EQ(m.phase(), UsvPhase::Manual);
  m.tick(7.0);  // 1.1 s after the last one
  EXPECT_EQ(m.phase(), UsvPhase::StationKeeping);
}

TEST(UsvMission, ATargetOutsideTheOperatingRegionIsRefusedSayingWhy) {
  UsvMission m;
  // the USV preset's region: 2 km square around the origin
  m.setRegion(safety::Region::fromList({-1000, -1000, 1000, -1000, 1000, 1000, -1000, 1000}));
  m.onPose({0, 0}, 0.0, 0.0);
  (void)m.takePath();
  // a target computed on another lake's origin: 2,520 km away
  EXPECT_FALSE(m.onTarget({2520.0e3, 0.0}, 1.0));
  EXPECT_EQ(m.phase(), UsvPhase::StationKeeping);  // the mission goes on waiting, no transit planned
  EXPECT_FALSE(m.takePath());
  EXPECT_EQ(m.counters().get("target_outside_region"), 1u);
  EXPECT_NE(m.refusal().find("2520.0 km"), std::string::npos) << m.refusal();
  EXPECT_NE(m.detail().find("refused a target"), std::string::npos) << m.detail();
  EXPECT_FALSE(m.onTarget({2520.0e3, 0.1}, 2.0));  // the relay's resend is refused again, counted once
  EXPECT_EQ(m.counters().get("target_outside_region"), 1u);
  // a good target afterwards is used
  EXPECT_TRUE(m.onTarget({40.0, 30.0}, 3.0));
  EXPECT_EQ(m.phase(), UsvPhase::Transit);
}

TEST(UsvMission, ATransitThatWouldLeaveAConcaveRegionIsRefused) {
  UsvMission m;
  // a U-shaped lake: two arms (east 0..20 and 80..100, north to 100) joined in the south (north 0..20)
  m.setRegion(safety::Region::fromList({0, 0, 100, 0, 100, 20, 20, 20, 20, 80, 100, 80, 100, 100, 0, 100}));
  m.onPose({90, 10}, 0.0, 0.0);  // in the west arm
  EXPECT_FALSE(m.onTarget({90, 90}, 1.0));  // in the east arm: straight across the land between
  EXPECT_NE(m.refusal().find("would leave the operating region"), std::string::npos) << m.refusal();
  EXPECT_EQ(m.phase(), UsvPhase::StationKeeping);
  EXPECT_TRUE(m.onTarget({10, 15}, 2.0));  // down its own arm: inside all the way
}
