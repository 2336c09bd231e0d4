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
      .number("i_radius", &P::i_radius, 0.0, 1e3, "m", "the integral learns within this distance of the point")
      .number("i_speed", &P::i_speed, 0.0, 10.0, "m/s", "... and while closing in on it slower than this")
      .number("heading_force", &P::heading_force, 0.0, 1e5, "N", "a (low-passed) force above this starts the weathervaning")
      .number("weathervane_force", &P::weathervane_force, 1.0, 1e5, "N",
              "below this force the heading turns in proportion to it")
      .number("weathervane_gain", &P::weathervane_gain, 0.0, 10.0, "1/s", "heading rate per radian off the water's flow")
      .number("force_tf", &P::force_tf, 0.1, 1000.0, "s", "low-pass time constant of the force the weathervaning reads")
      .number("drag_ratio", &P::drag_ratio, 1.0, 1000.0, "",
              "hull drag across over drag along at the same water speed (Table 3.4: Y_|v|v / X_|u|u)")
      .number("turn_rate", &P::turn_rate, 1e-3, 1.0, "rad/s", "largest rate of the held heading")
      .number("filter_tf", &P::filter_tf, 0.0, 100.0, "s", "low-pass time constant of the position and velocity feedback");
  return t;
}

void DpParams::validate() const { table().validate(*this, "dp/"); }

namespace {
// Body axes of a NED vector and back.
Eigen::Vector2d toBody(const Eigen::Vector2d& v, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {c * v.x() + s * v.y(), -s * v.x() + c * v.y()};
}
Eigen::Vector2d toNed(const Eigen::Vector2d& v, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}
double signedRoot(double x) { return std::copysign(std::sqrt(std::abs(x)), x); }
}  // namespace

Eigen::Vector2d DynamicPositioning::currentOf(const Eigen::Vector2d& force, double yaw) const {
  // Quadratic drag (Table 3.4's X_|u|u, Y_|v|v dominate at current speeds): the force's body components are
  // k u|u| and k drag_ratio v|v| of the water's flow; in units of sqrt(k), the same scale both ways.
  const Eigen::Vector2d f = toBody(force, yaw);
  return toNed({signedRoot(f.x()), signedRoot(f.y() / p_.drag_ratio)}, yaw);
}

DynamicPositioning::DynamicPositioning(const DpParams& p, double dt) : p_(p), dt_(dt) {
  p_.validate();
  makeFilters();
}

void DynamicPositioning::makeFilters() {
  FilterParams low_pass;
  low_pass.tf = p_.filter_tf;
  low_pass.notch_w.clear();
  fn_ = fe_ = fvn_ = fve_ = FeedbackFilter(low_pass, dt_);
  primed_ = false;
}

void DynamicPositioning::setParams(const DpParams& p) {
  p.validate();
  const bool refilter = p.filter_tf != p_.filter_tf;
  p_ = p;
  if (refilter) makeFilters();
}

void DynamicPositioning::resume() { primed_ = false; }

void DynamicPositioning::reset() {
  integral_.setZero();
  force_lp_.setZero();
  into_force_ = false;
  primed_ = false;
}

DpOutput DynamicPositioning::update(const VehicleState& s, const Eigen::Vector2d& point, double heading) {
  const double c = std::cos(s.yaw), sn = std::sin(s.yaw);
  const Eigen::Vector2d v_ned(c * s.velocity.x() - sn * s.velocity.y(), sn * s.velocity.x() + c * s.velocity.y());
  const double moved = (point - point_).norm();
  if (moved > 20.0) reset();  // a new hold far away: the current there is learnt afresh
  point_ = point;
  if (!primed_) {
    fn_.reset(s.position.x());
    fe_.reset(s.position.y());
    fvn_.reset(v_ned.x());
    fve_.reset(v_ned.y());
    // The same hold resumed (after a moment of neutral: stale odometry on a loaded computer) keeps the bow into
    // the current; going back to the hold's heading put the boat beam on and cost 8 m in 0.5 m/s. A new hold
    // (a safety stop under way, the end of a path) starts from its own heading: the old weathervaned one spun
    // the braking boat round and its stop took 8.8 s instead of under 8.
    if (!into_force_ || moved > kSameHold) heading_ref_ = heading;
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
  // Learn while held off or pushed away, not while closing in (approaching, an offset is no sign of the current:
  // learnt then, it overshot the point by a metre on the far side).
  const double closing = out.distance > 1e-6 ? v.dot(e) / out.distance : 0.0;
  if (out.distance < p_.i_radius && closing < p_.i_speed) integral_ += p_.ki * e * dt_;
  if (integral_.norm() > p_.i_limit) integral_ *= p_.i_limit / integral_.norm();
  out.force = p_.kd * (v_d - v) + integral_;
  out.steady_force = integral_;
  // Weathervaning (see the header): the held heading turns toward the water's flow that the force, low-passed
  // over force_tf, stands for; at a rate in proportion to the angle and, below weathervane_force, to the force
  // (a weak force's direction is mostly the position loop's wandering), at most turn_rate. Once the force is
  // clear, a hold goes on weathervaning until reset.
  force_lp_ += (out.force - force_lp_) * std::min(1.0, dt_ / p_.force_tf);
  const double f = force_lp_.norm();
  if (f > p_.heading_force) into_force_ = true;
  const Eigen::Vector2d upstream = currentOf(force_lp_, s.yaw);
  const double off = angleDiff(into_force_ ? std::atan2(upstream.y(), upstream.x()) : heading, heading_ref_);
  const double rate = into_force_ ? p_.weathervane_gain * off * std::min(1.0, f / p_.weathervane_force)
                                  : off;  // else back to the hold's heading, within a second
  heading_ref_ = wrapAngle(heading_ref_ + std::clamp(rate, -p_.turn_rate, p_.turn_rate) * dt_);
  out.heading = heading_ref_;
  out.weathervaning = into_force_;
  out.t = s.t;
  out.body_force = toBody(out.force, s.yaw);
  return out;
}

}  // namespace control
}  // namespace offshore_gnc
