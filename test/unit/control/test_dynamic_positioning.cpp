// Dynamic positioning of the twin-waterjet USV (control/dynamic_positioning.h) in closed loop on the models' USV
// (jet by jet, config/models/usv.yaml) in a current, the USV controller between them as on the vehicle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/control/dynamic_positioning.h"
#include "offshore_gnc/control/vehicle_control.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/models/usv.h"

using namespace offshore_gnc;
using namespace offshore_gnc::control;

namespace {

struct HoldRun {
  double final_distance = 0.0, max_distance = 0.0, final_yaw = 0.0, max_north = -1e9;
  double max_distance_after_idle = 0.0;
  bool entered_box = false;
};

struct Idle {  // a moment of neutral command (the control loop's stale-input case)
  double from = -1.0, seconds = 0.0;
};

// The boat from `start` holds `point` for `seconds` in a current (north, east); the box (centre, half side) must
// stay clear.
HoldRun hold(const VehicleState& start, const Eigen::Vector2d& point, double north, double east, double seconds,
         const Eigen::Vector2d& box = Eigen::Vector2d::Constant(1e9), double half = 0.0, Idle idle = {}) {
  models::UsvModel boat(models::loadUsvParams("config/models/usv.yaml"));
  models::EnvironmentParams ep;
  ep.current_north = north;
  ep.current_east = east;
  const models::Environment env(ep);
  boat.reset(start);
  UsvControlParams p;
  p.dt = 0.1;
  p.filter.notch_w.clear();  // as config/control/usv.yaml
  UsvController c(p);
  MotionReference r;
  r.mode = ReferenceMode::kHold;
  r.point = Eigen::Vector3d(point.x(), point.y(), 0.0);
  r.heading = start.yaw;
  MotionReference idle_ref;  // idle: neutral
  HoldRun out;
  for (double t = 0.0; t < seconds; t += p.dt) {
    const VehicleState& s = boat.state();
    const bool idling = t >= idle.from && t < idle.from + idle.seconds;
    const JoystickOut j = c.update(s, idling ? idle_ref : r);
    boat.setCommand({j.surge, j.sway, j.yaw});
    boat.step(p.dt, env);
    const Eigen::Vector2d ne = boat.state().position.head<2>();
    out.max_distance = std::max(out.max_distance, (ne - point).norm());
    out.max_north = std::max(out.max_north, ne.x());
    if (idle.from >= 0.0 && t >= idle.from)
      out.max_distance_after_idle = std::max(out.max_distance_after_idle, (ne - point).norm());
    out.entered_box = out.entered_box || ((ne - box).cwiseAbs().maxCoeff() < half);
  }
  out.final_distance = (boat.state().position.head<2>() - point).norm();
  out.final_yaw = boat.state().yaw;
  return out;
}

VehicleState at(double north, double east, double yaw) {
  VehicleState s;
  s.position = Eigen::Vector3d(north, east, 0.0);
  s.yaw = yaw;
  return s;
}

}  // namespace

TEST(DynamicPositioning, RecoversFromATenMetreOffsetWithoutOvershootingIntoABox) {
  // Hold point at the origin, the boat 10 m short of it, a buoy's keep-out square (0.6 m + sbb/hold_clearance
  // 3 m) just beyond it: the offset is closed at most at max_speed and the boat stops short of the box.
  const Eigen::Vector2d box(4.5, 0.0);
  const HoldRun r = hold(at(-10.0, 0.0, 0.0), Eigen::Vector2d::Zero(), 0.0, 0.2, 240.0, box, 3.6);
  EXPECT_FALSE(r.entered_box);
  EXPECT_LT(r.max_north, 0.6);  // overshoot beyond the point, toward the box
  EXPECT_LT(r.final_distance, 1.0);
}

TEST(DynamicPositioning, WeathervanesIntoTheCurrentAndHoldsItsPoint) {
  // Beam on to a 0.2 m/s current setting east: the bow turns west, into it, and the boat stays near its point
  // (the mission's usv_wait_drift_m, goal 3 m, is this figure from rest).
  const HoldRun r = hold(at(0.0, 0.0, 0.0), Eigen::Vector2d::Zero(), 0.0, 0.2, 300.0);
  EXPECT_LT(std::abs(angleDiff(r.final_yaw, -kPi / 2)), deg2rad(25.0)) << r.final_yaw;
  EXPECT_LT(r.max_distance, 3.0);
  EXPECT_LT(r.final_distance, 0.5);
}

TEST(DynamicPositioning, AStrongCurrentIsHeldBowOn) {
  // 0.5 m/s beam on asks more side force than the jets can balance: the boat drifts while it turns bow on
  // (the strong_current scenario's goal: at most 5 m), then holds.
  const HoldRun r = hold(at(0.0, 0.0, 0.0), Eigen::Vector2d::Zero(), 0.1, 0.5, 300.0);
  EXPECT_LT(std::abs(angleDiff(r.final_yaw, std::atan2(-0.5, -0.1))), deg2rad(25.0)) << r.final_yaw;
  EXPECT_LT(r.max_distance, 5.0);
  EXPECT_LT(r.final_distance, 1.0);
}

TEST(DynamicPositioning, AMomentOfNeutralKeepsTheBowIntoTheCurrent) {
  // Bow on to 0.5 m/s after 150 s, then a second of neutral command (stale odometry): station keeping resumes
  // with the bow where it was. Going back to the hold's heading (beam on) carried the boat 8 m in a ROS mission.
  const HoldRun r = hold(at(0.0, 0.0, 0.0), Eigen::Vector2d::Zero(), 0.1, 0.5, 300.0,
                         Eigen::Vector2d::Constant(1e9), 0.0, Idle{150.0, 1.0});
  EXPECT_LT(std::abs(angleDiff(r.final_yaw, std::atan2(-0.5, -0.1))), deg2rad(25.0)) << r.final_yaw;
  EXPECT_LT(r.max_distance_after_idle, 1.5);
}

TEST(DynamicPositioning, ANewHoldStartsFromItsOwnHeading) {
  // Weathervaning at one point, then resumed: at the same point the bow stays where it was turned; at a new point
  // (a safety stop under way) the hold's own heading comes first, so the braking boat is not spun round.
  DynamicPositioning dp(DpParams{}, 0.1);
  const VehicleState s = at(3.0, 0.0, 0.0);  // 3 m past the point, at rest: a steady force astern
  DpOutput o;
  for (int i = 0; i < 300; ++i) o = dp.update(s, Eigen::Vector2d::Zero(), 0.0);
  ASSERT_TRUE(o.weathervaning);
  const double turned = o.heading;
  ASSERT_GT(std::abs(turned), 0.5);
  dp.resume();
  EXPECT_NEAR(dp.update(s, Eigen::Vector2d::Zero(), 0.0).heading, turned, 0.05);
  dp.resume();
  EXPECT_NEAR(dp.update(s, Eigen::Vector2d(7.0, 0.0), 1.0).heading, 1.0, 0.05);
}

TEST(DynamicPositioning, BadParametersAreRefusedNamingThem) {
  DpParams p;
  p.turn_rate = 0.0;
  try {
    DynamicPositioning dp(p, 0.1);
    FAIL() << "accepted turn_rate 0";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("dp/turn_rate"), std::string::npos) << e.what();
  }
}
