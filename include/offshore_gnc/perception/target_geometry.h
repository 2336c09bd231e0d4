#pragma once
// Geometry of one extracted target (LiDAR cluster or run of sonar beams), shared by both extractors so that
// a target means the same thing whichever sensor saw it (thesis eq. 4.3, paper Algorithm 2).
#include <Eigen/Geometry>

#include <cmath>
#include <cstddef>
#include <vector>

namespace offshore_gnc {
namespace perception {

struct TargetGeometry {
  Eigen::Vector3d origin{0, 0, 0};    // eq. 4.3: midpoint of the first and last return (angular order)
  Eigen::Vector3d centroid{0, 0, 0};  // mean of the returns
  Eigen::Vector3d nearest{0, 0, 0};   // return closest to the sensor (horizontal distance)
  double length = 0.0;                // extent along first -> last [m]
  Eigen::Vector3d axis{0, 0, 0};      // unit direction first -> last in the x-y plane (zero: no points)
  double width = 0.0;                 // extent across first -> last [m]
  double height = 0.0;                // z extent [m]
  double range = 0.0;                 // horizontal sensor -> nearest [m]
  double bearing = 0.0;               // atan2(dy, dx) of origin - sensor in the points' frame [rad]
  std::size_t num_points = 0;
};

// Describes the points (any order) as seen from `sensor` (same frame). "First" and "last" are the angular
// extremes around the centroid's direction, so a target across the +-pi or 0/2pi seam is handled. The
// length/width axes are first -> last and its normal in the x-y plane. Empty input gives num_points = 0.
TargetGeometry describeTarget(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& sensor);

// The same target in another frame (`T`: points' frame -> that frame); extents and range are unchanged.
inline TargetGeometry transformed(const TargetGeometry& g, const Eigen::Isometry3d& T) {
  TargetGeometry o = g;
  o.origin = T * g.origin;
  o.centroid = T * g.centroid;
  o.nearest = T * g.nearest;
  o.axis = T.linear() * g.axis;
  return o;
}

// Monotonic stand-in for atan2(y, x) on (-pi, pi] mapped to (-2, 2]: no trigonometry in the inner loops.
inline double pseudoAngle(double y, double x) {
  const double s = std::abs(y) + std::abs(x);
  if (s == 0.0) return 0.0;
  const double p = y / s;  // in [-1, 1] for x >= 0
  if (x >= 0.0) return p;
  return y >= 0.0 ? 2.0 - p : -2.0 - p;
}

}  // namespace perception
}  // namespace offshore_gnc
