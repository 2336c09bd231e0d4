// A mission's outcome as a skipper means it: each class, and which wins when several apply.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/closed_loop/outcome.h"

using namespace offshore_gnc::closed_loop;

namespace {
OutcomeFacts held(double target_error = 0.3) {
  OutcomeFacts f;
  f.held = true;
  f.recovered = true;
  f.target_reported = true;
  f.target_error_m = target_error;
  f.min_clearance_m = 4.0;
  f.final_distance_m = 3.2;
  return f;
}
}  // namespace

TEST(Outcome, SuccessNeedsTheHoldNoContactAndTheRightTarget) {
  EXPECT_EQ(classify(held()), Outcome::kSuccess);
  OutcomeFacts f = held();
  f.min_clearance_m = 0.0;  // touching is contact
  EXPECT_EQ(classify(f), Outcome::kCollision);
  f = held();
  f.auv_clearance_m = -0.2;  // the hull over the surfaced AUV, recovered or not
  EXPECT_EQ(classify(f), Outcome::kCollision);
  EXPECT_EQ(classify(held(2.5)), Outcome::kWrongTarget);  // held, but 2.5 m from the true target (tolerance 2 m)
  f = held();
  f.target_error_m = std::nan("");  // reported where no true target lies
  EXPECT_EQ(classify(f), Outcome::kWrongTarget);
  f = held();
  f.safety_stop = true;  // a supervisor acted on the way but the mission still ended on station: success
  EXPECT_EQ(classify(f), Outcome::kSuccess);
  f.final_distance_m = 19.8;  // "on station", but where a safety hold left it, 20 m from the target
  EXPECT_EQ(classify(f), Outcome::kOffStation);
  f.final_distance_m = std::nan("");  // nothing known of where it ended: not a success
  EXPECT_EQ(classify(f), Outcome::kOffStation);
}

TEST(Outcome, FailuresByCause) {
  OutcomeFacts f;  // no target, never held
  f.auv_no_target = true;
  EXPECT_EQ(classify(f), Outcome::kMissedTarget);
  f.auv_no_target = false;
  EXPECT_EQ(classify(f), Outcome::kTimeout);
  f.safety_stop = true;
  EXPECT_EQ(classify(f), Outcome::kSafetyAbort);
  f.min_clearance_m = -0.4;
  EXPECT_EQ(classify(f), Outcome::kCollision);
  f.stack_died = true;  // a dead stack explains the rest
  EXPECT_EQ(classify(f), Outcome::kStackDied);
}

TEST(Outcome, AnAuvLeftInTheWaterIsItsOwnOutcome) {
  // the USV held at the target, the AUV came up, nobody recovered it (a lost link, an AUV that cannot hold)
  OutcomeFacts f = held();
  f.recovered = false;
  EXPECT_EQ(classify(f), Outcome::kAuvAdrift);
  EXPECT_STREQ(toString(Outcome::kAuvAdrift), "auv_adrift");
  f.held = false;  // nor did the USV get there
  EXPECT_EQ(classify(f), Outcome::kAuvAdrift);
  f.safety_stop = true;
  EXPECT_EQ(classify(f), Outcome::kAuvAdrift);  // the vehicle in the water is what matters
  f.stack_died = true;
  EXPECT_EQ(classify(f), Outcome::kStackDied);
  OutcomeFacts searching;  // the search not over: nothing is adrift yet
  EXPECT_EQ(classify(searching), Outcome::kTimeout);
  OutcomeFacts none;  // no target expected, the AUV came up and was not recovered
  none.expect_target = false;
  none.auv_no_target = true;
  EXPECT_EQ(classify(none), Outcome::kAuvAdrift);
}

TEST(Outcome, TheHullsClearanceToTheAuvIsToItsOutline) {
  const offshore_gnc::sim::HullFootprint hull;  // bow 5.3 m ahead of the reference point
  // bow on, 8 m ahead: 8 - 5.3 to the AUV's centre, less half its length
  EXPECT_NEAR(auvClearance(hull, {0, 0}, 0.0, {8, 0}, 1.5), 8 - 5.3 - 0.75, 1e-9);
  EXPECT_NEAR(auvClearance(hull, {0, 0}, 0.0, {0, 4}, 1.0), 4 - 1.3 - 0.5, 1e-9);  // abeam
  EXPECT_LT(auvClearance(hull, {0, 0}, 0.0, {1, 0}, 1.0), 0.0);  // under the hull
}

TEST(Outcome, WhereNoTargetIsExpected) {
  OutcomeFacts f;
  f.expect_target = false;
  f.auv_no_target = true;
  f.recovered = true;
  EXPECT_EQ(classify(f), Outcome::kSuccess);
  f.target_reported = true;  // a false alarm sent the USV somewhere
  f.target_error_m = std::nan("");
  EXPECT_EQ(classify(f), Outcome::kWrongTarget);
  EXPECT_STREQ(toString(Outcome::kWrongTarget), "wrong_target");
  EXPECT_STREQ(toString(Outcome::kStackDied), "stack_died");
}
