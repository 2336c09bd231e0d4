#pragma once
// Core state <-> ROS messages, for every nodelet: the cores work in NED / body FRD, messages in REP-103 frames
// (map ENU, base_link FLU; docs/architecture.md).
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <offshore_gnc/GuidanceStatus.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/utils.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <string>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/reference.h"
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

// Orientation of a FLU body in the ENU map from NED/FRD Euler angles.
inline geometry_msgs::Quaternion enuQuaternion(double roll, double pitch, double yaw_ned) {
  tf2::Quaternion q;
  q.setRPY(roll, -pitch, geo::nedYawToEnu(yaw_ned));
  geometry_msgs::Quaternion m;
  m.x = q.x();
  m.y = q.y();
  m.z = q.z();
  m.w = q.w();
  return m;
}

inline nav_msgs::Odometry toOdometry(const VehicleState& s, const std::string& frame, const std::string& child) {
  nav_msgs::Odometry o;
  o.header.stamp = ros::Time(s.t);
  o.header.frame_id = frame;
  o.child_frame_id = child;
  const Eigen::Vector3d p = geo::nedToEnu(s.position);
  o.pose.pose.position.x = p.x();
  o.pose.pose.position.y = p.y();
  o.pose.pose.position.z = p.z();
  o.pose.pose.orientation = enuQuaternion(s.roll, s.pitch, s.yaw);
  o.twist.twist.linear.x = s.velocity.x();  // body FRD -> FLU
  o.twist.twist.linear.y = -s.velocity.y();
  o.twist.twist.linear.z = -s.velocity.z();
  o.twist.twist.angular.x = s.angular_rate.x();
  o.twist.twist.angular.y = -s.angular_rate.y();
  o.twist.twist.angular.z = -s.angular_rate.z();
  return o;
}

inline geometry_msgs::TransformStamped toTransform(const nav_msgs::Odometry& o) {
  geometry_msgs::TransformStamped t;
  t.header = o.header;
  t.child_frame_id = o.child_frame_id;
  t.transform.translation.x = o.pose.pose.position.x;
  t.transform.translation.y = o.pose.pose.position.y;
  t.transform.translation.z = o.pose.pose.position.z;
  t.transform.rotation = o.pose.pose.orientation;
  return t;
}

// A static sensor mount (body FRD <- sensor, sim::sensorMount) as the TF from the FLU base frame to the sensor.
inline geometry_msgs::TransformStamped mountTransform(const std::string& base, const std::string& sensor,
                                                      const Eigen::Isometry3d& body_frd_to_sensor) {
  const Eigen::Isometry3d t = Eigen::Isometry3d(Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX())) * body_frd_to_sensor;
  const Eigen::Quaterniond q(t.rotation());
  geometry_msgs::TransformStamped m;
  m.header.stamp = ros::Time(0);
  m.header.frame_id = base;
  m.child_frame_id = sensor;
  m.transform.translation.x = t.translation().x();
  m.transform.translation.y = t.translation().y();
  m.transform.translation.z = t.translation().z();
  m.transform.rotation.x = q.x();
  m.transform.rotation.y = q.y();
  m.transform.rotation.z = q.z();
  m.transform.rotation.w = q.w();
  return m;
}

// GuidanceStatus' reference fields, as the guidance pipeline computed them (a field copy, no decisions).
inline MotionReference referenceFromStatus(const GuidanceStatus& g) {
  MotionReference r;
  r.mode = g.reference_mode == GuidanceStatus::REFERENCE_FOLLOW ? ReferenceMode::kFollow
           : g.reference_mode == GuidanceStatus::REFERENCE_HOLD ? ReferenceMode::kHold
                                                                  : ReferenceMode::kIdle;
  r.heading = g.desired_heading;
  r.surge = g.desired_surge;
  r.depth = g.desired_depth;
  r.path_angle = g.path_angle;
  r.point = Eigen::Vector3d(g.reference_point.x, g.reference_point.y, g.reference_point.z);
  r.room_to_turn = g.reference_room_to_turn;
  return r;
}

inline void fillReference(const MotionReference& r, GuidanceStatus& g) {
  g.reference_mode = r.mode == ReferenceMode::kFollow ? GuidanceStatus::REFERENCE_FOLLOW
                     : r.mode == ReferenceMode::kHold ? GuidanceStatus::REFERENCE_HOLD
                                                      : GuidanceStatus::REFERENCE_IDLE;
  g.desired_heading = r.heading;
  g.desired_surge = r.surge;
  g.desired_depth = r.depth;
  g.path_angle = r.path_angle;
  g.reference_point.x = r.point.x();
  g.reference_point.y = r.point.y();
  g.reference_point.z = r.point.z();
  g.reference_room_to_turn = r.room_to_turn;
}

// /auv/navigation/status (std_msgs/String, latched): the AUV navigation's state (navigation::NavStatus), written by
// the AuvNavigation nodelet; the aColor's Control nodelet lets its hold drift while the fix is lost.
namespace nav_status {
constexpr char kNoFix[] = "no_fix", kOk[] = "ok", kFixLost[] = "fix_lost", kNoHeading[] = "no_heading";
}  // namespace nav_status

}  // namespace ros_util
}  // namespace offshore_gnc
