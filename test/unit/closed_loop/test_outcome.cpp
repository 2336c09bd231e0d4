// A mission's outcome as a skipper means it: each class, and which wins when several apply.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/closed_loop/outcome.h"

using namespace offshore_gnc::closed_loop;

namespace {
OutcomeFacts held(double target_error = 0.3) {
  OutcomeFacts f;
  f.held = true;
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

TEST(Outcome, WhereNoTargetIsExpected) {
  OutcomeFacts f;
  f.expect_target = false;
  f.auv_no_target = true;
  EXPECT_EQ(classify(f), Outcome::kSuccess);
  f.target_reported = true;  // a false alarm sent the USV somewhere
  f.target_error_m = std::nan("");
  EXPECT_EQ(classify(f), Outcome::kWrongTarget);
  EXPECT_STREQ(toString(Outcome::kWrongTarget), "wrong_target");
  EXPECT_STREQ(toString(Outcome::kStackDied), "stack_died");
}
