// guidance::ColregsAvoidance through the pipeline (issue 33): the encounter classified at its sector boundaries,
// the give-way alteration to starboard that passes astern, the stand-on vessel that keeps its course until the
// rule-17 trigger, a head-on meeting in which both turn to starboard, and bad tracks counted. The boats here are
// kinematic: the heading follows guidance's at a limited rate of turn, at its surge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/guidance/colregs.h"
#include "offshore_gnc/guidance/paths.h"
#include "offshore_gnc/guidance/pipeline.h"

using namespace offshore_gnc;
using namespace offshore_gnc::guidance;

namespace {
const ColregsParams kP;

Eigen::Vector2d ahead(double bearing_deg, double range) {
  const double b = deg2rad(bearing_deg);
  return range * Eigen::Vector2d(std::cos(b), std::sin(b));
}
// We at the origin heading north; the contact at `bearing_deg` off our bow on `course_deg`.
Encounter seen(double bearing_deg, double course_deg, const ColregsParams& p = kP) {
  return classify({0, 0}, 0.0, ahead(bearing_deg, 50.0), deg2rad(course_deg), p);
}

// A boat under guidance: heading follows the reference at up to 5 deg/s, speed its surge.
struct Boat {
  GuidancePipeline g;
  Eigen::Vector2d p;
  double yaw = 0.0, u = 1.5;
  GuidanceOutput out;
  Boat(const Eigen::Vector2d& start, double yaw0, const Eigen::Vector2d& end) : g(GuidanceParams::preset("usv")), p(start), yaw(yaw0) {
    g.setHullReach({4.0, 4.0, 1.5});
    g.setPath(straightLine({start.x(), start.y(), 0}, {end.x(), end.y(), 0}, 10.0));
  }
  Eigen::Vector2d velocity() const { return u * Eigen::Vector2d(std::cos(yaw), std::sin(yaw)); }
  Contact asContact(std::uint32_t id) const {
    Contact c;
    c.id = id;
    c.position = p;
    c.velocity = velocity();
    c.covariance = 0.01 * Eigen::Matrix4d::Identity();
    c.length = 8.0;
    c.width = 3.0;
    c.confirmed = true;
    return c;
  }
  void step(double t, double dt, const std::vector<Contact>& traffic) {
    VehicleState s;
    s.position = {p.x(), p.y(), 0.0};
    s.yaw = yaw;
    s.velocity = {u, 0.0, 0.0};
    g.setState(s, t);
    g.setTracks(traffic, t);
    ASSERT_TRUE(g.update(t, dt, out));
    yaw += std::clamp(angleDiff(out.reference.heading, yaw), -deg2rad(5.0) * dt, deg2rad(5.0) * dt);
    u = out.reference.surge > 0.0 ? out.reference.surge : u;
    p += dt * velocity();
  }
};

// A vessel on a constant course and speed.
Contact vessel(const Eigen::Vector2d& p, double course_deg, double speed, double t = 0.0) {
  Contact c;
  c.id = 9;
  c.velocity = speed * Eigen::Vector2d(std::cos(deg2rad(course_deg)), std::sin(deg2rad(course_deg)));
  c.position = p + t * c.velocity;
  c.covariance = 0.01 * Eigen::Matrix4d::Identity();
  c.length = 8.0;
  c.width = 3.0;
  c.confirmed = true;
  return c;
}
// Hull to hull: the boats' reach (4 m hull, half the 8 m contact).
double hullDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return (a - b).norm() - 8.0; }
}  // namespace

// ------------------------------------------------------------------------------------------- the classifier
TEST(ColregsClassify, OvertakingFromJustMoreThan22_5DegAbaftItsBeam) {
  // The contact 50 m dead ahead; we lie at 180 - course off its bow: 112.6 deg (course 67.4) is abaft, 112.4 is not.
  EXPECT_EQ(seen(0.0, 67.4), Encounter::kOvertaking);
  EXPECT_EQ(seen(0.0, -67.4), Encounter::kOvertaking);
  EXPECT_EQ(seen(0.0, 67.6), Encounter::kCrossingGiveWay);
  EXPECT_EQ(seen(0.0, 180.0 - 112.4), Encounter::kCrossingGiveWay);
  EXPECT_EQ(seen(0.0, 0.0), Encounter::kOvertaking);  // dead astern of it, same course
}

TEST(ColregsClassify, BeingOvertakenByOneFromJustMoreThan22_5DegAbaftOurBeam) {
  EXPECT_EQ(seen(112.6, 0.0), Encounter::kOvertaken);
  EXPECT_EQ(seen(-112.6, 0.0), Encounter::kOvertaken);
  EXPECT_EQ(seen(112.4, 0.0), Encounter::kCrossingGiveWay);  // abeam to starboard, a little forward: crossing
  EXPECT_EQ(seen(-112.4, 0.0), Encounter::kCrossingStandOn);
}

TEST(ColregsClassify, HeadOnWithinTheSectorOfBearingAndReciprocalCourse) {
  EXPECT_EQ(seen(9.9, 180.0), Encounter::kHeadOn);
  EXPECT_EQ(seen(-9.9, 180.0), Encounter::kHeadOn);
  EXPECT_EQ(seen(10.1, 180.0), Encounter::kCrossingGiveWay);
  EXPECT_EQ(seen(-10.1, 180.0), Encounter::kCrossingStandOn);
  EXPECT_EQ(seen(0.0, 170.1), Encounter::kHeadOn);
  EXPECT_EQ(seen(0.0, -170.1), Encounter::kHeadOn);
  EXPECT_EQ(seen(0.0, 169.9), Encounter::kCrossingGiveWay);
  EXPECT_EQ(seen(-1.0, -169.9), Encounter::kCrossingStandOn);
}

TEST(ColregsClassify, CrossingFromStarboardGivesWayFromPortStandsOn) {
  EXPECT_EQ(seen(30.0, 270.0), Encounter::kCrossingGiveWay);
  EXPECT_EQ(seen(90.0, 200.0), Encounter::kCrossingGiveWay);
  EXPECT_EQ(seen(-30.0, 90.0), Encounter::kCrossingStandOn);
  EXPECT_EQ(seen(-90.0, 160.0), Encounter::kCrossingStandOn);
}

TEST(ColregsClassify, TheSectorsAreParameters) {
  ColregsParams p;
  p.head_on_sector = deg2rad(20.0);
  p.abaft_beam = deg2rad(30.0);
  EXPECT_EQ(seen(15.0, 180.0, p), Encounter::kHeadOn);
  EXPECT_EQ(seen(0.0, 180.0 - 120.1, p), Encounter::kOvertaking);
  EXPECT_EQ(seen(0.0, 180.0 - 119.9, p), Encounter::kCrossingGiveWay);
  EXPECT_EQ(seen(119.9, 0.0, p), Encounter::kCrossingGiveWay);
  EXPECT_EQ(seen(120.1, 0.0, p), Encounter::kOvertaken);
}

TEST(ColregsGeometry, ClosestApproachAndCrossingAhead) {
  // we north at 1.5 m/s; it from 100 m east at N 100 heading west at 1.5 m/s: both at (100, 0) in 66.7 s
  const Cpa a = closestApproach({0, 0}, {1.5, 0}, {100, 100}, {0, -1.5});
  EXPECT_NEAR(a.tcpa, 66.67, 0.01);
  EXPECT_NEAR(a.distance, 0.0, 1e-6);
  const Cpa still = closestApproach({0, 0}, {0, 0}, {10, 0}, {0, 0});  // no relative motion: now, no NaN
  EXPECT_EQ(still.tcpa, 0.0);
  EXPECT_NEAR(still.distance, 10.0, 1e-12);
  // turning to port by 10 deg we reach its track line at E -17 in 67 s, it in 78 s: ahead of it
  EXPECT_TRUE(crossesAhead({0, 0}, 1.5 * Eigen::Vector2d(std::cos(-0.17), std::sin(-0.17)), {100, 100}, {0, -1.5}));
  // to starboard by 10 deg, at E 17 in 67 s, which it passed at 55 s: astern of it (however close); by 60 deg too
  EXPECT_FALSE(crossesAhead({0, 0}, 1.5 * Eigen::Vector2d(std::cos(0.17), std::sin(0.17)), {100, 100}, {0, -1.5}));
  EXPECT_FALSE(crossesAhead({0, 0}, 1.5 * Eigen::Vector2d(std::cos(1.05), std::sin(1.05)), {100, 100}, {0, -1.5}));
  EXPECT_FALSE(crossesAhead({0, 0}, {1.5, 0}, {0, 10}, {1.5, 0}));  // parallel: never
}

// ------------------------------------------------------------------------------------------- bad input
TEST(ColregsTracks, BadTracksAreCountedNeverUsed) {
  ColregsAvoidance c;
  Contact nan = vessel({50, 0}, 180.0, 1.5);
  nan.velocity.x() = std::numeric_limits<double>::quiet_NaN();
  Contact zero = vessel({50, 0}, 180.0, 1.5);
  zero.id = 0;
  Contact twice = vessel({50, 0}, 180.0, 1.5);  // id 9 as the first good one below
  Contact still = vessel({30, 0}, 180.0, 0.0);
  still.id = 4;
  Contact tentative = vessel({30, 0}, 180.0, 1.5);
  tentative.id = 5;
  tentative.confirmed = false;
  c.setTracks({nan, vessel({50, 0}, 180.0, 1.5), zero, twice, still, tentative}, 1.0);
  c.setTracks({}, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(c.counters().get("bad_tracks"), 2u);
  EXPECT_EQ(c.counters().get("unknown_track_id"), 2u);
  // the one good moving vessel dead ahead on the reciprocal: a head-on give-way; the still and tentative ones none
  const ColregsOutput o = c.update(1.0, {0, 0}, {1.5, 0}, 0.0, 0.0, 1.5, 4.0, {}, true);
  EXPECT_EQ(o.encounter, Encounter::kHeadOn);
  EXPECT_EQ(o.contact, 9u);
  EXPECT_TRUE(o.steer);
  EXPECT_GT(angleDiff(o.course, 0.0), deg2rad(34.9));  // starboard, at least course_offset
  EXPECT_EQ(c.counters().get("encounters"), 1u);
}

TEST(ColregsTracks, AMovingTrackIsNotBoxedAStillOneIs) {
  GuidancePipeline g(GuidanceParams::preset("usv"));
  VehicleState s;
  s.position = {0, 0, 0};
  g.setPath(straightLine({0, 0, 0}, {200, 0, 0}, 10.0));
  g.setState(s, 0.0);
  Contact buoy = vessel({40, 0}, 0.0, 0.05);  // a buoy's track: slower than min_speed
  buoy.id = 3;
  g.setTracks({buoy, vessel({60, 20}, 270.0, 1.5)}, 0.0);
  SbbObstacle b, v;
  b.origin = {40, 0.2};
  b.length = b.width = 1.0;
  v.origin = {60.3, 19.0};  // the vessel's target: its centroid a little off its track's position
  v.length = 8.0;
  v.width = 3.0;
  g.setObstacles({b, v}, 0.05);
  const auto planned = g.obstacles(0.05);
  ASSERT_EQ(planned.size(), 1u);
  EXPECT_EQ(planned[0].origin, b.origin);
}

// ------------------------------------------------------------------------------------------- manoeuvres
TEST(ColregsManoeuvre, GiveWayToOneFromStarboardTurnsToStarboardAndPassesAstern) {
  // We north along E 0 at 1.5 m/s; a vessel from 100 m east on N 100 heading west at 1.5 m/s: a collision at
  // (100, 0) in 67 s if neither acts.
  Boat us({0, 0}, 0.0, {300, 0});
  const Eigen::Vector2d start(100, 100);
  double min_hull = 1e9, crossed_at = -1, their_east = 0, our_east = 0;
  bool turned = false, ported = false;
  Eigen::Vector2d prev = us.p;
  for (double t = 0.1; t < 300.0; t += 0.1) {
    const Contact c = vessel(start, 270.0, 1.5, t);
    us.step(t, 0.1, {c});
    if (us.out.colregs.steer) {
      turned = true;
      ported = ported || angleDiff(us.out.reference.heading, 0.0) < deg2rad(30.0);  // less than offset: a port turn
      EXPECT_EQ(us.out.colregs.encounter, Encounter::kCrossingGiveWay);
      EXPECT_EQ(us.out.colregs.action, EncounterAction::kStarboard);
    }
    min_hull = std::min(min_hull, hullDistance(us.p, c.position));
    if (prev.x() < 100.0 && us.p.x() >= 100.0) crossed_at = t, their_east = c.position.y(), our_east = us.p.y();
    prev = us.p;
  }
  EXPECT_TRUE(turned);
  EXPECT_FALSE(ported);
  EXPECT_GE(min_hull, kP.safe_distance - 0.5);  // the hull-to-hull closest approach kept (the turn takes time)
  ASSERT_GT(crossed_at, 0.0);
  EXPECT_GT(our_east, their_east + 8.0) << "crossed its track at E " << our_east << ", it at E " << their_east;
  // then back on the leg, the encounter over
  EXPECT_EQ(us.out.colregs.encounter, Encounter::kNone);
  EXPECT_FALSE(us.out.colregs.steer);
  EXPECT_LT(std::abs(us.out.los.cross_track_error), 2.0);
  EXPECT_EQ(us.g.colregsCounters().get("give_way"), 1u);
}

TEST(ColregsManoeuvre, StandOnKeepsCourseAndSpeedUntilTheTriggerThenTurnsToStarboard) {
  // A vessel from port that does not give way: from 100 m west on N 100 heading east.
  Boat us({0, 0}, 0.0, {300, 0});
  const Eigen::Vector2d start(100, -100);
  double acted_at = -1, tcpa_at_act = 0, min_hull = 1e9;
  for (double t = 0.1; t < 200.0; t += 0.1) {
    const Contact c = vessel(start, 90.0, 1.5, t);
    us.step(t, 0.1, {c});
    const ColregsOutput& o = us.out.colregs;
    min_hull = std::min(min_hull, hullDistance(us.p, c.position));
    if (acted_at < 0 && o.encounter != Encounter::kNone) {
      EXPECT_EQ(o.encounter, Encounter::kCrossingStandOn);
      if (o.action == EncounterAction::kStandOn) {
        // course and speed kept: the path's heading and surge, unaltered
        EXPECT_FALSE(o.steer);
        EXPECT_NEAR(us.out.reference.heading, 0.0, 1e-3);
        EXPECT_NEAR(us.out.reference.surge, 1.5, 1e-9);
        EXPECT_NEAR(us.p.y(), 0.0, 1e-3);
        EXPECT_GT(o.tcpa, kP.stand_on_tcpa - 0.2);
      } else {
        acted_at = t;
        tcpa_at_act = o.tcpa;
      }
    }
    if (acted_at > 0 && o.steer) {
      EXPECT_GT(angleDiff(us.out.reference.heading, 0.0), 0.0) << "never to port";
    }
  }
  ASSERT_GT(acted_at, 0.0) << "never acted";
  EXPECT_NEAR(tcpa_at_act, kP.stand_on_tcpa, 0.3);  // at the trigger, not before
  EXPECT_GT(acted_at, 30.0);
  EXPECT_GT(min_hull, 0.0);  // no contact
  EXPECT_EQ(us.g.colregsCounters().get("stand_on_acted"), 1u);
}

TEST(ColregsManoeuvre, HeadOnBothTurnToStarboardAndPassPortToPort) {
  Boat a({0, 0}, 0.0, {400, 0});
  Boat b({200, 1.0}, kPi, {-200, 1.0});
  double min_hull = 1e9;
  bool a_turned = false, b_turned = false;
  double a_east_at_pass = 0, b_east_at_pass = 0;
  bool passed = false;
  for (double t = 0.1; t < 250.0; t += 0.1) {
    const Contact ca = a.asContact(1), cb = b.asContact(2);
    a.step(t, 0.1, {cb});
    b.step(t, 0.1, {ca});
    if (a.out.colregs.steer) {
      a_turned = true;
      EXPECT_EQ(a.out.colregs.encounter, Encounter::kHeadOn);
      EXPECT_GT(angleDiff(a.out.reference.heading, 0.0), 0.0);  // north-bound: starboard is east
    }
    if (b.out.colregs.steer) {
      b_turned = true;
      EXPECT_EQ(b.out.colregs.encounter, Encounter::kHeadOn);
      EXPECT_GT(angleDiff(b.out.reference.heading, kPi), 0.0);  // south-bound: starboard is west
    }
    min_hull = std::min(min_hull, hullDistance(a.p, b.p));
    if (!passed && a.p.x() >= b.p.x()) passed = true, a_east_at_pass = a.p.y(), b_east_at_pass = b.p.y();
  }
  EXPECT_TRUE(a_turned);
  EXPECT_TRUE(b_turned);
  ASSERT_TRUE(passed);
  EXPECT_GT(a_east_at_pass, b_east_at_pass);  // each has the other to port
  EXPECT_GE(min_hull, kP.safe_distance);
  EXPECT_LT(std::abs(a.out.los.cross_track_error), 2.0);
  EXPECT_LT(std::abs(b.out.los.cross_track_error), 2.0);
}
