#pragma once
// The Girona500's COLA2 conventions, ROS-free: our thruster order and signs -> COLA2's thruster_setpoints
// order, and COLA2's navigation (NavSts: NED in the frame of its own origin, plus latitude/longitude) -> our
// vehicle state in our map_ned, whatever origin each side uses.
#include <optional>
#include <string>
#include <vector>

#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace cola2 {

// COLA2 setpoint i = sign[i] * ours[order[i]]; both lists as long as the thruster count.
struct ThrusterMapping {
  std::vector<int> order;
  std::vector<double> sign;
  static ThrusterMapping identity(int n);
  void validate(int thrusters) const;  // throws ConfigError: a permutation of 0..n-1, signs +-1
  // nullopt when `ours` has the wrong size or a value that is not finite; values clamped to -1..1.
  std::optional<std::vector<double>> apply(const std::vector<double>& ours) const;
};

// The Cola2Bridge nodelet's parameters. An empty thruster_order or thruster_sign is the identity's (ours in COLA2's
// order, signs +1) for `thrusters`: its sizes and values depend on that count, checked by mapping().
struct BridgeParams {
  std::string cola2_namespace = "/girona500";
  int thrusters = 5;
  std::vector<double> thruster_order, thruster_sign;
  double watchdog_timeout = 1.0;  // [s]
  int neutral_messages = 5;
  double startup_timeout = 10.0;  // [s]
  std::string base_frame = "auv/base_link";
  static const ParamTable<BridgeParams>& table();
  ThrusterMapping mapping() const;  // validated: throws ConfigError
};

struct NavSts {  // the fields of cola2_msgs/NavSts the bridge uses
  double stamp = 0.0;
  double latitude = 0.0, longitude = 0.0;            // global_position [deg]
  double origin_latitude = 0.0, origin_longitude = 0.0;
  double north = 0.0, east = 0.0, depth = 0.0;        // in the frame of `origin` [m]
  double u = 0.0, v = 0.0, w = 0.0;                   // body velocity FRD [m/s]
  double roll = 0.0, pitch = 0.0, yaw = 0.0;          // [rad]
  double p = 0.0, q = 0.0, r = 0.0;                   // [rad/s]
};

// COLA2's estimate in our local frame. The position comes from COLA2's NED through its origin, so the two
// stacks may use different origins; when COLA2 has no origin (0, 0) its NED is taken as ours. Returns nullopt
// (the caller counts it) for a non-finite or out-of-range message.
std::optional<VehicleState> toVehicleState(const NavSts& n, const geo::LocalNed& ours);

}  // namespace cola2
}  // namespace offshore_gnc
