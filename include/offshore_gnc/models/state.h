#pragma once
// Vehicle state shared by the models, the sensor simulators, guidance and control (all ROS-free).
// NED world frame (x north, y east, z down) and body frame (x forward, y starboard, z down), SI units,
// angles in radians (yaw clockwise from north, wrapped to (-pi, pi]).
#include <cmath>

#include <Eigen/Core>

namespace offshore_gnc {

// Shallower than this an AUV is at the surface: the default of its mission's surface_depth (SURFACED) and of its
// navigation's (where the wind starts to set the hull), one fact for both. [m]
constexpr double kAuvSurfaceDepth = 0.5;

struct VehicleState {
  double t = 0.0;                                       // simulated time [s]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   // eta_1 = (north, east, down) [m]
  double roll = 0.0, pitch = 0.0, yaw = 0.0;            // eta_2 [rad]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();   // nu_1 = (u, v, w) body [m/s]
  Eigen::Vector3d angular_rate = Eigen::Vector3d::Zero();  // nu_2 = (p, q, r) body [rad/s]
};

inline bool isFinite(const VehicleState& s) {
  return std::isfinite(s.t) && s.position.allFinite() && std::isfinite(s.roll) && std::isfinite(s.pitch) &&
         std::isfinite(s.yaw) && s.velocity.allFinite() && s.angular_rate.allFinite();
}

}  // namespace offshore_gnc
