#pragma once
// Sonar wall detection (Publication II, Algorithm 1), ROS-free: split-and-merge line extraction over the
// sweep's points in acquisition order, then merging of collinear segments (also across the sweep's start,
// so a wall crossing the 0-degree bearing stays one wall), then the two waypoints at a set distance from the
// chosen wall, `spacing` apart, for the LOS path follower. WallDetector reads the sweep as the sonar targets
// publish it (a PointCloud2 layout), so the beams are assembled into sweeps once, by SonarTargetExtractor.
#include <Eigen/Core>

#include <string>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/perception/cloud_view.h"

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

// What the wall detection made of one sweep.
struct SweepWalls {
  CloudError error = CloudError::None;
  std::string message;                  // the reason when error != None
  std::vector<Eigen::Vector2d> points;  // the sweep's finite detections (x, y), acquisition order
  std::size_t non_finite = 0;           // points dropped for a NaN or infinite x or y
  std::vector<WallSegment> walls;       // longest first
};

// The WallDetection nodelet's core. A sweep is the sonar targets' sweep cloud (`sonar/sweep`): one point per
// detection, x, y, z in the world frame, in acquisition order (the order split-and-merge follows).
class WallDetector {
 public:
  explicit WallDetector(const WallConfig& cfg);  // throws ConfigError
  // A sweep without points is no error: the sonar saw nothing (no walls; counted empty_sweep). A malformed one
  // (checkCloudLayout) has no walls and is counted under its error's name; a non-finite point is dropped and
  // counted (non_finite_point): the sonar targets never publish one.
  SweepWalls detect(const CloudView& sweep);
  WallPath plan(const std::vector<WallSegment>& walls, const Eigen::Vector2d& vehicle, double yaw) const {
    return planWallPath(walls, vehicle, yaw, cfg_);
  }
  const Counters& counters() const { return counters_; }
  Counters& counters() { return counters_; }
  const WallConfig& config() const { return cfg_; }

 private:
  WallConfig cfg_;
  Counters counters_;
};

}  // namespace perception
}  // namespace offshore_gnc
