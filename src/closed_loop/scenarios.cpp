#include "offshore_gnc/closed_loop/scenarios.h"

#include "offshore_gnc/guidance/paths.h"

namespace offshore_gnc {
namespace closed_loop {
namespace scenarios {

ClosedLoopConfig usvStraight(bool adaptive_crab) {
  ClosedLoopConfig c;
  // 5 waypoints, 40 m apart, heading north; the current sets east (across the path).
  for (int i = 0; i < 5; ++i) c.path.emplace_back(40.0 * i, 0.0, 0.0);
  c.start = Eigen::Vector3d(0.0, 0.0, 0.0);
  c.current = Eigen::Vector2d(0.0, 0.2);
  c.los.acceptance_radius = 16.0;  // 2 L_USV
  c.los.adaptive_crab = adaptive_crab;
  c.los.surge_speed = 1.5;
  c.los.crab_gain = 0.004;
  c.los.final_radius = 2.0;        // as config/guidance/usv.yaml: stop at the last waypoint, slow down before it
  c.los.approach_distance = 60.0;
  c.los.approach_speed = 0.2;
  c.max_time = 400.0;
  return c;
}

ClosedLoopConfig usvBuoy(bool adaptive_crab) {
  ClosedLoopConfig c = usvStraight(adaptive_crab);
  c.path = guidance::straightLine(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(160, 0, 0), 10.0);
  guidance::SbbObstacle buoy;
  buoy.id = 1;
  buoy.origin = Eigen::Vector2d(80.0, 1.0);
  buoy.length = buoy.width = 2.0;
  c.obstacles = {buoy};
  c.sbb.safety_x = 10.0;
  c.sbb.safety_y = 6.0;
  c.sbb.corridor = 3.0;  // half beam (1.5 m) + tracking error at the corners
  c.sbb.approach = 25.0;  // the 8 m waterjet boat needs a run-in to the rear corner
  c.los.detour_radius = 2.0;  // as config/guidance/usv.yaml: box corners are reached, route waypoints on R = 16 m
  return c;
}

ClosedLoopConfig usvNearBuoy(bool adaptive_crab) {
  ClosedLoopConfig c = usvBuoy(adaptive_crab);
  c.path = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(40, 0, 0), Eigen::Vector3d(80, 0, 0), Eigen::Vector3d(120, 0, 0)};
  c.obstacles[0].origin = Eigen::Vector2d(25.0, 0.5);
  c.obstacles[0].length = c.obstacles[0].width = 1.2;
  return c;
}

ClosedLoopConfig usvHoldFromRest() {
  ClosedLoopConfig c = usvStraight(true);
  c.path = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
  c.hold_until = 300.0;  // as long as the USV waits for the AUV in the default mission
  return c;
}

ClosedLoopConfig usvShortTransit() {
  ClosedLoopConfig c = usvStraight(true);
  c.path = guidance::straightLine(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(42, -38, 0), 10.0);
  return c;
}

ClosedLoopConfig auvCoverage(bool adaptive_crab) {
  ClosedLoopConfig c;
  c.path = guidance::lawnmower(Eigen::Vector2d(0, 0), 0.0, 30.0, 10.0, 5.0, 3.0);
  c.start = Eigen::Vector3d(0.0, 0.0, 3.0);
  c.current = Eigen::Vector2d(0.0, 0.2);
  c.los.kp = 0.0333;  // Table 4.3 LOS
  c.los.ki = 0.0;
  c.los.acceptance_radius = 0.5;  // sphere: the holonomic Girona500 turns on the spot; the passed rule covers misses
  c.los.sphere = true;
  c.los.adaptive_crab = adaptive_crab;
  c.los.surge_speed = 0.3;
  c.max_time = 900.0;
  return c;
}

}  // namespace scenarios
}  // namespace closed_loop
}  // namespace offshore_gnc
