#pragma once
// ROS side shared by the Micron driver and its emulator: the head's parameters (defaults and ranges live in
// micron::SonarSettings / EmulatorConfig, checked by their validate()), and ground-truth odometry as the
// simulator's NED state.
#include <nav_msgs/Odometry.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <limits>

#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/micron/session.h"
#include "offshore_gnc/models/state.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/usbl/positioning.h"

namespace offshore_gnc {
namespace micron_ros {

constexpr double kAny = 1e9;

// Device time: both the head and its emulator run on the wall clock, also under simulated /clock.
inline double monotonic() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}  // ranges are checked by the core's validate(), not twice

inline micron::HeadGeometry readGeometry(const ros_util::ParamReader& p) {
  micron::HeadGeometry g;
  g.forward_offset = deg2rad(p.number("forward_offset_deg", rad2deg(g.forward_offset), 0, 360));
  g.inverted = p.flag("inverted", g.inverted);
  return g;
}

inline micron::SonarSettings readSettings(const ros_util::ParamReader& p) {
  micron::SonarSettings s;
  s.range = p.number("range", s.range, -kAny, kAny);
  s.sector = deg2rad(p.number("sector_deg", rad2deg(s.sector), -kAny, kAny));
  s.step = deg2rad(p.number("step_deg", rad2deg(s.step), -kAny, kAny));
  s.bins = p.integer("bins", s.bins, 0, 1 << 20);
  s.gain = p.number("gain", s.gain, -kAny, kAny);
  s.ad_low = p.number("ad_low_db", s.ad_low, -kAny, kAny);
  s.ad_span = p.number("ad_span_db", s.ad_span, -kAny, kAny);
  s.sound_speed = p.number("sound_speed", s.sound_speed, -kAny, kAny);
  s.beam_width = deg2rad(p.number("beam_width_deg", rad2deg(s.beam_width), -kAny, kAny));
  s.geometry = readGeometry(p);
  ros_util::readParams(p, micron::FourBitFormat::table(), s.four_bit);
  s.head_type = static_cast<std::uint8_t>(p.integer("head_type", s.head_type, 0, 255));
  s.mo_time = p.integer("mo_time", s.mo_time, 0, 1 << 20);
  s.reboot_on_start = p.flag("reboot_on_start", s.reboot_on_start);
  s.reply_timeout = p.number("reply_timeout", s.reply_timeout, -kAny, kAny);
  s.command_retry = p.number("command_retry", s.command_retry, -kAny, kAny);
  s.alive_timeout = p.number("alive_timeout", s.alive_timeout, -kAny, kAny);
  s.max_data_timeouts = p.integer("max_data_timeouts", s.max_data_timeouts, 0, 1 << 20);
  s.validate();
  return s;
}

// Ground truth (map ENU, base_link FLU) -> the simulator's state (NED, body FRD). False when not finite.
inline bool toVehicleState(const nav_msgs::Odometry& o, VehicleState& s) {
  const auto& q = o.pose.pose.orientation;
  const Eigen::Quaterniond e(q.w, q.x, q.y, q.z);
  const Eigen::Vector3d enu(o.pose.pose.position.x, o.pose.pose.position.y, o.pose.pose.position.z);
  if (!enu.allFinite() || !std::isfinite(e.norm()) || e.norm() < 0.5) return false;
  const Eigen::Matrix3d r = usbl::enuFluToNedFrd(e.normalized()).toRotationMatrix();
  s.t = o.header.stamp.toSec();
  s.position = geo::enuToNed(enu);
  s.yaw = std::atan2(r(1, 0), r(0, 0));
  s.pitch = -std::asin(std::clamp(r(2, 0), -1.0, 1.0));
  s.roll = std::atan2(r(2, 1), r(2, 2));
  return true;
}

}  // namespace micron_ros
}  // namespace offshore_gnc
