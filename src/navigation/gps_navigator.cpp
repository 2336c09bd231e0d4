// GPS-compass navigation: pose from the fix and heading; velocity from the receiver's Doppler velocity, or by
// filtered differences of fixes when it reports none.
#include "offshore_gnc/navigation/gps_navigator.h"

#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace navigation {

const ParamTable<GpsNavigatorConfig>& GpsNavigatorConfig::table() {
  using P = GpsNavigatorConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .list("antenna", 3, -50.0, 50.0, "m", "GPS antenna in the body frame (x forward, y starboard, z down)",
            [](const P& p) { return std::vector<double>{p.antenna.x(), p.antenna.y(), p.antenna.z()}; },
            [](P& p, const std::vector<double>& v) { p.antenna = {v[0], v[1], v[2]}; })
      .number("heading_timeout", &P::heading_timeout, 1e-3, 60.0, "s", "a fix needs a heading at most this old")
      .number("velocity_filter", &P::velocity_filter, 0.0, 60.0, "s",
              "time constant of the filter on differenced velocity (receivers without Doppler)");
  return t;
}

const ParamTable<GpsNavigationParams>& GpsNavigationParams::table() {
  using P = GpsNavigationParams;
  static const ParamTable<P> t = ParamTable<P>()
      .flag("use_rate_of_turn", &P::use_rate_of_turn,
            "the velocity message's angular.z is the receiver's rate of turn (false: from differenced headings)")
      .string("base_frame", &P::base_frame, "the USV's body frame")
      .string("world_frame", &P::world_frame, "frame of /usv/odom");
  return t;
}

GpsNavigator::GpsNavigator(const geo::LatLonAlt& origin, const GpsNavigatorConfig& cfg) : frame_(origin), cfg_(cfg) {
  GpsNavigatorConfig::table().validate(cfg);
  for (int i = 0; i < 3; ++i) requireRange("antenna", cfg.antenna[i], -50, 50);
}

bool GpsNavigator::heading(double t, double yaw) {
  if (!std::isfinite(t) || !std::isfinite(yaw)) {
    counters_.increment("bad_heading");
    return false;
  }
  if (t > heading_t_ && heading_t_ > -1e299 && t - heading_t_ < 5.0)
    yaw_rate_ = angleDiff(yaw, yaw_) / (t - heading_t_);
  heading_t_ = t;
  yaw_ = wrapAngle(yaw);
  return true;
}

bool GpsNavigator::velocity(double t, const Eigen::Vector2d& v_ned, double rate_of_turn) {
  if (!std::isfinite(t) || !v_ned.allFinite() || std::isinf(rate_of_turn)) {
    counters_.increment("bad_velocity");
    return false;
  }
  velocity_t_ = t;
  v_ned_ = v_ned;
  rate_of_turn_ = rate_of_turn;
  return true;
}

std::optional<VehicleState> GpsNavigator::fix(double t, const geo::LatLonAlt& p) {
  if (!std::isfinite(t) || !std::isfinite(p.lat_deg) || !std::isfinite(p.lon_deg) || std::abs(p.lat_deg) > 90 ||
      std::abs(p.lon_deg) > 180) {
    counters_.increment("bad_fix");
    return std::nullopt;
  }
  if (std::abs(t - heading_t_) > cfg_.heading_timeout) {
    counters_.increment("fix_without_heading");
    return std::nullopt;
  }
  VehicleState s;
  s.t = t;
  s.yaw = yaw_;
  s.angular_rate.z() = yaw_rate_;
  const Eigen::Vector3d ant = frame_.toNed(p);
  const double c = std::cos(yaw_), sn = std::sin(yaw_);
  // the vessel's reference point is the antenna minus its lever arm; 3-DOF: on the surface
  s.position = {ant.x() - (c * cfg_.antenna.x() - sn * cfg_.antenna.y()),
                ant.y() - (sn * cfg_.antenna.x() + c * cfg_.antenna.y()), 0.0};
  if (last_ && t <= last_->t) {
    counters_.increment("stale_fix");
    return std::nullopt;
  }
  if (std::abs(t - velocity_t_) <= cfg_.heading_timeout) {
    // Doppler: the antenna's ground velocity in the body frame, minus the yaw rate acting on the lever arm
    const double r = std::isfinite(rate_of_turn_) ? rate_of_turn_ : yaw_rate_;
    s.velocity.x() = c * v_ned_.x() + sn * v_ned_.y() + r * cfg_.antenna.y();
    s.velocity.y() = -sn * v_ned_.x() + c * v_ned_.y() - r * cfg_.antenna.x();
    s.angular_rate.z() = r;
  } else if (last_) {
    const double dt = t - last_->t;
    const Eigen::Vector2d v_ned = (s.position - last_->position).head<2>() / dt;
    const Eigen::Vector2d v_body(c * v_ned.x() + sn * v_ned.y(), -sn * v_ned.x() + c * v_ned.y());
    const double a = cfg_.velocity_filter > 0 ? 1.0 - std::exp(-dt / cfg_.velocity_filter) : 1.0;
    s.velocity.head<2>() = last_->velocity.head<2>() + a * (v_body - last_->velocity.head<2>());
  }
  last_ = s;
  return s;
}

}  // namespace navigation
}  // namespace offshore_gnc
