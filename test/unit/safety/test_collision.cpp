// Time to collision of the supervisor's collision rule: head on, passing clear, oblique faces, the ends of a
// face, inside, unknown axes, several obstacles, bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/safety/collision.h"

using namespace offshore_gnc;
using namespace offshore_gnc::safety;

namespace {

// A face across north (its axis east), `ahead` north of the origin, `length` long, `width` thick.
SeenObstacle faceAcross(double ahead, double length, double width = 0.0, double east = 0.0) {
  SeenObstacle o;
  o.origin = {ahead, east};
  o.axis = {0.0, 1.0};
  o.length = length;
  o.width = width;
  return o;
}

const Eigen::Vector2d kHere(0.0, 0.0);

}  // namespace

TEST(TimeToCollision, HeadOnItIsTheDistanceToReachOverTheSpeed) {
  // 20 m to the face, 4 m of the vehicle's radius, 1 m of the face's half width: 15 m at 1.5 m/s
  const Collision c = timeToCollision(kHere, {1.5, 0.0}, {faceAcross(20.0, 100.0, 2.0)}, 4.0);
  EXPECT_EQ(c.obstacle, 0);
  EXPECT_NEAR(c.distance, 15.0, 1e-9);
  EXPECT_NEAR(c.ttc, 10.0, 1e-9);
  // twice the speed, half the time
  EXPECT_NEAR(timeToCollision(kHere, {3.0, 0.0}, {faceAcross(20.0, 100.0, 2.0)}, 4.0).ttc, 5.0, 1e-9);
}

TEST(TimeToCollision, StillMovingAwayOrPassingClearIsNoCollisionCourse) {
  const std::vector<SeenObstacle> face{faceAcross(20.0, 10.0)};  // from east -5 to 5
  EXPECT_TRUE(std::isinf(timeToCollision(kHere, {0.0, 0.0}, face, 4.0).ttc));    // still
  EXPECT_TRUE(std::isinf(timeToCollision(kHere, {-1.5, 0.0}, face, 4.0).ttc));   // away
  EXPECT_TRUE(std::isinf(timeToCollision(kHere, {0.0, 1.5}, face, 4.0).ttc));    // along it, 20 m off
  // parallel courses past its end: 9.1 m east clears the 5 m half length plus the 4 m radius, 8.9 m does not
  EXPECT_TRUE(std::isinf(timeToCollision({0.0, 9.1}, {1.0, 0.0}, face, 4.0).ttc));
  const Collision grazing = timeToCollision({0.0, 8.9}, {1.0, 0.0}, face, 4.0);
  ASSERT_TRUE(std::isfinite(grazing.ttc));  // touches the end's disc, just short of 20 m
  EXPECT_NEAR(grazing.distance, 20.0 - std::sqrt(16.0 - 3.9 * 3.9), 1e-9);
}

TEST(TimeToCollision, AnObliqueFaceIsReachedWhereTheCourseMeetsIt) {
  SeenObstacle o;  // a face through (20, 0) at 45 degrees to the course
  o.origin = {20.0, 0.0};
  o.axis = Eigen::Vector2d(1.0, 1.0).normalized();
  o.length = 40.0;
  const Collision c = timeToCollision(kHere, {2.0, 0.0}, {o}, 1.0);
  // the vehicle's disc touches the line when its centre is 1 m from it: sqrt(2) m before the crossing
  EXPECT_NEAR(c.distance, 20.0 - std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(c.ttc, c.distance / 2.0, 1e-12);
}

TEST(TimeToCollision, WithinReachItIsNowWhileClosingAndNothingWhileOpening) {
  const std::vector<SeenObstacle> face{faceAcross(3.0, 20.0)};
  EXPECT_EQ(timeToCollision(kHere, {0.5, 0.0}, face, 4.0).ttc, 0.0);
  EXPECT_TRUE(std::isinf(timeToCollision(kHere, {-0.5, 0.0}, face, 4.0).ttc));
}

TEST(TimeToCollision, WithoutAnAxisTheObstacleIsADiscOfItsLargerExtent) {
  SeenObstacle buoy;
  buoy.origin = {10.0, 0.0};
  buoy.length = 1.0, buoy.width = 3.0;  // no axis: radius 1.5
  const Collision c = timeToCollision(kHere, {1.0, 0.0}, {buoy}, 2.0);
  EXPECT_NEAR(c.distance, 10.0 - 3.5, 1e-9);
  EXPECT_TRUE(std::isinf(timeToCollision({0.0, 3.6}, {1.0, 0.0}, {buoy}, 2.0).ttc));  // passes 3.6 m off
}

TEST(TimeToCollision, TheFirstObstacleOnTheCourseCounts) {
  const Collision c = timeToCollision(kHere, {1.0, 0.0},
                                      {faceAcross(30.0, 10.0), faceAcross(12.0, 10.0, 0.0, 20.0),  // off the course
                                       faceAcross(18.0, 10.0)},
                                      2.0);
  EXPECT_EQ(c.obstacle, 2);
  EXPECT_NEAR(c.ttc, 16.0, 1e-9);
  EXPECT_TRUE(std::isinf(timeToCollision(kHere, {1.0, 0.0}, {}, 2.0).ttc));  // nothing seen
}

TEST(TimeToCollision, BadInputIsNaNOrSkippedNeverACrash) {
  const std::vector<SeenObstacle> face{faceAcross(20.0, 10.0)};
  EXPECT_TRUE(std::isnan(timeToCollision({NAN, 0.0}, {1.0, 0.0}, face, 2.0).ttc));
  EXPECT_TRUE(std::isnan(timeToCollision(kHere, {1.0, INFINITY}, face, 2.0).ttc));
  SeenObstacle bad = faceAcross(5.0, 10.0);
  bad.length = NAN;
  SeenObstacle negative = faceAcross(6.0, 10.0);
  negative.width = -1.0;
  const Collision c = timeToCollision(kHere, {1.0, 0.0}, {bad, negative, face[0]}, 2.0);
  EXPECT_EQ(c.skipped, 2u);
  EXPECT_EQ(c.obstacle, 2);  // the good one still counts
  EXPECT_NEAR(c.ttc, 18.0, 1e-9);
}

TEST(SafeSide, NoneWhenABoxOnThePathIsBlockedOrTheVehicleIsAlreadyInsideOne) {
  SafetyBoxView box;  // 20 x 10 m about (30, 0), cutting the path
  box.corners = {Eigen::Vector2d(20, -5), Eigen::Vector2d(40, -5), Eigen::Vector2d(40, 5), Eigen::Vector2d(20, 5)};
  box.cuts_path = true;
  EXPECT_TRUE(safeSideExists({}, kHere));
  EXPECT_TRUE(safeSideExists({box}, kHere));                           // outside: the detour goes round it
  EXPECT_FALSE(safeSideExists({box}, Eigen::Vector2d(25.0, 1.0)));      // inside: no room left
  SafetyBoxView reversed = box;  // the other winding
  std::swap(reversed.corners[1], reversed.corners[3]);
  EXPECT_FALSE(safeSideExists({reversed}, Eigen::Vector2d(25.0, 1.0)));
  SafetyBoxView aside = box;  // off the path: the planner ignores it, so does the check
  aside.cuts_path = false;
  EXPECT_TRUE(safeSideExists({aside}, Eigen::Vector2d(25.0, 1.0)));
  SafetyBoxView blocked = box;
  blocked.blocked = true;
  EXPECT_FALSE(safeSideExists({aside, blocked}, kHere));
}
