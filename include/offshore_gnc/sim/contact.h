#pragma once
// Contact between the USV's hull and what is in the water, for judging a mission as a skipper would: the hull's
// footprint (its outline in the body frame, turning with the boat) against each obstacle's true shape (buoys as
// discs, vessels as their boxes, the shorelines as polygons), not a reference point against circles. ROS-free.
#include <Eigen/Core>

#include <string>
#include <vector>

#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/sim/world.h"

namespace offshore_gnc {
namespace sim {

// The hull's waterline outline, body frame (x forward, y starboard) about the vehicle's reference point [m].
struct HullFootprint {
  // The 8 m aColor USV (Table 3.3 gives the length only): the reference point is the model's pivot, the jets
  // 2.4 m aft of it at the transom (+0.3 m), the bow 5.3 m ahead, a 2.6 m beam assumed, tapering over the bow's
  // last 1.5 m. vehicle/outline in config/usv.yaml, x0, y0, x1, y1, ...
  std::vector<double> outline{5.3, 0.0, 3.8, 1.3, -2.7, 1.3, -2.7, -1.3, 3.8, -1.3};
  static const ParamTable<HullFootprint>& table();
  void validate() const;  // at least 3 corners, finite (ConfigError)
  // The outline placed at (north, east) with heading yaw, NED.
  Polygon placed(const Eigen::Vector2d& ne, double yaw) const;
};

// Signed clearance [m] between the placed hull and the nearest obstacle of `world` (and `extra` vessels, e.g. a
// fault's): > 0 the gap, <= 0 contact (0 when the shapes touch or overlap; a buoy's centre inside the hull gives
// minus its radius). +inf when the world is empty. `nearest`, when given, names the nearest obstacle and where it is.
double hullClearance(const HullFootprint& hull, const Eigen::Vector2d& ne, double yaw, const World& world,
                     const std::vector<Vessel>& extra = {}, std::string* nearest = nullptr);

}  // namespace sim
}  // namespace offshore_gnc
