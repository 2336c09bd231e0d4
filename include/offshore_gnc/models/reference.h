#pragma once
// What guidance asks of control: the one contract between the two (GuidanceStatus carries the same fields), in
// this lower module so that neither includes the other. NED, radians.
#include <Eigen/Core>

#include <cmath>
#include <cstdint>

namespace offshore_gnc {

enum class ReferenceMode : std::uint8_t { kIdle = 0, kFollow = 1, kHold = 2 };

struct MotionReference {
  ReferenceMode mode = ReferenceMode::kIdle;  // kIdle: neutral actuators
  double heading = 0.0;                       // psi_d [rad]
  double surge = 0.0;                         // u_d [m/s]
  double depth = 0.0;                         // AUV depth [m]
  double path_angle = 0.0;                    // chi_p of the active leg [rad]
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // kHold: the hold point; kFollow: the projection on the leg
  // kFollow: nothing guidance knows of lies within the hull's sweep about where the vehicle is, so control may hold
  // it there while it turns onto the path (UsvControlParams::turn_hold_angle)
  bool room_to_turn = false;

  bool valid() const {
    return std::isfinite(heading) && std::isfinite(surge) && std::isfinite(path_angle) && point.head<2>().allFinite();
  }
};

}  // namespace offshore_gnc
