#pragma once
// Message <-> core conversions shared by the guidance and control nodelets (ROS layer only). Odometry comes in
// `map` (ENU) / base_link (FLU); the cores work in NED / FRD (docs/architecture.md).
#include <nav_msgs/Odometry.h>
#include <offshore_gnc/GuidanceStatus.h>
#include <tf2/utils.h>

#include <cmath>

#include "offshore_gnc/control/vehicle_control.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace ros_util {

inline VehicleState stateFromOdom(const nav_msgs::Odometry& o) {
  VehicleState s;
  s.t = o.header.stamp.toSec();
  const auto& p = o.pose.pose.position;
  s.position = geo::enuToNed(Eigen::Vector3d(p.x, p.y, p.z));
  const auto& q = o.pose.pose.orientation;
  const double n2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  s.yaw = (std::isfinite(n2) && n2 > 1e-6) ? geo::enuYawToNed(tf2::getYaw(o.pose.pose.orientation))
                                          : std::numeric_limits<double>::quiet_NaN();
  const auto& v = o.twist.twist.linear;
  s.velocity = Eigen::Vector3d(v.x, -v.y, -v.z);  // FLU -> FRD
  const auto& w = o.twist.twist.angular;
  s.angular_rate = Eigen::Vector3d(w.x, -w.y, -w.z);
  return s;
}

// GuidanceStatus -> control reference (the same mapping as control::toReference for the core output).
inline control::Reference referenceFromStatus(const GuidanceStatus& g, const Eigen::Vector3d& hold,
                                              const Eigen::Vector3d& path_point) {
  control::Reference r;
  r.heading = g.desired_heading;
  r.surge = g.desired_surge;
  r.depth = std::isfinite(g.desired_depth) ? g.desired_depth : 0.0;
  r.path_angle = g.path_angle;
  if (g.mode == GuidanceStatus::MODE_FOLLOW_PATH) {
    r.mode = control::RefMode::kFollow;
    r.point = path_point;
  } else if (g.mode == GuidanceStatus::MODE_STATION_KEEPING || g.mode == GuidanceStatus::MODE_HOLD_FAULT) {
    r.mode = control::RefMode::kHold;
    r.point = hold;
  } else {
    r.mode = control::RefMode::kIdle;
  }
  return r;
}

}  // namespace ros_util
}  // namespace offshore_gnc
