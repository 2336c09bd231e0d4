// control::ControlLoop: the reference selection only the nodelet knew before (missing and stale input, a
// reference that is not finite), and each vehicle's command.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/control/control_loop.h"

using namespace offshore_gnc;
using namespace offshore_gnc::control;

namespace {
MotionReference follow(double heading, double surge) {
  MotionReference r;
  r.mode = ReferenceMode::kFollow;
  r.heading = heading;
  r.surge = surge;
  r.depth = 3.0;
  return r;
}
ControlLoopParams vehicle(const std::string& v) {
  ControlLoopParams p;
  p.vehicle = v;
  return p;
}
}  // namespace

TEST(ControlLoop, NeutralUntilReferenceAndStateHaveCome) {
  ControlLoop c(vehicle("usv"));
  EXPECT_FALSE(c.update(0.0).active);
  EXPECT_NE(c.why().find("waiting"), std::string::npos);
  c.onReference(follow(0.5, 1.5), 0.0);
  EXPECT_FALSE(c.update(0.1).active);
  c.onState(VehicleState(), 0.1);
  const ActuatorCommand cmd = c.update(0.2);
  EXPECT_TRUE(cmd.active);
  EXPECT_TRUE(c.why().empty());
  EXPECT_GT(cmd.joystick.surge, 0.0);  // 1.5 m/s asked, at rest
  EXPECT_GT(cmd.joystick.yaw, 0.0);    // to starboard
}

TEST(ControlLoop, StaleInputGivesTheNeutralCommandAndIsCounted) {
  ControlLoop c(vehicle("usv"));
  c.onReference(follow(0.5, 1.5), 0.0);
  c.onState(VehicleState(), 0.0);
  EXPECT_TRUE(c.update(0.5).active);
  const ActuatorCommand late = c.update(1.5);  // input_timeout 1 s
  EXPECT_FALSE(late.active);
  EXPECT_EQ(late.joystick.surge, 0.0);
  EXPECT_EQ(late.joystick.yaw, 0.0);
  EXPECT_EQ(c.counters().get("stale_input"), 1u);
  EXPECT_NE(c.why().find("stale"), std::string::npos);
}

TEST(ControlLoop, ANonFiniteReferenceIsRefused) {
  ControlLoop c(vehicle("girona500"));
  MotionReference r = follow(NAN, 0.3);
  c.onReference(r, 0.0);
  c.onState(VehicleState(), 0.0);
  const ActuatorCommand cmd = c.update(0.1);
  EXPECT_FALSE(cmd.active);
  EXPECT_EQ(c.counters().get("bad_reference"), 1u);
  EXPECT_TRUE(cmd.thrusters.alloc.setpoint.allFinite());
  EXPECT_NEAR(cmd.thrusters.alloc.setpoint.norm(), 0.0, 1e-12);
}

TEST(ControlLoop, EachVehicleGetsItsOwnCommand) {
  ControlLoop g(vehicle("girona500"));
  g.onReference(follow(0.0, 0.3), 0.0);
  g.onState(VehicleState(), 0.0);
  EXPECT_EQ(g.update(0.1).thrusters.alloc.setpoint.size(), 5);
  ControlLoop a(vehicle("acolor"));
  a.onReference(follow(0.0, 0.3), 0.0);
  a.onState(VehicleState(), 0.0);
  const ActuatorCommand rc = a.update(0.1);
  ASSERT_EQ(rc.rc.size(), 8u);
  // constant surge on channel 5 while following: guidance's 0.3 m/s through the aColor model
  EXPECT_EQ(rc.rc[4], AcolorController::pwm(acolorSurgeCommand(models::AuvModel(models::AuvParams::aColor()), 0.3)));
  EXPECT_GT(rc.rc[4], 1540);  // beyond the thrusters' dead band
  EXPECT_GT(rc.rc[2], 1500);  // heave down towards 3 m
  ControlLoopParams p = vehicle("acolor");
  EXPECT_THROW(a.setParams(vehicle("usv")), ConfigError);  // the vehicle cannot change at run time
  p.input_timeout = -1.0;
  EXPECT_THROW(ControlLoop bad(p), ConfigError);
}

TEST(ControlLoop, SafetyNeutralWinsOverGuidanceUntilCleared) {
  ControlLoop c(vehicle("usv"));
  c.onReference(follow(0.5, 1.5), 0.0);
  c.onState(VehicleState(), 0.0);
  EXPECT_TRUE(c.update(0.1).active);
  c.setSafety(SafetyOverride::kNeutral, "gps silent for 1.2 s");
  const ActuatorCommand n = c.update(0.2);
  EXPECT_FALSE(n.active);
  EXPECT_EQ(n.joystick.surge, 0.0);
  EXPECT_EQ(n.joystick.yaw, 0.0);
  EXPECT_EQ(c.why(), "safety neutral: gps silent for 1.2 s");
  c.setSafety(SafetyOverride::kSurface, "link lost");  // a USV cannot surface: neutral too
  EXPECT_FALSE(c.update(0.3).active);
  c.setSafety(SafetyOverride::kNone, "");
  const ActuatorCommand back = c.update(0.4);
  EXPECT_TRUE(back.active);
  EXPECT_TRUE(c.why().empty());
  EXPECT_GT(back.joystick.surge, 0.0);
}

TEST(ControlLoop, SafetySurfaceBringsTheAuvUpWhereItIsAndHoldHoldsItsDepth) {
  ControlLoop c(vehicle("girona500"));
  c.onReference(follow(0.0, 0.3), 0.0);
  VehicleState s;
  s.position = {10.0, -4.0, 5.0};
  c.onState(s, 0.0);
  c.setSafety(SafetyOverride::kSurface, "navigation silent");
  ActuatorCommand up = c.update(0.1);
  EXPECT_TRUE(up.active);
  EXPECT_LT(up.thrusters.tau(2), 0.0);           // heave force up (z down): towards depth 0
  EXPECT_NEAR(up.thrusters.tau(0), 0.0, 1e-9);   // no surge: it holds the point where the override began
  s.position = {12.0, -4.0, 4.0};                // it drifted 2 m north meanwhile
  c.onState(s, 0.2);
  up = c.update(0.3);
  EXPECT_LT(up.thrusters.tau(0), 0.0);           // pushed back south to the hold point
  ControlLoop h(vehicle("girona500"));
  h.onReference(follow(0.0, 0.3), 0.0);
  h.onState(s, 0.0);
  h.setSafety(SafetyOverride::kHold, "sonar silent");  // hold: where it is, at its present depth
  const ActuatorCommand hold = h.update(0.1);
  EXPECT_TRUE(hold.active);
  EXPECT_NEAR(hold.thrusters.tau(2), 0.0, 1e-9);
  EXPECT_NEAR(hold.thrusters.tau(0), 0.0, 1e-9);  // no surge although guidance asks 0.3 m/s
}

// The one reading of the supervisor's decision (the Control nodelet's and the ROS-free stacks').
TEST(ControlLoop, SafetyOverrideOfTheSupervisorsAction) {
  using A = SupervisorAction;
  using O = SafetyOverride;
  EXPECT_EQ(safetyOverrideOf(A::kNone, false), O::kNone);
  EXPECT_EQ(safetyOverrideOf(A::kWarn, false), O::kNone);
  EXPECT_EQ(safetyOverrideOf(A::kHold, false), O::kHold);
  EXPECT_EQ(safetyOverrideOf(A::kNeutral, false), O::kNeutral);
  EXPECT_EQ(safetyOverrideOf(A::kSurface, false), O::kSurface);
  EXPECT_EQ(safetyOverrideOf(A::kAbort, false), O::kSurface);
  EXPECT_EQ(safetyOverrideOf(static_cast<A>(17), false), O::kNone);  // an unknown action asks nothing
  for (A a : {A::kNone, A::kWarn, A::kHold, A::kNeutral, A::kSurface, A::kAbort})
    EXPECT_EQ(safetyOverrideOf(a, true), O::kNone);  // manual control wins
}
