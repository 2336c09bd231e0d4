#pragma once
// Dynamic positioning of the twin-waterjet USV (paper 3.2.3: "PID controllers for surge, sway and yaw"): holds a
// point in NED with a PID per horizontal axis whose integral learns the steady force the current asks for, and
// turns the bow into that force, where the jets are strongest (ahead thrust) and the hull's drag is least, so that
// the weak sway axis only trims. Forces are computed in NED (the integral does not rotate with the boat) and
// handed over in body axes; the yaw is the USV controller's heading PID on the returned heading. The proportional
// term is limited to an approach speed, so a large offset is closed at max_speed, never with an overshoot.
// Feedback: the velocity through the low-pass + notch cascade of eq. 4.15-4.16; the position through the low-pass
// only (notches at 0.1-0.4 rad/s would take out the DP loop's own band).
#include <Eigen/Core>

#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/control/filters.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace control {

struct DpParams {
  double kp = 60.0;            // N per m of offset
  double ki = 1.5;             // N per m s
  double kd = 1200.0;          // N per m/s of velocity error (about 2 * omega * mass for omega 0.1 rad/s)
  double max_speed = 0.4;      // the offset is closed at most this fast [m/s]
  double i_limit = 1500.0;     // |integral force| bound (anti-windup) [N]
  double surge_force = 4000.0; // force of full joystick surge [N] (as UsvControlParams::max_surge_force)
  double sway_force = 300.0;   // force of full joystick sway [N] (scale only: the side force the buckets balance grows with the rpm)
  double heading_force = 40.0; // a learnt steady force above this turns the bow into it [N]
  double heading_tau = 5.0;    // time constant of the bow's turn into the steady force [s]
  static const ParamTable<DpParams>& table();
  void validate() const;
};

struct DpOutput {
  double surge = 0.0, sway = 0.0;           // normalised joystick axes
  double heading = 0.0;                     // heading to hold [rad]
  Eigen::Vector2d force = Eigen::Vector2d::Zero();        // requested force, NED [N]
  Eigen::Vector2d steady_force = Eigen::Vector2d::Zero(); // the integral's: the current's push, reversed [N]
  double distance = 0.0;                    // from the hold point [m]
};

class DynamicPositioning {
 public:
  DynamicPositioning(const DpParams& p, const FilterParams& filter, double dt);
  // `heading` is the reference heading of the hold (e.g. the path's last leg), used until a steady force is learnt.
  DpOutput update(const VehicleState& s, const Eigen::Vector2d& point, double heading);
  void reset();  // forget the learnt force (a new hold point far from the last)
  void setParams(const DpParams& p);  // validates; keeps the learnt force
  const DpParams& params() const { return p_; }

 private:
  DpParams p_;
  FilterParams filter_;
  double dt_;
  FeedbackFilter fn_, fe_, fvn_, fve_;
  Eigen::Vector2d integral_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d point_ = Eigen::Vector2d::Constant(1e300);
  double heading_ref_ = 0.0, last_t_ = -1e300;
  bool primed_ = false, into_force_ = false;
};

}  // namespace control
}  // namespace offshore_gnc
