#pragma once
// One vehicle on a given route, ROS-free: its stack (closed_loop/stacks.h: simulator, navigation, perception,
// guidance pipeline, control loop, all from the vehicle's config files) fed a path instead of the mission's,
// in a scenario built from the route (start, current, buoys in the world the LiDAR sees). Used by the gtests
// and `./scripts/bench tracking`, so both measure what the vehicles run.
#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

#include "offshore_gnc/closed_loop/stacks.h"
#include "offshore_gnc/guidance/metrics.h"
#include "offshore_gnc/sim/world.h"

namespace offshore_gnc {
namespace closed_loop {

struct ClosedLoopConfig {
  std::vector<Eigen::Vector3d> path;                 // NED waypoints
  Eigen::Vector3d start = Eigen::Vector3d::Zero();   // start position (NED)
  double start_yaw = 0.0;
  std::string sea_state = "calm";                    // models::seaState: wind, waves (its current is replaced:)
  Eigen::Vector2d current = Eigen::Vector2d(0.0, 0.2);  // NED current [m/s] (0.2 m/s cross current)
  std::vector<sim::Buoy> buoys;                      // in the simulated world (the USV's LiDAR sees them)
  double max_time = 600.0;                           // [s]
  std::uint64_t seed = 1;
  // true: guidance and control see the navigation estimate (USV: GPS-compass; AUV: the INS estimate), as on the
  // vehicle; false: the true state (isolates the controller).
  bool navigation = true;
  double hold_until = 90.0;  // station keeping is measured from 30 s after the end of the path to this [s]
  std::string config_dir = "config";                 // the vehicles' configuration files
  std::function<void(UsvStackConfig&)> usv;          // changes to the loaded USV configuration
  std::function<void(AuvStackConfig&)> auv;          // changes to the loaded AUV configuration
};

struct ClosedLoopResult {
  guidance::TrackingMetrics metrics;   // over guidance's samples in path following
  bool finished = false;               // station keeping reached
  double time = 0.0;                   // time to the end of the path [s]
  double min_clearance = 1e9;          // closest approach to a buoy's surface [m]
  std::size_t inside_box_samples = 0;  // samples inside a safety box that cuts the path (must be 0)
  std::size_t rejected_commands = 0;   // actuator commands the simulator refused (NaN; must be 0)
  double hold_error = 0.0;             // largest distance to the last waypoint 30 s to hold_until into station keeping [m]
  std::vector<Eigen::Vector3d> track;  // true positions at the guidance rate
  std::vector<Eigen::Vector3d> planned_path;  // the last path planned around a box (else the route)
  std::string status;
};

ClosedLoopResult runUsv(const ClosedLoopConfig& cfg);
ClosedLoopResult runAuv(const ClosedLoopConfig& cfg, const std::string& model = "girona500");

}  // namespace closed_loop
}  // namespace offshore_gnc
