#pragma once
// guidance::SbbObstacle <-> offshore_gnc/TargetArray, for the nodelets that pass obstacles between them (LiDAR
// targets into guidance, the mission's keep-clear into guidance, guidance's obstacles into the mission).
#include <cstdint>
#include <vector>

#include "offshore_gnc/TargetArray.h"
#include "offshore_gnc/guidance/sbb.h"

namespace offshore_gnc {
namespace guidance_ros {

inline std::vector<guidance::SbbObstacle> obstaclesOf(const TargetArray& m) {
  std::vector<guidance::SbbObstacle> obstacles;
  for (const auto& t : m.targets) {
    guidance::SbbObstacle o;
    o.id = t.id;
    o.origin = Eigen::Vector2d(t.origin.x, t.origin.y);
    o.length = t.length;
    o.width = t.width;
    o.boxed = !t.unboxed;
    obstacles.push_back(o);
  }
  return obstacles;
}

// Each obstacle a target of `source` (its origin also its centroid and nearest point: all that is known of it).
inline TargetArray targetsOf(const std::vector<guidance::SbbObstacle>& obstacles, const std_msgs::Header& header,
                             std::uint8_t source) {
  TargetArray a;
  a.header = header;
  for (const auto& o : obstacles) {
    Target t;
    t.header = header;
    t.id = o.id;
    t.source = source;
    t.origin.x = t.centroid.x = t.nearest.x = o.origin.x();
    t.origin.y = t.centroid.y = t.nearest.y = o.origin.y();
    t.length = o.length;
    t.width = o.width;
    t.unboxed = !o.boxed;
    a.targets.push_back(t);
  }
  return a;
}

}  // namespace guidance_ros
}  // namespace offshore_gnc
