#include "offshore_gnc/closed_loop/scenarios.h"

#include "offshore_gnc/guidance/paths.h"

namespace offshore_gnc {
namespace closed_loop {
namespace scenarios {

ClosedLoopConfig usvStraight(bool adaptive_crab) {
  ClosedLoopConfig c;
  // 5 waypoints, 40 m apart, heading north; the current sets east (across the path).
  for (int i = 0; i < 5; ++i) c.path.emplace_back(40.0 * i, 0.0, 0.0);
  c.current = Eigen::Vector2d(0.0, 0.2);
  c.usv = [adaptive_crab](UsvStackConfig& u) {
    u.guidance.los.adaptive_crab = adaptive_crab;  // false: no crab compensation at all (the thesis' eq. 4.9)
    u.guidance.los.measured_crab = u.guidance.los.measured_crab && adaptive_crab;
  };
  c.max_time = 400.0;
  return c;
}

ClosedLoopConfig usvBuoy(bool adaptive_crab) {
  ClosedLoopConfig c = usvStraight(adaptive_crab);
  c.path = guidance::straightLine(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(160, 0, 0), 10.0);
  sim::Buoy buoy;
  buoy.centre = Eigen::Vector2d(80.0, 1.0);
  buoy.radius = 1.0;
  c.buoys = {buoy};
  return c;
}

ClosedLoopConfig usvNearBuoy(bool adaptive_crab) {
  ClosedLoopConfig c = usvBuoy(adaptive_crab);
  c.path = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(40, 0, 0), Eigen::Vector3d(80, 0, 0), Eigen::Vector3d(120, 0, 0)};
  c.buoys[0].centre = Eigen::Vector2d(25.0, 0.5);
  c.buoys[0].radius = 0.6;
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
  c.auv = [adaptive_crab](AuvStackConfig& a) { a.guidance.los.adaptive_crab = adaptive_crab; };
  c.max_time = 900.0;
  return c;
}

}  // namespace scenarios
}  // namespace closed_loop
}  // namespace offshore_gnc
