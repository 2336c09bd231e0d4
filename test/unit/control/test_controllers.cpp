#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/control/vehicle_control.h"
#include "offshore_gnc/models/auv.h"

using namespace offshore_gnc;
using namespace offshore_gnc::control;

namespace {
const double kNan = std::numeric_limits<double>::quiet_NaN();
MotionReference follow(double heading, double surge = 1.0, double depth = 2.0) {
  MotionReference r;
  r.mode = ReferenceMode::kFollow;
  r.heading = heading;
  r.surge = surge;
  r.depth = depth;
  return r;
}
}  // namespace

TEST(Allocation, SetpointsThroughTheModelsInverseCurveGiveTheAllocatedThrust) {
  const Girona500ControlParams p;
  ThrustAllocator a(p.tcm, p.max_thrust, p.command_for, p.max_reverse_thrust);
  models::AuvModel m(models::AuvParams::girona500());
  const auto r = a.allocate(Eigen::Vector4d(-20.0, 8.0, 15.0, 2.0));
  ASSERT_FALSE(r.saturated);
  for (int i = 0; i < r.thrust.size(); ++i) EXPECT_NEAR(m.thrust(i, r.setpoint[i]), r.thrust[i], 1e-6) << i;
  EXPECT_TRUE(a.allocate(Eigen::Vector4d(kNan, 0, 0, 0)).setpoint.allFinite());
}

TEST(Girona500, AllocationOnTheModelsTcmReproducesTheWrench) {
  Girona500Controller ctrl;
  VehicleState s;
  s.position = Eigen::Vector3d(0, 0, 2);
  MotionReference r;
  r.mode = ReferenceMode::kHold;
  r.point = Eigen::Vector3d(0.05, -0.03, 0);
  r.depth = 2.02;
  r.heading = 0.01;
  const auto o = ctrl.update(s, r);
  ASSERT_FALSE(o.alloc.saturated);
  EXPECT_NEAR((ctrl.allocator().tcm() * o.alloc.thrust - o.tau).norm(), 0.0, 1e-9);
  EXPECT_GT(o.tau[0], 0.0);  // north error, yaw 0 -> surge force forward
  EXPECT_LT(o.tau[1], 0.0);  // west error -> sway to port
  EXPECT_GT(o.tau[2], 0.0);  // deeper -> down
  EXPECT_GT(o.tau[3], 0.0);  // heading to starboard
}

TEST(Controllers, BadInputGivesNeutralNeverNaN) {
  UsvController usv;
  AcolorController ac;
  Girona500Controller g5;
  VehicleState bad;
  bad.position.x() = kNan;
  const auto j = usv.update(bad, follow(0.3));
  EXPECT_EQ(j.surge, 0.0);
  EXPECT_EQ(j.yaw, 0.0);
  EXPECT_EQ(usv.counters().get("nan_state"), 1u);
  for (auto ch : ac.update(bad, follow(0.3))) EXPECT_EQ(ch, 1500);
  const auto o = g5.update(bad, follow(0.3));
  EXPECT_TRUE(o.alloc.setpoint.allFinite());
  EXPECT_EQ(o.alloc.setpoint.norm(), 0.0);
  VehicleState ok;
  const auto j2 = usv.update(ok, follow(kNan));
  EXPECT_EQ(j2.yaw, 0.0);
  EXPECT_EQ(usv.counters().get("bad_reference"), 1u);
}

TEST(Controllers, UsvTurnsTowardTheReferenceAcrossPlusMinusPi) {
  UsvController usv;
  VehicleState s;
  s.yaw = 3.1;  // just short of +pi
  s.velocity.x() = 1.0;
  const auto j = usv.update(s, follow(-3.1, 1.0));  // 0.083 rad further to starboard through pi
  EXPECT_GT(j.yaw, 0.0);
  EXPECT_LE(std::abs(j.yaw), 1.0);
  EXPECT_LE(std::abs(j.surge), 1.0);
}

TEST(Controllers, UsvTurnsHeldOnStationOnlyWhereGuidanceFindsRoom) {
  // At rest with the path astern: held while it turns where guidance finds room for the hull's sweep, unheld where
  // it does not (a surfaced AUV beside the boat: the swinging hull touched it).
  UsvControlParams p;
  p.turn_hold_angle = 1.0;
  for (const bool room : {false, true}) {
    UsvController usv(p);
    VehicleState s;
    s.yaw = 0.0;
    MotionReference r = follow(kPi, 1.0);
    r.point = Eigen::Vector3d(-1.0, 0.0, 0.0);
    r.room_to_turn = room;
    for (int i = 0; i < 10; ++i) usv.update(s, r);
    EXPECT_EQ(usv.counters().get("turns_held"), room ? 1u : 0u) << (room ? "room" : "no room");
  }
}

TEST(Controllers, AcolorPwmChannels) {
  AcolorController ac;
  VehicleState s;
  s.position.z() = 1.0;
  const auto ch = ac.update(s, follow(-0.5, 0.5, 2.0));
  ASSERT_EQ(ch.size(), 8u);
  EXPECT_EQ(ch[4], AcolorController::pwm(AcolorControlParams().surge_command_for(0.5)));  // surge on channel 5
  EXPECT_LT(ch[3], 1500);  // yaw to port on channel 4
  EXPECT_EQ(ch[2], 1800);  // heave P: 300 us/m x 1 m too shallow -> down
  for (auto c : ch) {
    EXPECT_GE(c, 1100);
    EXPECT_LE(c, 1900);
  }
  EXPECT_EQ(AcolorController::pwm(5.0), 1900);
  EXPECT_EQ(AcolorController::pwm(kNan), 1500);
}

TEST(Acolor, TheSurgeCommandHoldsGuidancesSpeedOnTheModel) {
  // Each horizontal thruster at the command times its share of the surge row (the flight controller's mixer),
  // 60 s from rest in still water: the model settles at the speed the command was computed for.
  const models::AuvParams ap = models::AuvParams::aColor();
  const AcolorControlParams p;
  for (double speed : {0.3, 0.7, 1.2}) {
    models::AuvModel m(ap);
    const double c = p.surge_command_for(speed);
    ASSERT_GT(c, 0.1) << speed;  // beyond the dead band
    ASSERT_LT(c, 1.0) << speed;
    VehicleState s;
    s.position.z() = 3.0;
    m.reset(s);
    const Eigen::RowVectorXd row = m.tcm().row(0);
    ASSERT_TRUE(m.setCommand(c * row.transpose() / row.cwiseAbs().maxCoeff()));
    const models::Environment still;
    for (int i = 0; i < 6000; ++i) m.step(0.01, still);
    EXPECT_NEAR(m.state().velocity.x(), speed, 0.01 * speed) << speed;
  }
  EXPECT_EQ(p.surge_command_for(0.0), 0.0);
  EXPECT_EQ(p.surge_command_for(kNan), 0.0);
  EXPECT_EQ(p.surge_command_for(10.0), 1.0);  // beyond full thrust
}

namespace {
MotionReference holdAt(double n, double e, double heading, double depth = 2.0) {
  MotionReference r;
  r.mode = ReferenceMode::kHold;
  r.point = Eigen::Vector3d(n, e, depth);
  r.heading = r.path_angle = heading;
  r.depth = depth;
  return r;
}
}  // namespace

TEST(Acolor, HoldsAPointWithItsVectoredThrustersOnlyWithGains) {
  VehicleState s;
  s.position = Eigen::Vector3d(0, 0, 2);
  s.yaw = kPi / 2;  // facing east: north is to port
  AcolorController none;  // the thesis' aColor: no dynamic positioning, it stops and holds its depth
  auto ch = none.update(s, holdAt(3, 0, kPi / 2));
  EXPECT_EQ(ch[4], 1500);
  EXPECT_EQ(ch[5], 1500);
  AcolorControlParams p;
  p.hold = {0.15, 0.0, 0.3, 0.6, 0.2};  // config/control/acolor_sim.yaml
  AcolorController dp(p);
  ch = dp.update(s, holdAt(3, 0, kPi / 2));  // 3 m north of it
  EXPECT_EQ(ch[5], AcolorController::pwm(-0.45));  // sway to port (channel 6), 0.15 x 3
  EXPECT_EQ(ch[4], 1500);                          // nothing ahead or astern
  s.velocity = Eigen::Vector3d(0, -0.5, 0);        // already moving north (to port) at 0.5 m/s: damped
  EXPECT_EQ(dp.update(s, holdAt(3, 0, kPi / 2))[5], AcolorController::pwm(-0.45 + 0.15));
  s.velocity.setZero();
  EXPECT_EQ(dp.update(s, holdAt(-30, 0, kPi / 2))[5], AcolorController::pwm(0.6));  // bounded
  EXPECT_EQ(dp.update(s, follow(kPi / 2, 0.5))[5], 1500);  // following: no sway
}

TEST(Acolor, ItsWaterVelocityIsWhatTheModelDoesWithTheChannelsItSends) {
  // The navigation's speed without a DVL: a hold toward a point ahead and to starboard (surge and sway at once,
  // through the mixer) and then a leg at 0.7 m/s, the channels driving the model in still water; the controller's
  // prediction follows the model's velocity through every transient.
  AcolorControlParams p;
  p.hold = {0.1, 0.0, 0.2, 0.4, 0.3};
  AcolorController ctrl(p);
  models::AuvModel m(models::AuvParams::aColor());
  VehicleState s0;
  s0.position = Eigen::Vector3d(0, 0, 2);
  m.reset(s0);
  const models::Environment still;
  double worst = 0.0, moved = 0.0;
  for (int k = 0; k < 600; ++k) {  // 60 s at 10 Hz
    const VehicleState& s = m.state();
    const auto ch = ctrl.update(s, k < 300 ? holdAt(6, 4, 0.0) : follow(0.0, 0.7));
    auto n = [&](int c) { return (ch[c - 1] - 1500.0) / 400.0; };
    ASSERT_TRUE(m.setCommand(models::mixAxes(m.tcm(), Eigen::Vector4d(n(5), n(6), 0.0, n(4)))));
    for (int i = 0; i < 10; ++i) m.step(0.01, still);
    const Eigen::Vector2d v = m.state().velocity.head<2>();
    worst = std::max(worst, (ctrl.waterVelocity() - v).norm());
    moved = std::max(moved, std::abs(v.y()));
  }
  EXPECT_GT(moved, 0.1);  // it did sway
  EXPECT_NEAR(ctrl.waterVelocity().x(), 0.7, 0.02);
  EXPECT_LT(worst, 0.03);
}

TEST(Girona500, ItsWaterVelocityIsWhatTheModelDoesWithTheAllocatedThrust) {
  // The same for the Girona500, whose navigation falls back on it when the DVL is silent.
  Girona500Controller ctrl;
  models::AuvModel m(models::AuvParams::girona500());
  VehicleState s0;
  s0.position = Eigen::Vector3d(0, 0, 2);
  m.reset(s0);
  const models::Environment still;
  double worst = 0.0;
  for (int k = 0; k < 600; ++k) {
    const VehicleState& s = m.state();
    MotionReference r = k < 300 ? holdAt(5, 3, 0.0) : follow(0.0, 0.5);
    r.path_angle = 0.0;
    r.point = k < 300 ? r.point : Eigen::Vector3d(s.position.x(), 0.0, 2.0);
    const Girona500Out out = ctrl.update(s, r);
    ASSERT_TRUE(m.setCommand(out.alloc.setpoint));
    for (int i = 0; i < 10; ++i) m.step(0.01, still);
    worst = std::max(worst, (ctrl.waterVelocity() - m.state().velocity.head<2>()).norm());
  }
  EXPECT_GT(ctrl.waterVelocity().x(), 0.2);
  EXPECT_LT(worst, 0.05);
}

TEST(Acolor, AHoldDriftsWhileTheNavigationHasNoFixAndResumesFromRest) {
  // Without a speed sensor its estimate stands still between fixes: pushing on it would wind the integral up
  // against an error that never changes (evaluation run 4: 26 m in 54 s into the USV's way).
  VehicleState s;
  s.position = Eigen::Vector3d(0, 0, 2);
  s.yaw = kPi / 2;
  AcolorControlParams p;
  p.hold = {0.1, 0.05, 0.0, 0.6, 0.3};
  AcolorController dp(p);
  for (int i = 0; i < 50; ++i) dp.update(s, holdAt(3, 0, kPi / 2));  // 5 s of integral on a 3 m error
  const auto wound = dp.update(s, holdAt(3, 0, kPi / 2))[5];
  EXPECT_LT(wound, AcolorController::pwm(-0.3));  // beyond the proportional part
  dp.setFixLost(true);
  auto ch = dp.update(s, holdAt(3, 0, kPi / 2, 3.0));
  EXPECT_EQ(ch[4], 1500);  // surge and sway neutral: it drifts
  EXPECT_EQ(ch[5], 1500);
  EXPECT_EQ(ch[2], 1800);  // its depth still held: 1 m too shallow -> down
  EXPECT_EQ(dp.counters().get("hold_without_fix"), 1u);
  dp.setFixLost(false);
  // it resumes from rest: the integral built before is dropped
  AcolorController fresh(p);
  const auto resumed = dp.update(s, holdAt(3, 0, kPi / 2))[5];
  EXPECT_EQ(resumed, fresh.update(s, holdAt(3, 0, kPi / 2))[5]);
  EXPECT_GT(resumed, wound);
  dp.setFixLost(true);  // following a path is not a hold: its surge is guidance's, fix or none
  EXPECT_EQ(dp.update(s, follow(kPi / 2, 0.5))[4], AcolorController::pwm(p.surge_command_for(0.5)));
}

TEST(Girona500, HoldingTurnsTheBowIntoALateralDemandItsSwayThrusterCannotMeet) {
  // Beam on to a cross current the 40 N sway thruster gives up (0.3 m/s needs about 46 N): holding, the heading
  // turns from guidance's toward the demand until the thruster's part of it fits (hold_crab); following, it keeps
  // guidance's (max_crab 0, the thesis' heading).
  Girona500ControlParams p;
  Girona500Controller g(p);
  VehicleState s;
  s.position = Eigen::Vector3d(0, -1.0, 2);  // 1 m west of the point, facing north: the demand is east, abeam
  for (int i = 0; i < 300; ++i) g.update(s, holdAt(0, 0, 0.0));
  const Girona500Out held = g.update(s, holdAt(0, 0, 0.0));
  EXPECT_GT(held.tau(3), 1.0);  // a yaw moment toward the east (starboard)
  p.hold_crab = 0.0;
  Girona500Controller fixed(p);
  for (int i = 0; i < 300; ++i) fixed.update(s, holdAt(0, 0, 0.0));
  EXPECT_NEAR(fixed.update(s, holdAt(0, 0, 0.0)).tau(3), 0.0, 1e-6);
  Girona500Controller following;
  MotionReference f = follow(0.0, 0.3, 2.0);
  f.point = Eigen::Vector3d(0, 0, 2);
  for (int i = 0; i < 300; ++i) following.update(s, f);
  EXPECT_NEAR(following.update(s, f).tau(3), 0.0, 1.0);
}

TEST(Girona500, HoldingAbeamOfAStrongCurrentPicksOneSideAndStaysThere) {
  // A 0.45 m/s current from the east, guidance's heading north: the demand lies abeam, where bow-to and stern-to
  // are equally near. Choosing afresh every step, the bow swung from one to the other (its yaw moment saturated,
  // the vehicle never facing either way) and a surfaced Girona500 went 260 m downstream (evaluation seed 1000 run
  // 94). Beam on it cannot hold (about 115 N of drag against its 40 N sway thruster); head or stern on it can (60 N).
  models::EnvironmentParams ep;
  ep.current_east = -0.45;
  const models::Environment env(ep);
  Girona500Controller g;
  models::AuvModel m(models::AuvParams::girona500());
  VehicleState s0;
  s0.position = Eigen::Vector3d(0, 0, 2);
  m.reset(s0);
  double yaw_lo = 1e9, yaw_hi = -1e9, worst = 0.0;
  for (int k = 0; k < 6000; ++k) {  // 600 s at 10 Hz
    ASSERT_TRUE(m.setCommand(g.update(m.state(), holdAt(0, 0, 0.0)).alloc.setpoint));
    for (int i = 0; i < 10; ++i) m.step(0.01, env);
    if (k >= 3000) {
      const double y = std::abs(m.state().yaw);  // bow or stern into the current: +-90 deg
      yaw_lo = std::min(yaw_lo, y);
      yaw_hi = std::max(yaw_hi, y);
      worst = std::max(worst, m.state().position.head<2>().norm());
    }
  }
  EXPECT_LT(yaw_hi - yaw_lo, 0.3);
  EXPECT_LT(worst, 2.0);
}

// Each direction its own limit: T200-like surge propellers push 51.5 N ahead and 40.2 N astern. A demand ahead past
// the 40.2 N a symmetric limit allowed gets the propellers' full ahead thrust, one astern saturates at the
// weaker limit, and either way the saturated group keeps the wrench's direction.
TEST(Allocation, EachDirectionSaturatesAtItsOwnLimit) {
  const Girona500ControlParams p;
  const ThrustAllocator a(p.tcm, p.max_thrust, p.command_for, p.max_reverse_thrust);
  const auto ahead = a.allocate(Eigen::Vector4d(500.0, 0.0, 0.0, 10.0));
  const auto astern = a.allocate(Eigen::Vector4d(-500.0, 0.0, 0.0, 10.0));
  ASSERT_TRUE(ahead.saturated && astern.saturated);
  const Eigen::Vector4d got_ahead = a.tcm() * ahead.thrust, got_astern = a.tcm() * astern.thrust;
  // with the yaw's share (10 N m over the propellers' 0.49 m) the group saturates at 95 N of surge ahead; the
  // symmetric 40.2 N limit gave 74 N
  EXPECT_GT(got_ahead[0], 90.0);
  EXPECT_LT(got_ahead[0], 2 * 51.5 + 1e-6);
  EXPECT_GT(got_astern[0], -2 * 40.2 - 1e-6);
  EXPECT_NEAR(got_ahead[3] / got_ahead[0], 10.0 / 500.0, 1e-9);  // the direction kept
  EXPECT_NEAR(got_astern[3] / got_astern[0], 10.0 / -500.0, 1e-9);
  for (int i = 0; i < ahead.setpoint.size(); ++i) {
    EXPECT_LE(std::abs(ahead.setpoint[i]), 1.0 + 1e-9);
    EXPECT_LE(std::abs(astern.setpoint[i]), 1.0 + 1e-9);
  }
  EXPECT_THROW(ThrustAllocator(p.tcm, p.max_thrust, {}, Eigen::VectorXd::Constant(2, 40.0)), ConfigError);
}

TEST(Girona500, HoldingAgainstAStrongDemandFromAsternTurnsTheBowIntoIt) {
  // 0.6 m/s from dead astern of guidance's heading (north, the current setting north): 91 N of drag (X_u u +
  // X_uu u^2), more than the propellers back with (80 N: 0.56 m/s), less than they push ahead (103 N: 0.64 m/s).
  // Facing it (hold_face) the vehicle holds its point; backing (off) it is carried downstream.
  models::EnvironmentParams ep;
  ep.current_north = 0.6;
  const models::Environment env(ep);
  auto run = [&](bool face) {
    Girona500ControlParams p;
    p.hold_face = face;
    Girona500Controller g(p);
    models::AuvModel m(models::AuvParams::girona500());
    VehicleState s0;
    s0.position = Eigen::Vector3d(0, 0, 2);
    m.reset(s0);
    double worst = 0.0;
    for (int k = 0; k < 6000; ++k) {  // 600 s at 10 Hz
      EXPECT_TRUE(m.setCommand(g.update(m.state(), holdAt(0, 0, 0.0)).alloc.setpoint));
      for (int i = 0; i < 10; ++i) m.step(0.01, env);
      if (k >= 3000) worst = std::max(worst, m.state().position.head<2>().norm());
    }
    return std::make_pair(worst, m.state().yaw);
  };
  const auto faced = run(true), backed = run(false);
  EXPECT_LT(faced.first, 2.0);
  EXPECT_GT(std::abs(faced.second), 2.8);  // bow south, into the current
  EXPECT_GT(backed.first, 10.0);
}

TEST(Girona500, HoldingIntegratesTheStandingErrorAwayWithinItsBound) {
  // Table 4.3's own integral (K_I 0.0106) would take an hour to build against a steady push: a hold stood off in
  // proportion to it (1.6 m against 240 N at the surface). The hold's integral (hold_ki N per metre-second, bounded
  // at hold_i_limit N) adds to the demand while the error stands, and starts from nothing at the next hold.
  Girona500ControlParams p;
  Girona500Controller g(p);
  VehicleState s;
  s.position = Eigen::Vector3d(-1.0, 0, 2);  // 1 m south of the point, facing north: the demand is ahead
  const double first = g.update(s, holdAt(0, 0, 0.0)).tau(0);
  EXPECT_NEAR(first, p.north.kp + p.hold_ki * p.dt, 1.0);
  for (int i = 1; i < 100; ++i) g.update(s, holdAt(0, 0, 0.0));  // 10 s
  EXPECT_NEAR(g.update(s, holdAt(0, 0, 0.0)).tau(0), p.north.kp + p.hold_ki * 10.1, 2.0);
  for (int i = 0; i < 300; ++i) g.update(s, holdAt(0, 0, 0.0));  // 40 s: the bound
  EXPECT_NEAR(g.update(s, holdAt(0, 0, 0.0)).tau(0), p.north.kp + p.hold_i_limit, 2.0);
  MotionReference f = follow(0.0, 0.0, 2.0);  // following: no hold integral, and the next hold starts afresh
  f.point = Eigen::Vector3d(0, 0, 2);
  EXPECT_NEAR(g.update(s, f).tau(0), p.north.kp * (1.0 + p.lead), 2.0);  // the reference `lead` ahead
  EXPECT_NEAR(g.update(s, holdAt(0, 0, 0.0)).tau(0), first, 2.0);
  p.hold_ki = 0.0;  // off: Table 4.3 alone
  Girona500Controller plain(p);
  for (int i = 0; i < 400; ++i) plain.update(s, holdAt(0, 0, 0.0));
  EXPECT_NEAR(plain.update(s, holdAt(0, 0, 0.0)).tau(0), p.north.kp, 1.0);
}
