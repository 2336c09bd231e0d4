#pragma once
// Vehicle controllers (thesis 4.2.3, Tables 4.1-4.3): guidance references in, actuator commands out. ROS-free.
// - USV: surge and yaw PIDs on low-pass + notch filtered feedback -> normalised joystick command (the CAN gateway
//   forwards it as the manual 3-axis joystick would); station keeping with position PIDs in the body frame.
// - aColor AUV: yaw PID, heave P, constant surge (from guidance's speed through the model) -> RC channel PWM
//   (1100-1900 us); holding a point, north and east PIDs on the surge and sway channels.
// - Girona500: north, east, down, yaw PIDs -> body wrench -> allocation T^+ tau with saturation.
#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <functional>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/control/allocation.h"
#include "offshore_gnc/control/dynamic_positioning.h"
#include "offshore_gnc/control/filters.h"
#include "offshore_gnc/control/pid.h"
#include "offshore_gnc/models/joystick_allocation.h"
#include "offshore_gnc/models/auv.h"
#include "offshore_gnc/models/reference.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace control {

struct JoystickOut {
  double surge = 0.0, sway = 0.0, yaw = 0.0;  // -1..1
};

struct UsvControlParams {
  PidGains surge{506.598, 83.2, 2.531, 4000.0, 2000.0};  // Table 4.1, output [N]
  PidGains yaw{5.236, 0.071, 15.084, 1.0, 0.3};          // Table 4.1, output: normalised yaw deflection
  double max_surge_force = 4000.0;                       // force at full joystick deflection [N]
  FilterParams filter;                                   // eq. 4.15-4.16
  DpParams dp;                                           // station keeping (dynamic_positioning.h)
  // Path following: the surge reference scaled by cos^2 of the heading error (turn first, then drive: the twin
  // jets turn the boat at rest). The thesis' lumped jets steer only with thrust (propulsion: lumped): set
  // turn_first false and turn_thrust 0.3, the least joystick surge while the bow is more than 30 deg off.
  bool turn_first = true;
  double turn_thrust = 0.0;
  // Turning onto a path from near rest (slower than turn_hold_speed) with the bow more than turn_hold_angle off:
  // dynamic positioning holds the boat where the turn began until the bow is within a quarter of that angle, then
  // it drives. Turning unheld, the field day's wind and current set the boat 2 m off the path's start before it
  // had way on (the transit's largest cross-track). Only where guidance finds room for the hull's sweep
  // (MotionReference::room_to_turn): held beside a surfaced AUV, the swinging hull touched it. 0: off.
  double turn_hold_angle = 0.0;  // [rad]
  double turn_hold_speed = 0.3;  // [m/s]
  double dt = 0.1;                                       // control period [s] (from the control rate)
  static const ParamTable<UsvControlParams>& table();
  void validate() const;
};

class UsvController {
 public:
  explicit UsvController(const UsvControlParams& p = UsvControlParams());
  void setParams(const UsvControlParams& p);  // rebuilds the filters on changed filter settings
  const UsvControlParams& params() const { return p_; }
  JoystickOut update(const VehicleState& s, const MotionReference& r);  // never NaN; bad input -> neutral
  const Counters& counters() const { return counters_; }
  double filteredHeading() const { return yaw_f_; }
  const DpOutput& stationKeeping() const { return dp_out_; }  // the last station-keeping step's figures

 private:
  UsvControlParams p_;
  Pid surge_, yaw_;
  FeedbackFilter f_u_, f_yaw_, f_r_;  // surge speed, heading (unwrapped), yaw rate
  std::unique_ptr<DynamicPositioning> dp_;
  // The jets' allocation (models::UsvParams' thesis values, as the Girona500's controller takes its thrusters
  // from models::AuvParams): station keeping asks forces, the joystick axes are not linear in them.
  models::JoystickAllocation jets_{models::UsvParams()};
  void keepYawAuthority(JoystickOut& out) const;  // station keeping: the heading first when the jets saturate
  DpOutput dp_out_;
  bool holding_ = false;  // the last step was station keeping
  bool turning_ = false;  // holding where a turn onto the path began (turn_hold_angle)
  Eigen::Vector2d turn_point_ = Eigen::Vector2d::Zero();
  double yaw_unwrapped_ = 0.0, yaw_prev_ = 0.0, yaw_f_ = 0.0, u_f_prev_ = 0.0;
  bool primed_ = false;
  Counters counters_;
};

struct AcolorControlParams {
  PidGains yaw{0.580, 0.276, 0.812, 1.0, 0.3};  // Table 4.2, normalised yaw deflection
  PidGains heave{300.0, 0.0, 0.0, 400.0, 0.0};  // Table 4.2 heave P, output in PWM microseconds from neutral
  // Holding a point (after the find, at the surface, a safety hold): a PID per horizontal axis in NED on the
  // position error, its output the normalised surge and sway commands (rotated into the body) of the four vectored
  // thrusters. All zero by default: the thesis' aColor had no dynamic positioning (it stopped and held its depth);
  // config/control/acolor_sim.yaml sets the simulated vehicle's.
  PidGains hold{0.0, 0.0, 0.0, 1.0, 0.3};
  bool drift_without_fix = true;  // while the navigation has no fix, the hold drifts (setFixLost); false: it holds on
  int channel_heave = 3, channel_yaw = 4, channel_surge = 5, channel_sway = 6;  // 1-based RC channels (ArduSub's)
  int num_channels = 8;
  double dt = 0.1;
  // Forward command (normalised, -1..1) for a surge speed through the water [m/s]: constant for guidance's
  // constant speed (the thesis' constant surge PWM; the aColor has no speed sensor to close a loop on), so the
  // speed the navigation assumes from the command is the one the PWM gives. Default: the aColor model's steady
  // state (acolorSurgeCommand).
  std::function<double(double)> surge_command_for;
  // The vehicle whose speed through the water its commands predict (waterVelocity); default the aColor model.
  std::shared_ptr<const models::AuvModel> model;
  AcolorControlParams();
  static const ParamTable<AcolorControlParams>& table();
  void validate() const;
};

// The forward command at which a flight controller's mixer (each thruster driven at the command times its share
// of the surge row of the thruster configuration matrix, as ArduSub's and sim::mixToThrusters do) makes the
// model's surge thrust equal its surge damping at `speed` through the water; 1 when even full thrust is short.
double acolorSurgeCommand(const models::AuvModel& model, double speed);

class AcolorController {
 public:
  explicit AcolorController(const AcolorControlParams& p = AcolorControlParams());
  void setParams(const AcolorControlParams& p);
  const AcolorControlParams& params() const { return p_; }
  std::vector<std::uint16_t> update(const VehicleState& s, const MotionReference& r);  // PWM per channel
  // The navigation has accepted no position fix lately (it dead-reckons). The aColor has no speed sensor and its
  // navigation takes no speed from a hold, so holding a point its estimate then stands still at (the last fix plus
  // the current): the position PIDs would push, their integral winding up, against an error that never changes
  // (evaluation run 4, 2026-12-05: 26 m at full hold thrust in 54 s without fixes, into the USV's way). While lost,
  // a hold drifts (surge and sway neutral, counted hold_without_fix) and resumes from rest at the next fix: an
  // integral built on a frozen estimate is no measure of the push needed (kept instead, it drove the aColor on at
  // its bound while its estimate sat on the point: evaluation run 64). docs/guidance-control.md has the figures.
  void setFixLost(bool lost) { fix_lost_ = lost; }
  // The velocity through the water (body surge, sway) [m/s] that the channels it has sent give: the model's surge
  // and sway equations driven through the mixer by them, integrated at the control rate. The aColor has no DVL;
  // its navigation takes this as its speed whether it follows a leg or holds a point (AuvNavigator::
  // commandedVelocity): guidance's desired surge alone said nothing of a hold's thrust, so the hold's velocity
  // estimate was only what the lagging USBL fixes revealed, and with more than a gentle push it swung on that lag.
  Eigen::Vector2d waterVelocity() const { return water_; }
  const Counters& counters() const { return counters_; }
  static std::uint16_t pwm(double normalised);  // -1..1 -> 1100..1900 us, 1500 neutral

 private:
  std::vector<std::uint16_t> command(const VehicleState& s, const MotionReference& r);
  void predictWater(const std::vector<std::uint16_t>& ch);
  AcolorControlParams p_;
  Eigen::Vector2d water_ = Eigen::Vector2d::Zero();
  bool fix_lost_ = false;
  Pid yaw_, heave_, north_, east_;
  Counters counters_;
};

struct Girona500ControlParams {
  PidGains north{151.366, 0.0106, 1081.310, 300.0, 50.0};  // Table 4.3, output [N]
  PidGains east{151.366, 0.0106, 1081.310, 300.0, 50.0};
  PidGains down{151.366, 0.0106, 1081.310, 300.0, 50.0};
  PidGains yaw{63.425, 0.0037, 271.85, 100.0, 20.0};       // output [N m]
  double lead = 0.12;            // path following: reference this far ahead of the projection on the leg; with
                                 // the reference moving at u_d the P term alone sets the transit thrust [m]
  double cross_ki = 0.05;        // path frame cross-track integral gain (moves the reference across the leg so
                                 // that current leaves no standing error; 0 = off) [1/s]
  double cross_limit = 3.0;      // |cross-track offset| bound (anti-windup) [m]
  // Crab into a cross current while following: the lateral thruster (about 40 N) cannot hold 0.5 m/s of cross
  // current (about 120 N of sway drag), the two surge thrusters can. The heading turns from guidance's toward the
  // low-passed horizontal force demand, as far as needed to leave at most crab_force of it across the bow, at
  // most max_crab. Off by default (the thesis' heading from guidance): in the default mission it cost the sonar's
  // target accuracy (docs/guidance-control.md); 1.2 for currents near 0.5 m/s.
  double max_crab = 0.0;         // [rad]
  // The same while holding a point (the AUV keeping the spot after the find, or at the surface): the heading is
  // guidance's (toward the target) only while the lateral thruster can hold the sideways part of the demand. On
  // by default: beam on to 0.3 m/s the Girona500 needs 46 N of sway (its 40 N thruster let it go), and while it
  // holds its sonar only has to keep the target within its sector, not pass it on a leg.
  double hold_crab = 1.5;        // [rad]
  // Holding a point, an integral of the horizontal position error in NED on top of Table 4.3's north and east PIDs.
  // Their own integral (K_I 0.0106, 50 N) takes over an hour to build against a steady push, so alone they stand
  // off in proportion to it: 1.6 m against a 6.5 m/s wind's sea at the surface (240 N), and the recovery, which
  // waits for an AUV within 1 m of its point, never began. Reset whenever the vehicle does not hold. 15 N/(m s)
  // (the integral's time constant K_P / hold_ki 10 s, beside the PD's 8 s period) from a tuning campaign
  // (docs/campaign.md, 2026-12-05): 0 12 of 24, 5 13, 15 14; auv_adrift 3, 1, 1.
  double hold_ki = 15.0;         // [N/(m s)]
  double hold_i_limit = 200.0;   // bound on the integral's force [N]
  // Holding, a demand astern (relative to guidance's heading) beyond what the thrusters can back with turns the bow
  // into it, past hold_crab: the surge propellers push 103 N ahead against 80 N astern, and a surfaced Girona500
  // backing against 0.48 m/s and a 7.5 m/s wind went 290 m downstream (tuning seed 32 run 28). Back to guidance's
  // heading once the demand is under half that. The demand read is low-passed over hold_face_tf: in a 1 m sea the
  // waves' push, on crab_tf's 5 s, crossed the threshold both ways and spun the surfaced vehicle beside the USV.
  bool hold_face = true;
  double hold_face_tf = 30.0;    // [s]
  double crab_tf = 5.0;          // low-pass time constant of the force demand [s]
  double crab_force = 40.0;      // the lateral thruster's limit: the bow turns once it is not enough [N]
  Eigen::MatrixXd tcm;           // 4 x n (surge, sway, heave, yaw); default: models::AuvParams::girona500().tcm()
  Eigen::VectorXd max_thrust;    // each thruster's largest positive thrust; default: its curve's [N]
  Eigen::VectorXd max_reverse_thrust;  // and its largest negative thrust's size; default: its curve's [N]
  ThrustAllocator::CommandFor command_for;  // default: the models' inverse thruster curves
  std::shared_ptr<const models::AuvModel> model;  // whose speed through the water the thrust predicts; Girona500
  double dt = 0.1;
  Girona500ControlParams();
  static const ParamTable<Girona500ControlParams>& table();
  void validate() const;
};

// The Control nodelet's override of the Girona500's allocation (another thruster layout, config/control/
// girona500.yaml): `tcm` row after row (X, Y, Z, N of `thrusters` values each), `max_thrust` and
// `max_reverse_thrust` [N] (empty: max_thrust's). Defaults: the controller's (the model's layout); with another
// thruster count tcm and max_thrust must be given.
struct ThrusterLayout {
  int thrusters = 0;
  std::vector<double> tcm, max_thrust, max_reverse_thrust;
  static ThrusterLayout of(const Girona500ControlParams& c);
  static const ParamTable<ThrusterLayout>& table();
  void applyTo(Girona500ControlParams& c) const;  // throws ConfigError naming a list that does not fit `thrusters`
};

struct Girona500Out {
  Eigen::Vector4d tau = Eigen::Vector4d::Zero();  // requested body wrench (X, Y, Z, N)
  AllocationResult alloc;
};

class Girona500Controller {
 public:
  explicit Girona500Controller(const Girona500ControlParams& p = Girona500ControlParams());
  void setParams(const Girona500ControlParams& p);
  const Girona500ControlParams& params() const { return p_; }
  Girona500Out update(const VehicleState& s, const MotionReference& r);
  // The velocity through the water its allocated thrust gives (as AcolorController::waterVelocity): the
  // navigation's speed while the DVL is silent (no bottom lock, a fault).
  Eigen::Vector2d waterVelocity() const { return water_; }
  const ThrustAllocator& allocator() const { return alloc_; }
  const Counters& counters() const { return counters_; }

 private:
  Girona500Out command(const VehicleState& s, const MotionReference& r);
  Girona500ControlParams p_;
  Eigen::Vector2d water_ = Eigen::Vector2d::Zero();
  Pid n_, e_, d_, yaw_;
  double cross_offset_ = 0.0;
  Eigen::Vector2d hold_i_ = Eigen::Vector2d::Zero();  // the hold's integral of the NED error [m s]
  Eigen::Vector2d force_lp_ = Eigen::Vector2d::Zero();  // low-passed NED force demand (crab)
  double crab_ = 0.0;  // heading offset from guidance's heading [rad]
  double backing_ = 0.0;  // the largest force astern the allocation gives (hold_face) [N]
  Eigen::Vector2d steady_lp_ = Eigen::Vector2d::Zero();  // the demand low-passed over hold_face_tf (NED) [N]
  bool facing_ = false;   // holding bow on to a demand from astern (hold_face)
  void updateCrab(const MotionReference& r, const Eigen::Vector2d& f_ned, double yaw);
  ThrustAllocator alloc_;
  Counters counters_;
};

}  // namespace control
}  // namespace offshore_gnc
