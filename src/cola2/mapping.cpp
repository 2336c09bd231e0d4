// COLA2 conventions (include/offshore_gnc/cola2/mapping.h).
#include "offshore_gnc/cola2/mapping.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace cola2 {

ThrusterMapping ThrusterMapping::identity(int n) {
  ThrusterMapping m;
  for (int i = 0; i < n; ++i) {
    m.order.push_back(i);
    m.sign.push_back(1.0);
  }
  return m;
}

void ThrusterMapping::validate(int thrusters) const {
  if (static_cast<int>(order.size()) != thrusters || static_cast<int>(sign.size()) != thrusters)
    throw ConfigError("parameters 'thruster_order' and 'thruster_sign' need " + std::to_string(thrusters) +
                      " entries each (one per thruster)");
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < thrusters; ++i)
    if (sorted[i] != i) throw ConfigError("parameter 'thruster_order' must be a permutation of 0.." + std::to_string(thrusters - 1));
  for (double s : sign)
    if (s != 1.0 && s != -1.0) throw ConfigError("parameter 'thruster_sign' entries must be 1 or -1");
}

std::optional<std::vector<double>> ThrusterMapping::apply(const std::vector<double>& ours) const {
  if (ours.size() != order.size()) return std::nullopt;
  std::vector<double> out(ours.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    const double v = ours[static_cast<std::size_t>(order[i])];
    if (!std::isfinite(v)) return std::nullopt;
    out[i] = std::clamp(sign[i] * v, -1.0, 1.0);
  }
  return out;
}

std::optional<VehicleState> toVehicleState(const NavSts& n, const geo::LocalNed& ours) {
  const double vals[] = {n.stamp, n.origin_latitude, n.origin_longitude, n.north, n.east, n.depth, n.u, n.v, n.w,
                         n.roll, n.pitch, n.yaw, n.p, n.q, n.r};
  for (double v : vals)
    if (!std::isfinite(v)) return std::nullopt;
  if (std::abs(n.origin_latitude) > 90 || std::abs(n.origin_longitude) > 180) return std::nullopt;
  VehicleState s;
  s.t = n.stamp;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  if (n.origin_latitude != 0.0 || n.origin_longitude != 0.0) {
    offset = ours.toNed({n.origin_latitude, n.origin_longitude, 0.0});
    offset.z() = 0.0;  // depth is measured from the surface on both sides
    // (a translation between the two tangent planes: their axes differ by far less than a degree within km)
  }
  s.position = offset + Eigen::Vector3d(n.north, n.east, n.depth);
  s.roll = wrapAngle(n.roll);
  s.pitch = wrapAngle(n.pitch);
  s.yaw = wrapAngle(n.yaw);
  s.velocity = {n.u, n.v, n.w};
  s.angular_rate = {n.p, n.q, n.r};
  return s;
}

}  // namespace cola2
}  // namespace offshore_gnc
