#pragma once
// Dynamic positioning of the twin-waterjet USV (paper 3.2.3: "PID controllers for surge, sway and yaw"): holds a
// point with a PID per horizontal axis, computed in NED so that its integral, which learns the steady force the
// current asks for, does not rotate with the boat. It returns the force (NED and body axes, which the USV
// controller allocates to the jets) and the heading to hold (the controller's heading PID follows it).
// - The proportional term is limited to an approach speed, so a large offset is closed at max_speed, never with
//   an overshoot. The integral learns within i_radius of the point and not while the boat closes in on it.
// - The heading weathervanes: once the force (low-passed over force_tf) is clear, the bow turns toward where the
//   water comes from, found from that force through the hull's drag (across it drag_ratio times that along it):
//   bow on to the current the jets push hardest (ahead) and the hull's drag is least, so that the weaker sway axis
//   only trims. The bow never follows the force's own direction: a few degrees off the current the hull's side
//   drag turns that force much further to the beam (bow into the force swung +-60 degrees about the current), and
//   its P and D parts swing round as the boat passes the point (that made the first twin-jet missions circle).
// Feedback: position and velocity through a first-order low-pass of filter_tf. Not the notches of eq. 4.16: this
// loop's band (0.05-0.15 rad/s) lies inside theirs, and their lag (7 s at the thesis' xi) took its damping.
#include <Eigen/Core>

#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/control/filters.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace control {

struct DpParams {
  double kp = 300.0;           // N per m of offset
  double ki = 5.0;             // N per m s
  double kd = 2500.0;          // N per m/s of velocity error
  double max_speed = 0.4;      // the offset is closed at most this fast [m/s]
  double i_limit = 1500.0;     // |integral force| bound (anti-windup) [N]
  double i_radius = 8.0;       // the integral learns within this distance of the point [m]
  double i_speed = 0.1;        // ... and while closing in on it slower than this [m/s]
  double heading_force = 40.0; // a (low-passed) force above this starts the weathervaning [N]
  double weathervane_force = 150.0;  // below this force the heading turns in proportion to it [N]
  double weathervane_gain = 0.25;    // heading rate per radian off the water's flow [1/s]
  double force_tf = 10.0;      // low-pass time constant of the force the weathervaning reads [s]
  double drag_ratio = 9.5;     // hull drag across / along at the same water speed (Table 3.4: Y_|v|v / X_|u|u)
  double turn_rate = 0.1;      // largest rate of the held heading [rad/s]
  double filter_tf = 1.0;      // low-pass time constant of the position and velocity feedback [s]
  static const ParamTable<DpParams>& table();
  void validate() const;
};

struct DpOutput {
  double heading = 0.0;                     // heading to hold [rad]
  Eigen::Vector2d force = Eigen::Vector2d::Zero();        // requested force, NED [N]
  Eigen::Vector2d body_force = Eigen::Vector2d::Zero();   // the same in body axes (surge, sway) [N]
  Eigen::Vector2d steady_force = Eigen::Vector2d::Zero(); // the integral's: the current's push, reversed [N]
  double distance = 0.0;                    // from the hold point [m]
  bool weathervaning = false;               // the heading is the bow into the current's (else the hold's own)
  double t = -1e300;                        // the step's time [s]
};

class DynamicPositioning {
 public:
  DynamicPositioning(const DpParams& p, double dt);
  // `heading` is the reference heading of the hold (e.g. the path's last leg), used until a steady force is learnt.
  DpOutput update(const VehicleState& s, const Eigen::Vector2d& point, double heading);
  void reset();   // forget the learnt force (a new hold point far from the last)
  // Back to station keeping after something else (path following, neutral): the filters restart, the learnt
  // force stays, and so does the weathervaned heading if the hold point is the same (else the hold's heading).
  // Not called on gaps in the state's stamps: on a loaded vehicle computer the odometry comes late now and then.
  void resume();
  void setParams(const DpParams& p);  // validates; keeps the learnt force
  const DpParams& params() const { return p_; }

 private:
  static constexpr double kSameHold = 1.0;  // a resumed hold point this close [m] is the same hold
  void makeFilters();
  // The water's flow (NED, upstream, in units of sqrt(N) along the hull) that asks for `force` at `yaw`.
  Eigen::Vector2d currentOf(const Eigen::Vector2d& force, double yaw) const;

  DpParams p_;
  double dt_;
  FeedbackFilter fn_, fe_, fvn_, fve_;
  Eigen::Vector2d integral_ = Eigen::Vector2d::Zero(), force_lp_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d point_ = Eigen::Vector2d::Constant(1e300);
  double heading_ref_ = 0.0;
  bool primed_ = false, into_force_ = false;
};

}  // namespace control
}  // namespace offshore_gnc
