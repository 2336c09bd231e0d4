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

const ParamTable<BridgeParams>& BridgeParams::table() {
  using P = BridgeParams;
  static const ParamTable<P> t = ParamTable<P>()
      .string("cola2_namespace", &P::cola2_namespace,
              "COLA2's robot namespace: <ns>/navigator/navigation, <ns>/controller/thruster_setpoints")
      .integer("thrusters", &P::thrusters, 1, 16, "thrusters of the vehicle")
      .numbers("thruster_order", &P::thruster_order, 0, 0, 15, "",
               "COLA2 setpoint i is ours thruster_order[i]: a permutation of 0..thrusters-1 (empty: the identity)")
      .numbers("thruster_sign", &P::thruster_sign, 0, -1, 1, "", "times thruster_sign[i], 1 or -1 (empty: all 1)")
      .number("watchdog_timeout", &P::watchdog_timeout, 0.05, 30.0, "s",
              "no thruster setpoints of ours for this long: zero to COLA2's thrusters")
      .integer("neutral_messages", &P::neutral_messages, 1, 1000, "zero setpoints sent when the watchdog trips")
      .number("startup_timeout", &P::startup_timeout, 0.0, 600.0, "s",
              "warn when COLA2's navigation is still silent this long after start (0: never)")
      .string("base_frame", &P::base_frame, "the AUV's body frame");
  return t;
}

ThrusterMapping BridgeParams::mapping() const {
  ThrusterMapping m = ThrusterMapping::identity(thrusters);
  if (!thruster_order.empty()) m.order.assign(thruster_order.begin(), thruster_order.end());
  if (!thruster_sign.empty()) m.sign = thruster_sign;
  m.validate(thrusters);
  return m;
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
