#pragma once
// Parameters shared by the USBL node and its simulator (mounting), read through ParamReader.
#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/usbl/positioning.h"

namespace offshore_gnc {
namespace usbl_ros {

// mount/{x,y,z} [m] in the USV body frame (x forward, y starboard, z down); mount/{roll,pitch,yaw} [deg].
inline usbl::Mounting readMounting(const ros_util::ParamReader& p) {
  usbl::Mounting m;
  m.offset = {p.number("mount/x", 0.0, -50, 50), p.number("mount/y", 0.0, -50, 50), p.number("mount/z", 0.5, -50, 50)};
  m.roll = deg2rad(p.number("mount/roll", 0.0, -180, 180));
  m.pitch = deg2rad(p.number("mount/pitch", 0.0, -90, 90));
  m.yaw = deg2rad(p.number("mount/yaw", 0.0, -180, 180));
  return m;
}

}  // namespace usbl_ros
}  // namespace offshore_gnc
