#pragma once
// What guidance plans round from the LiDAR's targets: each frame's, and the ones it saw before that the sensor
// cannot see now. A LiDAR on the bow is blind astern (the MRS1000's 275 degrees leave 85 behind it) and beside and
// under its own hull, so a buoy the USV has come alongside drops out of every frame exactly when it matters: a USV
// holding bow-on to a surfaced AUV with a buoy under its stern moved its hold point off the buoy's box and back
// onto the buoy as the box vanished (the default scenario's collisions, 3 seeds in 30, 2026-12-05). As costmap_2d's
// obstacle layer keeps what is out of its sensors' view, an obstacle here is dropped only when the sensor could
// see where it is and did not (in the latest frame, as before this memory), or after `memory` out of view.
// ROS-free; NED, seconds.
#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/guidance/sbb.h"

namespace offshore_gnc {
namespace guidance {

struct ObstacleMemoryParams {
  double timeout = 5.0;          // no frame for this long: nothing is planned round (the sensor is gone) [s]
  double memory = 300.0;         // one out of the sensor's view is kept this long after it was last seen [s]
  int confirm_frames = 5;        // ... when it was seen in this many frames (spray and clutter come once: clear_time)
  double match_gap = 1.0;        // a target this close to a remembered obstacle's extent is that obstacle [m]
  double extent_hold = 0.0;      // a target seen again keeps the largest extent it had over this long (0: each
                                 // frame's own). A vessel's LiDAR cluster shrank from 3.5 m to an edge's 0.1 m and
                                 // back frame by frame, merging its box with the next and splitting it, and the
                                 // detour flipped sides (tuning seed 31 run 286); 10 s helped there, but with
                                 // keep_side put the hull on the AUV in pyhajarvi_map.yaml: shipped off [s]
  double clear_time = 2.0;       // one in the sensor's view but not in the frame, or one not yet confirmed, is
                                 // dropped after missing this long (0: at the first such frame). A low buoy drops out
                                 // of the lowest layer's frames now and then as the boat pitches; dropped at once, the
                                 // detour round it went and came back scan by scan (tuning seed 32 run 274: the hull
                                 // on it) [s]
  double sensor_ahead = 1.5;     // the sensor ahead of the reference point (sim lidar/mount: on the bow) [m]
  double sensor_aperture = deg2rad(275.0);  // its horizontal field of view, centred on the bow (275 deg) [rad]
  double sensor_near = 12.0;     // nearer than this to the sensor a low object passes under its lowest layer or
                                 // lies in its hull box (perception hull_box): not seen even in the aperture. The
                                 // MRS1000's lowest layer, 2.5 deg down from 1 m above the water, passes over a
                                 // 0.5 m buoy (the envelope's lowest) nearer than 11.4 m; at 8 m such buoys were
                                 // dropped 8-11 m off and planned through [m]
  static const ParamTable<ObstacleMemoryParams>& table();
  void validate() const;
};

class ObstacleMemory {
 public:
  explicit ObstacleMemory(const ObstacleMemoryParams& p = {});
  void setParams(const ObstacleMemoryParams& p);
  // One frame's targets at time t (finite geometry), seen from a vehicle at `position` heading `yaw` (NED).
  void update(const std::vector<SbbObstacle>& seen, const Eigen::Vector2d& position, double yaw, double t);
  // What is planned round at time t: the last frame's targets and the obstacles kept out of view; nothing when
  // the last frame is older than `timeout`.
  std::vector<SbbObstacle> active(double t) const;
  // How many of those the sensor does not see now (kept from memory).
  int remembered() const { return remembered_; }
  
 private:
  struct Kept {
    SbbObstacle o;
    double seen_t = 0.0;
    int frames = 0;
    double extent = 0.0;    // the largest extent held (extent_hold), and when it was seen
    double extent_t = 0.0;
    double missed_t = -1.0;  // when it was first missed in the sensor's view (< 0: not missed since last seen)
  };
  bool inView(const Eigen::Vector2d& p, const Eigen::Vector2d& position, double yaw) const;

  ObstacleMemoryParams p_;
  std::vector<Kept> kept_;
  int remembered_ = 0;
  double frame_t_ = -1e300;
};

}  // namespace guidance
}  // namespace offshore_gnc
