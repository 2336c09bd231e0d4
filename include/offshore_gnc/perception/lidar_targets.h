#pragma once
// LiDAR target extraction (thesis 4.1.1, paper 3.1, eq. 4.3), ROS-free. Reads a PointCloud2-layout buffer
// in place (no copy into a PCL cloud), levels each return with the sensor's roll and pitch (its IMU: on a boat
// the layers sweep water and sky), keeps returns inside a range / height band and outside the own hull, splits
// each layer in scan order where consecutive returns jump by more than `gap` or skip beams, drops isolated
// returns (spray, foam, dropouts' leftovers), joins the wrap at the end of a 360-degree aperture, merges the
// layers' segments that touch, and describes each target.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/perception/cloud_view.h"
#include "offshore_gnc/perception/target_geometry.h"

namespace offshore_gnc {
namespace perception {

struct LidarConfig {
  double min_range = 0.5;        // [m] closer returns are dropped (spray, the sensor mount)
  double max_range = 200.0;      // [m]
  double min_z = -1.0;           // [m] in the levelled cloud frame: below = water-surface returns
  double max_z = 10.0;           // [m]
  double gap = 1.0;              // [m] jump between consecutive returns that starts a new target
  double layer_merge = 1.0;      // [m] segments of different layers closer than this are one target
  int min_points = 3;            // smaller clusters are dropped (spray, birds)
  int max_beam_gap = 2;          // consecutive returns of a layer more beams apart than this start a new target
  int min_run = 2;               // a layer's run of fewer returns is dropped before the layers merge (spray)
  // A target is reported once seen in this many consecutive frames, each within confirm_distance of the last
  // (spray and whitecaps last one frame: the boat's pitch sweeps the layers across the water). 1 = at once.
  int confirm_frames = 3;
  double confirm_distance = 1.0;  // [m]
  // Own hull, axis-aligned box in the cloud frame; returns inside are dropped. Empty box (min >= max) = off.
  double hull_min_x = 0, hull_max_x = 0, hull_min_y = 0, hull_max_y = 0;

  static const ParamTable<LidarConfig>& table();
  void validate() const;  // throws ConfigError naming the value
};

struct LidarResult {
  CloudError error = CloudError::None;
  std::string message;                  // human-readable reason when error != None
  std::vector<TargetGeometry> targets;  // in the (levelled) cloud frame, sensor at its origin; confirmed
  std::size_t points_in = 0, points_used = 0, non_finite = 0;
  std::size_t unconfirmed = 0;          // targets of this frame not (yet) seen in enough frames
};

// Rotation taking the cloud frame (x forward, y left, z up) to the levelled frame with the same heading, for a
// sensor at `roll` and `pitch` (REP-103: about its x and y axes, as sensor_msgs/Imu reports them).
Eigen::Matrix3d levelling(double roll, double pitch);

class LidarTargetExtractor {
 public:
  explicit LidarTargetExtractor(const LidarConfig& cfg);
  // Not thread-safe (reuses scratch buffers between frames); one extractor per nodelet. `level`: the cloud frame
  // to the levelled frame (levelling()); the range and height band apply there, the hull box in the cloud frame,
  // and the targets come out levelled.
  LidarResult extract(const CloudView& cloud, const Eigen::Matrix3d& level = Eigen::Matrix3d::Identity());
  // The cloud's layout alone (extract's first step, O(1)): false, with r.error and its counter, for a malformed one.
  // The nodelet checks it before it waits for the cloud's pose, so a bad cloud is named as such however late the
  // pose (before, one in ahead of its pose was counted no_transform).
  bool checkLayout(const CloudView& c, LidarResult& r);
  const Counters& counters() const { return counters_; }
  Counters& counters() { return counters_; }
  const LidarConfig& config() const { return cfg_; }

 private:
  struct P {
    float x, y, z;
    std::uint32_t beam;  // index in its layer's scan
  };
  struct Segment {
    std::uint32_t layer, begin, end;  // [begin, end) in layer_points_[layer]
    float minx, maxx, miny, maxy;
  };
  struct Seen {  // a target of the last frame: its x-y box and in how many frames in a row it was seen
    float minx, maxx, miny, maxy;
    int streak;
  };
  void confirm(std::vector<TargetGeometry>& raw, const std::vector<Seen>& boxes, LidarResult& r);
  bool closeEnough(const Segment& a, const Segment& b) const;
  std::size_t find(std::size_t i);

  LidarConfig cfg_;
  Counters counters_;
  std::vector<std::vector<P>> layers_;
  std::vector<std::uint32_t> beam_;
  std::vector<Segment> segments_;
  std::vector<std::size_t> parent_, order_;
  std::vector<std::vector<Eigen::Vector3d>> cluster_points_;
  std::vector<Seen> seen_, now_;
};

}  // namespace perception
}  // namespace offshore_gnc
