#pragma once
// Parameters shared by the USBL node and its simulator (mounting), read through its table (usbl/config.h).
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/usbl/config.h"

namespace offshore_gnc {
namespace usbl_ros {

// mount/{x,y,z} [m] in the USV body frame (x forward, y starboard, z down); mount/{roll,pitch,yaw} [deg].
inline usbl::Mounting readMounting(const ros_util::ParamReader& p) {
  usbl::Mounting m;
  ros_util::readParams(p, usbl::mountingTable(), m);
  return m;
}

}  // namespace usbl_ros
}  // namespace offshore_gnc
