#pragma once
// The USV's hull as the rest of the system needs it: its waterline outline about the reference point, for judging
// contact (sim/contact.h), for keeping a hold clear of obstacles (guidance) and for the recovery's bow distance
// (mission). One outline, read from the vehicle config (`vehicle/outline` in config/usv.yaml). ROS-free.
#include <Eigen/Core>

#include <vector>

#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace models {

// The hull's waterline outline, body frame (x forward, y starboard) about the vehicle's reference point [m].
struct HullFootprint {
  // The 8 m aColor USV (Table 3.3 gives the length only): the reference point is the model's pivot, the jets
  // 2.4 m aft of it at the transom (+0.3 m), the bow 5.3 m ahead, a 2.6 m beam assumed, tapering over the bow's
  // last 1.5 m. vehicle/outline in config/usv.yaml, x0, y0, x1, y1, ...
  std::vector<double> outline{5.3, 0.0, 3.8, 1.3, -2.7, 1.3, -2.7, -1.3, 3.8, -1.3};
  static const ParamTable<HullFootprint>& table();
  void validate() const;  // at least 3 corners, finite (ConfigError)
  // The outline placed at (north, east) with heading yaw, NED.
  std::vector<Eigen::Vector2d> placed(const Eigen::Vector2d& ne, double yaw) const;
  // How far the outline reaches from the reference point: ahead (the bow), astern, abeam (either side) [m].
  double ahead() const;
  double astern() const;
  double abeam() const;
};

}  // namespace models
}  // namespace offshore_gnc
