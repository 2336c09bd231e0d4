#include "offshore_gnc/control/dynamic_positioning.h"

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace control {

const ParamTable<DpParams>& DpParams::table() {
  using P = DpParams;
  static const ParamTable<P> t = ParamTable<P>()
      .number("kp", &P::kp, 0.0, 1e5, "N/m", "position gain")
      .number("ki", &P::ki, 0.0, 1e4, "N/(m s)", "integral gain: learns the current's steady push")
      .number("kd", &P::kd, 0.0, 1e6, "N s/m", "velocity gain")
      .number("max_speed", &P::max_speed, 0.01, 5.0, "m/s", "an offset is closed at most this fast")
      .number("i_limit", &P::i_limit, 0.0, 1e5, "N", "largest integral force (anti-windup)")
      .number("surge_force", &P::surge_force, 1.0, 1e6, "N", "force of full joystick surge")
      .number("sway_force", &P::sway_force, 1.0, 1e6, "N", "force of full joystick sway")
      .number("heading_force", &P::heading_force, 0.0, 1e5, "N",
              "a learnt steady force above this turns the bow into it")
      .number("heading_tau", &P::heading_tau, 0.1, 1e3, "s", "time constant of the bow's turn into that force");
  return t;
}

void DpParams::validate() const { table().validate(*this, "dp/"); }

DynamicPositioning::DynamicPositioning(const DpParams& p, const FilterParams& filter, double dt)
    : p_(p), filter_(filter), dt_(dt) {
  p_.validate();
  FilterParams low_pass = filter;
  low_pass.notch_w.clear();
  fn_ = FeedbackFilter(low_pass, dt);
  fe_ = FeedbackFilter(low_pass, dt);
  fvn_ = FeedbackFilter(filter, dt);
  fve_ = FeedbackFilter(filter, dt);
}

void DynamicPositioning::setParams(const DpParams& p) {
  p.validate();
  p_ = p;
}

void DynamicPositioning::reset() {
  integral_.setZero();
  into_force_ = false;
  primed_ = false;
}

DpOutput DynamicPositioning::update(const VehicleState& s, const Eigen::Vector2d& point, double heading) {
  const double c = std::cos(s.yaw), sn = std::sin(s.yaw);
  const Eigen::Vector2d v_ned(c * s.velocity.x() - sn * s.velocity.y(), sn * s.velocity.x() + c * s.velocity.y());
  if ((point - point_).norm() > 20.0) reset();  // a new hold far away: the current there is learnt afresh
  point_ = point;
  if (s.t - last_t_ > 2.5 * dt_) primed_ = false;  // back in station keeping: the filters restart, the force stays
  last_t_ = s.t;
  if (!primed_) {
    fn_.reset(s.position.x());
    fe_.reset(s.position.y());
    fvn_.reset(v_ned.x());
    fve_.reset(v_ned.y());
    heading_ref_ = heading;
    primed_ = true;
  }
  const Eigen::Vector2d p(fn_.step(s.position.x()), fe_.step(s.position.y()));
  const Eigen::Vector2d v(fvn_.step(v_ned.x()), fve_.step(v_ned.y()));
  const Eigen::Vector2d e = point - p;
  DpOutput out;
  out.distance = e.norm();
  // P limited to an approach speed: kd (v_d - v) with v_d = kp / kd e, at most max_speed.
  Eigen::Vector2d v_d = p_.kd > 0.0 ? Eigen::Vector2d(p_.kp / p_.kd * e) : Eigen::Vector2d::Zero();
  if (v_d.norm() > p_.max_speed) v_d *= p_.max_speed / v_d.norm();
  integral_ += p_.ki * e * dt_;
  if (integral_.norm() > p_.i_limit) integral_ *= p_.i_limit / integral_.norm();
  out.force = p_.kd * (v_d - v) + integral_;
  out.steady_force = integral_;
  // The bow into the force asked for once it is clear, turned there slowly (a filtered angle, never a jump): the
  // jets push hardest ahead and the hull's surge drag is a tenth of its sway drag, so near the point the bow ends
  // up in the current (the integral's force) and the weak sway axis only trims; far from it, the bow turns to the
  // point. Bow on, the force shrinks: it is followed down to a tenth of heading_force before the hold's own
  // heading returns (without that hysteresis the boat turned beam on and back).
  const Eigen::Vector2d& steer = out.force;
  const double f = steer.norm();
  if (f > p_.heading_force) into_force_ = true;
  else if (f < 0.1 * p_.heading_force) into_force_ = false;
  const double target = into_force_ ? std::atan2(steer.y(), steer.x()) : heading;
  heading_ref_ = wrapAngle(heading_ref_ + angleDiff(target, heading_ref_) * std::min(1.0, dt_ / p_.heading_tau));
  out.heading = heading_ref_;
  const Eigen::Vector2d body(c * out.force.x() + sn * out.force.y(), -sn * out.force.x() + c * out.force.y());
  out.surge = std::clamp(body.x() / p_.surge_force, -1.0, 1.0);
  out.sway = std::clamp(body.y() / p_.sway_force, -1.0, 1.0);
  return out;
}

}  // namespace control
}  // namespace offshore_gnc
