#pragma once
// Sonar wall detection (Publication II, Algorithm 1), ROS-free: split-and-merge line extraction over the
// sweep's points in acquisition order, then merging of collinear segments (also across the sweep's start,
// so a wall crossing the 0-degree bearing stays one wall), then the two waypoints at a set distance from the
// chosen wall, `spacing` apart, for the LOS path follower.
#include <Eigen/Core>

#include <string>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace perception {

// The WallDetection nodelet's parameters (config/perception/sonar_auv.yaml): defaults here, names and ranges in
// table(), checked by validate().
struct WallConfig {
  double split_distance = 0.25;  // [m] eq. 7 threshold: farther points split the set
  double break_distance = 1.5;   // [m] consecutive points farther apart start a new set (no line across gaps)
  double merge_angle = deg2rad(6.0);  // [rad] collinear when directions differ less than this...
  double merge_distance = 0.4;   // [m] ...and each segment's ends lie this close to the other's line...
  double merge_gap = 3.0;        // [m] ...and the gap between them is at most this
  int min_points = 6;            // segments with fewer points are not walls
  double min_length = 2.0;       // [m]
  double offset = 2.0;           // [m] waypoints' distance from the wall
  double spacing = 2.0;          // [m] distance between the two waypoints
  std::string base_frame = "auv/base_link";  // the vehicle frame whose pose places the waypoints
  static const ParamTable<WallConfig>& table();
  void validate() const;
};

struct WallSegment {
  Eigen::Vector2d a{0, 0}, b{0, 0};  // end points (on the fitted line)
  int num_points = 0;
  double rms = 0.0;                  // [m] residual of the fit
  double length() const { return (b - a).norm(); }
};

// Split-and-merge over ordered 2-D points (x north, y east or any plane frame).
std::vector<WallSegment> extractWalls(const std::vector<Eigen::Vector2d>& points, const WallConfig& cfg);

struct WallPath {
  bool ok = false;
  WallSegment wall;
  Eigen::Vector2d wp1{0, 0}, wp2{0, 0};  // wp1: abeam of the vehicle at `offset`, wp2: `spacing` further
};

// Picks the longest wall (>= min_length) and places the waypoints on the vehicle's side of it, the second
// one ahead in the direction closest to the vehicle's heading (yaw, same frame as the points, atan2 sense
// of that frame's x/y: NED yaw for x north, y east).
WallPath planWallPath(const std::vector<WallSegment>& walls, const Eigen::Vector2d& vehicle, double yaw,
                      const WallConfig& cfg);

}  // namespace perception
}  // namespace offshore_gnc
