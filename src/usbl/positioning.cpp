#include "offshore_gnc/usbl/positioning.h"

#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/usbl/config.h"

namespace offshore_gnc {
namespace usbl {

Eigen::Matrix3d Mounting::rotation() const {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Pose predictPose(const Pose& p, const Eigen::Vector3d& v_body, const Eigen::Vector3d& w_body, double dt) {
  // midpoint attitude for the translation: a turning vehicle's track curves
  const double angle = w_body.norm() * dt;
  const Eigen::Vector3d axis = angle > 1e-12 ? Eigen::Vector3d(w_body.normalized()) : Eigen::Vector3d::UnitZ();
  const Eigen::Quaterniond half = p.q * Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * angle, axis));
  Pose out;
  out.ned = p.ned + half * v_body * dt;
  out.q = (p.q * Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis))).normalized();
  return out;
}

Eigen::Quaterniond enuFluToNedFrd(const Eigen::Quaterniond& q_enu_flu) {
  Eigen::Matrix3d ned_enu;
  ned_enu << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  const Eigen::Matrix3d flu_frd = Eigen::Vector3d(1, -1, -1).asDiagonal();
  return Eigen::Quaterniond(ned_enu * q_enu_flu.normalized().toRotationMatrix() * flu_frd).normalized();
}

Eigen::Vector3d fromRangeAngles(double range, double azimuth, double elevation) {
  const double h = range * std::cos(elevation);
  return {h * std::cos(azimuth), h * std::sin(azimuth), -range * std::sin(elevation)};
}

void toRangeAngles(const Eigen::Vector3d& v, double& range, double& azimuth, double& elevation) {
  range = v.norm();
  azimuth = wrapTwoPi(std::atan2(v.y(), v.x()));
  elevation = std::atan2(-v.z(), std::hypot(v.x(), v.y()));
}

const char* qualityName(std::uint8_t q) {
  switch (q) {
    case Q_OK: return "ok";
    case Q_FILTER_ERROR: return "filter_error";
    case Q_FIT_ERROR: return "fit_error";
    case Q_STALE: return "stale";
    case Q_DEPTH: return "depth";
    default: return "no_position";
  }
}

Positioner::Positioner(const Mounting& mount, const QualityLimits& limits)
    : mount_(mount), r_body_xcvr_(mount.rotation()), limits_(limits) {
  qualityLimitsTable().validate(limits);
  requireRange("max_pose_wait", limits.max_pose_wait_s, 0.0, limits.max_age_s);
}

bool Positioner::ready(double t_reply, double t_now) const {
  return (usv_pos_.lastTime() >= t_reply && usv_att_.lastTime() >= t_reply) || t_now - t_reply >= limits_.max_pose_wait_s;
}

FixResult Positioner::process(const AcoFix& fix, double t_reply, double t_now) {
  FixResult r;
  const bool geometric = fix.has(AcoFix::RANGE) && fix.has(AcoFix::USBL);
  const double travel = fix.has(AcoFix::RANGE) ? fix.rangeTimeS() : 0.0;
  r.stamp = t_reply - (std::isfinite(travel) && travel > 0 && travel < 10 ? travel : 0.0);
  if (fix.has(AcoFix::POSITION))
    r.local = Eigen::Vector3d(fix.north * 0.1, fix.east * 0.1, fix.depth * 0.1);

  // The transceiver measures the direction when the reply arrives: the USV's pose at t_reply.
  const auto pos = usv_pos_.at(t_reply, limits_.max_pose_gap_s,
                               [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, double s) { return a + s * (b - a); });
  const auto att = usv_att_.at(t_reply, limits_.max_pose_gap_s,
                               [](const Eigen::Quaterniond& a, const Eigen::Quaterniond& b, double s) { return a.slerp(s, b); });
  if (geometric && pos && att) {
    const bool timed = limits_.water_sound_speed > 0.0 && std::isfinite(travel) && travel > 0.0 && travel < 10.0;
    const double range = timed ? travel * limits_.water_sound_speed : fix.rangeM();
    const Eigen::Vector3d v = fromRangeAngles(range, fix.azimuthRad(), fix.elevationRad());
    r.ned = *pos + *att * (mount_.offset + r_body_xcvr_ * v);
  }

  if (!geometric)
    r.quality = Q_NO_POSITION;
  else if (fix.has(AcoFix::FILTER_ERROR))
    r.quality = Q_FILTER_ERROR;
  else if (fix.fitError() > limits_.max_fit_error)
    r.quality = Q_FIT_ERROR;
  else if (t_now - r.stamp > limits_.max_age_s || !r.ned)
    r.quality = Q_STALE;  // too late, or no USV pose near the fix time to geo-reference it
  else {
    const auto d = depth_.at(r.stamp, limits_.max_depth_gap_s, [](double a, double b, double s) { return a + s * (b - a); });
    r.quality = (d && std::abs(*d - r.ned->z()) > limits_.max_depth_error_m) ? Q_DEPTH : Q_OK;
  }
  counters_.increment(r.quality == Q_OK ? std::string("accepted") : std::string("rejected_") + qualityName(r.quality));
  return r;
}

}  // namespace usbl
}  // namespace offshore_gnc
