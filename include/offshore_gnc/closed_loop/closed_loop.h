#pragma once
// ROS-free closed loop: the simulator's plant (sim::UsvSimulation / sim::AuvSimulation, with current) + LOS
// guidance (+ SBB planner) + the vehicle controller, at the control rate. Used by the gtests and by
// `./scripts/bench tracking`, so both measure the same thing.
#include <Eigen/Core>

#include <string>
#include <vector>

#include "offshore_gnc/control/vehicle_control.h"
#include "offshore_gnc/guidance/los.h"
#include "offshore_gnc/guidance/metrics.h"
#include "offshore_gnc/guidance/sbb.h"

namespace offshore_gnc {
namespace closed_loop {

struct ClosedLoopConfig {
  std::vector<Eigen::Vector3d> path;                 // NED waypoints
  Eigen::Vector3d start = Eigen::Vector3d::Zero();   // start position (NED)
  double start_yaw = 0.0;
  Eigen::Vector2d current = Eigen::Vector2d(0.0, 0.2);  // NED current [m/s] (0.2 m/s cross current)
  guidance::LosParams los;
  std::vector<guidance::SbbObstacle> obstacles;      // USV only: buoys (also placed in the simulated world)
  guidance::SbbParams sbb;
  double max_time = 600.0;                           // [s]
  double control_dt = 0.1;                           // [s]
  std::uint64_t seed = 1;
  // true: guidance and control see the navigation estimate from the simulated sensors, as on the vehicle (USV:
  // GPS-compass -> navigation::GpsNavigator; AUV: the INS estimate); false: the true state (isolates the controller).
  bool navigation = true;
  double hold_until = 90.0;  // station keeping is measured from 30 s after the end of the path to this [s]
};

struct ClosedLoopResult {
  guidance::TrackingMetrics metrics;   // over the samples in path-following mode
  bool finished = false;               // station keeping reached
  double time = 0.0;                   // time to the end of the path [s]
  double min_clearance = 1e9;          // closest approach to an obstacle's edge [m]
  std::size_t inside_box_samples = 0;  // samples inside a safety box (must be 0)
  std::size_t nan_outputs = 0;         // actuator outputs that were not finite (must be 0)
  double hold_error = 0.0;             // largest distance to the last waypoint 30 s to hold_until into station keeping [m]
  std::vector<Eigen::Vector3d> track;  // true positions at the control rate
  std::vector<Eigen::Vector3d> planned_path;
  std::string status;
};

ClosedLoopResult runUsv(const ClosedLoopConfig& cfg, const control::UsvControlParams& ctrl = control::UsvControlParams());
ClosedLoopResult runGirona500(const ClosedLoopConfig& cfg,
                              const control::Girona500ControlParams& ctrl = control::Girona500ControlParams());

}  // namespace closed_loop
}  // namespace offshore_gnc
