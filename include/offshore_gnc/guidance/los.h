#pragma once
// LOS path following (thesis 4.2.2, eq. 4.9-4.14): path-tangential angle, cross-track error, look-ahead steering
// with integral action (ILOS, anti-windup) and an optional adaptive crab-angle estimate (ALOS, Fossen 2023
// eq. 12.108, its update scaled by the speed), waypoint switching on a circle (USV) or sphere (AUV) of acceptance plus a passed-waypoint rule,
// and station keeping at the end of the path. ROS-free; NED, radians.
#include <Eigen/Core>

#include <string>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/models/reference.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace guidance {

enum class Mode { kIdle = 0, kFollowPath = 1, kStationKeeping = 2, kManual = 3, kHoldFault = 4 };

struct LosParams {
  double kp = 0.1;                 // 1/Delta: look-ahead proportional gain [1/m] (Table 4.1 LOS)
  double ki = 0.001;               // integral gain [1/(m s)] (Table 4.1 LOS)
  double integral_limit = 0.35;    // |Ki * int e| bound: at most ~20 deg of integral steering (anti-windup) [rad]
  bool adaptive_crab = true;       // estimate the crab (sideslip) angle beta (ALOS)
  double crab_gain = 0.0067;       // gamma of the beta estimate update, per m/s of speed (Fossen's ALOS) [1/m^2]
  double crab_limit = 0.6;         // |beta_hat| bound [rad]
  // The estimate learns only while |e| is below crab_band [m] (0: always). Farther off, the cross-track is the
  // approach to the path, not the current's doing: the Girona500 (whose heading does not close its cross-track:
  // it follows a position reference) learnt 34 deg on its 8 m approach and kept its bow 27 deg off every leg.
  double crab_band = 0.0;
  // With a velocity over ground (the USV's GPS-compass: Doppler speed and heading) the crab angle is measured,
  // beta = atan2(v, u), low-passed over crab_tf, instead of estimated: it is known at once on every new leg,
  // where the estimate of the last leg's crossflow was wrong (cross-track up to 2.5 m after each SBB corner).
  // Below crab_min_speed it is not measurable and the last value is kept.
  bool measured_crab = false;
  double crab_tf = 2.0;            // [s]
  double crab_min_speed = 0.3;     // [m/s]
  // Keep the crab estimate as a NED vector b (about the current over the speed through the water), the crab on a
  // leg being b . n with n the leg's starboard normal: what one leg learnt then gives a leg of another direction
  // its own crab (a lawnmower's legs alternate: the path-frame estimate started each leg with the wrong sign).
  bool crab_ned = false;
  double acceptance_radius = 16.0; // R: circle (USV, 2 L_USV) or sphere (AUV) of acceptance [m]
  bool sphere = false;             // 3-D sphere of acceptance (AUV) instead of the 2-D circle
  double surge_speed = 1.5;        // cruise surge reference [m/s]
  double min_leg_length = 0.05;    // consecutive waypoints closer than this are merged [m]
  // The last waypoint is where the vehicle must stop (the stand-off point), not a corner to cut: it is reached
  // within final_radius (0: acceptance_radius, as the other waypoints) or when passed. With R = 2 L_USV = 16 m
  // and waypoints every 10 m, the path otherwise ended up to 16 m short of the target.
  double final_radius = 0.0;       // [m]
  // Safety-box corners (SBB detour waypoints) are 10-20 m apart: switching them on the 16 m circle cut the
  // corners (cross-track up to 10 m on the simulator). They are reached within detour_radius instead
  // (0: acceptance_radius).
  double detour_radius = 0.0;      // [m]
  double approach_distance = 0.0;  // slow down over this distance to go to the last waypoint (0: no slowdown) [m]
  double approach_speed = 0.3;     // surge reference at the last waypoint when slowing down [m/s]

  static const ParamTable<LosParams>& table();  // names, ranges, units, docs
  void validate() const;           // throws ConfigError naming the value
};

struct LosOutput {
  Mode mode = Mode::kIdle;
  std::size_t active_leg = 0;      // index of the waypoint being approached
  std::size_t num_waypoints = 0;
  double cross_track_error = 0.0;  // e (eq. 4.12), positive to starboard [m]
  double along_track_distance = 0.0;
  double distance_to_go = 0.0;
  double path_angle = 0.0;         // chi_p (eq. 4.11)
  double desired_heading = 0.0;    // psi_d (eq. 4.9)
  double desired_depth = 0.0;      // depth of the active leg (constant-depth legs) [m]
  double desired_surge = 0.0;
  double crab_angle = 0.0;         // beta_hat
  double acceptance_radius = 0.0;
  Eigen::Vector3d hold_position = Eigen::Vector3d::Zero();  // station keeping / fault hold point (NED)
  Eigen::Vector3d path_point = Eigen::Vector3d::Zero();     // projection of the vehicle on the active leg
  std::string status_text;
};

class LosGuidance {
 public:
  explicit LosGuidance(const LosParams& p = LosParams());
  void setParams(const LosParams& p);  // keeps progress; validates
  const LosParams& params() const { return p_; }

  // New path (NED waypoints). Duplicates are merged; non-finite waypoints reject the path (hold). When
  // `resume` is set and a vehicle pose is known, the active leg is the one nearest to the vehicle (replanning
  // with SBB waypoints must not send the vehicle back to the start). Returns false when the path is unusable.
  // `detour` (empty or parallel to `waypoints`) marks safety-box corners, switched on detour_radius.
  bool setPath(const std::vector<Eigen::Vector3d>& waypoints, bool resume = false,
               const std::vector<bool>& detour = {});
  const std::vector<Eigen::Vector3d>& path() const { return wp_; }
  void clear();

  // One guidance step at time dt after the previous one. Never returns NaN: bad pose -> kHoldFault.
  LosOutput update(const VehicleState& s, double dt);

  // Whether dynamic positioning's straight run from the vehicle to the last waypoint would pass an obstacle (the
  // pipeline's check, each step): then the last waypoint is reached as a detour corner is (detour_radius, or
  // passed), not on final_radius, and the path's legs lead to it.
  void setFinalRunBlocked(bool blocked) { final_run_blocked_ = blocked; }

  // Hold the integral term (the pipeline's alteration for traffic: the cross-track it makes is no current's).
  void holdIntegral(bool hold) { hold_integral_ = hold; }

  const Counters& counters() const { return counters_; }
  std::size_t activeLeg() const { return leg_; }

 private:
  LosOutput hold(Mode mode, const std::string& why);
  double remaining(const Eigen::Vector3d& pos) const;

  LosParams p_;
  std::vector<Eigen::Vector3d> wp_;
  std::vector<bool> detour_;  // parallel to wp_
  std::size_t leg_ = 1;
  double integral_ = 0.0;
  double beta_hat_ = 0.0;
  Eigen::Vector2d crab_ned_ = Eigen::Vector2d::Zero();  // b of crab_ned
  bool finished_ = false;
  bool final_run_blocked_ = false;
  bool hold_integral_ = false;
  bool have_pose_ = false;
  std::string path_error_;
  Eigen::Vector3d last_pos_ = Eigen::Vector3d::Zero();
  double last_yaw_ = 0.0;
  Counters counters_;
};

// What control is asked to do (models/reference.h): follow the projection on the active leg, hold the end of
// the path (station keeping) or the last good position (hold fault), or nothing.
MotionReference referenceOf(const LosOutput& o);

// Cross-track error (eq. 4.12) and along-track distance of `p` on the leg a->b; returns chi_p (eq. 4.11).
double legGeometry(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p, double* e,
                   double* s);

}  // namespace guidance
}  // namespace offshore_gnc
