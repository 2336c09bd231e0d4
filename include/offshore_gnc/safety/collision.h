#pragma once
// Time to collision for the supervisor's `collision` rule (MOOS-IvP's allstop_ttc): how long until the vehicle,
// going on at its velocity over ground, touches an obstacle its LiDAR sees. Each obstacle is what perception
// reports (offshore_gnc/Target in local NED): its returns laid along their first -> last axis, `length` long and
// centred on eq. 4.3's origin, thickened by half its `width` (a capsule); without an axis, a disc of its larger
// extent (as the SBB planner takes it). The vehicle is a disc of `radius` about its position (half its length:
// head on, the bow touches first). The LiDAR gives no velocities, so obstacles are taken as still. ROS-free; NED.
// Whether a safe side exists comes from the SBB planner's safety boxes (safeSideExists).
#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <limits>
#include <vector>

namespace offshore_gnc {
namespace safety {

struct SeenObstacle {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // middle of its first and last return [m]
  Eigen::Vector2d axis = Eigen::Vector2d::Zero();    // first -> last (zero: unknown)
  double length = 0.0, width = 0.0;                  // along and across the axis [m]
};

struct Collision {
  double ttc = std::numeric_limits<double>::infinity();  // [s]; +inf: not closing on anything; NaN: bad state
  int obstacle = -1;                                     // the index of the one touched first
  double distance = std::numeric_limits<double>::infinity();  // travelled until then [m]
  std::size_t skipped = 0;                               // obstacles with non-finite or negative geometry
};

// position, velocity: the vehicle's over ground (NED) [m, m/s]; radius [m]. A non-finite position or velocity
// gives ttc NaN (the supervisor refuses and counts it); an obstacle already within reach counts as touched
// (ttc 0) while the vehicle closes on it, and not at all while it moves away.
Collision timeToCollision(const Eigen::Vector2d& position, const Eigen::Vector2d& velocity,
                          const std::vector<SeenObstacle>& obstacles, double radius);

// One of the SBB planner's safety boxes (offshore_gnc/SafetyBox) as the supervisor takes it.
struct SafetyBoxView {
  std::array<Eigen::Vector2d, 4> corners;  // in order around the box (rear-port, front-port, front-starboard, ...)
  bool cuts_path = false;                  // the box cuts the path's corridor: the planner goes round it
  bool blocked = false;                    // it found no side within its navigable corridor
};
// A safe side exists unless a box that cuts the path has none, or the vehicle is already inside one: its detour
// then starts behind it, with no room left to go round (a wide obstacle appearing close ahead).
bool safeSideExists(const std::vector<SafetyBoxView>& boxes, const Eigen::Vector2d& position);

}  // namespace safety
}  // namespace offshore_gnc
