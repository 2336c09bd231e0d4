#pragma once
// LiDAR targets become tracks (issue 33), ROS-free: one constant-velocity Kalman filter per track on the targets'
// positions in the world frame (x, y of the target frame: north, east in map_ned), a Mahalanobis gate about each
// track's predicted position, global nearest neighbour assignment (the Hungarian method over the gated squared
// distances: one target per track and one track per target, the set of pairs of least total distance, so two
// crossing targets do not swap tracks as a greedy nearest-first pairing may), ids that persist and are never reused.
// A track is born tentative on a target no track takes, confirmed after `confirm_hits` updates, and dropped when
// unseen for `drop_time` (`tentative_drop_time` before it is confirmed).
#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace perception {

struct TrackerParams {
  // [m/s^2] the white acceleration the constant-velocity model allows (a small boat changing course or speed)
  double accel_sigma = 0.5;
  double position_sigma = 0.3;  // [m] a target position's noise per axis (the returns' centroid)
  // share of the target's extent added to that: the centroid of a hull's returns moves along it as its aspect changes
  double extent_share = 0.05;
  double initial_speed_sigma = 4.0;  // [m/s] per axis: what a newborn track knows of its velocity
  double gate = 3.5;                 // Mahalanobis distance of a target from a track's prediction that it may take
  int confirm_hits = 4;              // updates (its first detection included) that confirm a track
  double drop_time = 2.0;            // [s] a confirmed track unseen this long is dropped
  double tentative_drop_time = 0.3;  // [s] a tentative one (clutter that is not seen again)
  static const ParamTable<TrackerParams>& table();
  void validate() const;  // throws ConfigError naming the value
};

// One target of a frame, in the world frame.
struct Detection {
  Eigen::Vector2d position{0, 0};  // [m]
  double length = 0.0, width = 0.0;  // its extent [m] (0: a point)
};

struct Track {
  std::uint32_t id = 0;  // from 1, never reused
  bool confirmed = false;
  Eigen::Vector4d x = Eigen::Vector4d::Zero();      // x, y [m], vx, vy [m/s]
  Eigen::Matrix4d P = Eigen::Matrix4d::Identity();  // its covariance
  double born = 0.0, last_seen = 0.0, t = 0.0;      // [s]: its birth, last update, the time x is predicted to
  int hits = 0;                                     // updates, its first detection included
  double length = 0.0, width = 0.0;                 // its last detection's extent [m]
  int detection = -1;                               // the index of the detection it took in the last frame, or -1
  Eigen::Vector2d position() const { return x.head<2>(); }
  Eigen::Vector2d velocity() const { return x.tail<2>(); }
};

class TargetTracker {
 public:
  explicit TargetTracker(const TrackerParams& p);
  // One frame's targets at time t [s]. Every track is predicted to t, takes at most one target in its gate, and is
  // born, confirmed or dropped by the rules above. A target with a non-finite position or extent is counted
  // (`non_finite_detection`) and left out. A time before the last frame's (a replay or a simulator that restarted)
  // is counted (`time_backwards`) and starts afresh: the tracks are dropped, the ids go on. A non-finite t is
  // counted (`non_finite_time`) and the frame ignored (false).
  bool update(double t, const std::vector<Detection>& detections);
  // Every track, tentative ones included, in the order they were born.
  const std::vector<Track>& tracks() const { return tracks_; }
  const Counters& counters() const { return counters_; }
  const TrackerParams& params() const { return p_; }

 private:
  void predict(Track& tr, double t) const;
  Eigen::Matrix2d noise(double length, double width) const;

  TrackerParams p_;
  std::vector<Track> tracks_;
  std::uint32_t next_id_ = 1;
  bool started_ = false;
  double last_t_ = 0.0;
  Counters counters_;
};

// Least-cost assignment of rows to columns (the Hungarian method, O(n^3)): cost[i][j] the cost of pairing row i with
// column j, `forbidden` (or more) for a pair that may not be made. Returns for each row its column or -1. Rows and
// columns left unpaired cost `unpaired` each, so a pair is made only when it costs less than leaving both alone.
std::vector<int> assignLeastCost(const std::vector<std::vector<double>>& cost, double unpaired, double forbidden);

}  // namespace perception
}  // namespace offshore_gnc
