#pragma once
// The navigation's recent poses, interpolated at a sensor's stamp: what the nodelets get from tf2 (the odometry's
// transforms, linear in position and spherical in orientation between the two samples around the stamp, never
// extrapolated), for the ROS-free loops that position LiDAR frames and sonar beams. NED / body FRD.
#include <Eigen/Geometry>

#include <deque>

#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace navigation {

// Body (FRD) attitude in NED from Euler angles (yaw, pitch, roll: z-y-x).
inline Eigen::Quaterniond attitudeNed(double roll, double pitch, double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

class PoseHistory {
 public:
  explicit PoseHistory(double span = 10.0) : span_(span) {}
  void add(const VehicleState& s) {
    if (!isFinite(s) || (!poses_.empty() && s.t <= poses_.back().t)) return;
    poses_.push_back({s.t, s.position, attitudeNed(s.roll, s.pitch, s.yaw)});
    while (poses_.size() > 2 && poses_.front().t < s.t - span_) poses_.pop_front();
  }
  double latest() const { return poses_.empty() ? -1e300 : poses_.back().t; }
  // Body -> NED at time t; false when t is outside the history (tf2 would wait, then drop).
  bool at(double t, Eigen::Isometry3d& body_to_ned) const {
    if (poses_.empty() || t < poses_.front().t || t > poses_.back().t) return false;
    std::size_t i = 1;
    while (i < poses_.size() && poses_[i].t < t) ++i;
    const Sample& b = poses_[std::min(i, poses_.size() - 1)];
    const Sample& a = poses_[i == 0 ? 0 : i - 1];
    const double f = b.t > a.t ? (t - a.t) / (b.t - a.t) : 0.0;
    body_to_ned = Eigen::Translation3d(a.p + f * (b.p - a.p)) * a.q.slerp(f, b.q);
    return true;
  }

 private:
  struct Sample {
    double t;
    Eigen::Vector3d p;
    Eigen::Quaterniond q;
  };
  double span_;
  std::deque<Sample> poses_;
};

}  // namespace navigation
}  // namespace offshore_gnc
