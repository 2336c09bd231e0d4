#pragma once
// Plane geometry shared by guidance, mission and safety (NED or any planar frame, metres).
#include <Eigen/Core>

#include <algorithm>

namespace offshore_gnc {

// Distance of p from the segment a-b (from a when the segment has no length).
inline double segmentDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double k = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + k * ab - p).norm();
}

}  // namespace offshore_gnc
