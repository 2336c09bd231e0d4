// Traffic end to end (issue 33): a vessel under way in a scenario, moved by the USV simulator, seen by its LiDAR
// where it is at each frame, its targets (the LidarTargets nodelet's extraction and placing) followed by the tracker.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <string>
#include <vector>

#include "offshore_gnc/closed_loop/stacks.h"
#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/perception/lidar_targets.h"
#include "offshore_gnc/perception/target_tracker.h"
#include "offshore_gnc/sim/scenario.h"
#include "offshore_gnc/sim/simulation.h"

using namespace offshore_gnc;

TEST(Traffic, ACrossingVesselThroughTheSimulatedLidarIsTrackedAtItsVelocity) {
  // A calm lake, the USV at rest; an 8 x 3 m boat 25 m ahead crossing from port to starboard at 2 m/s.
  const sim::Scenario sc = sim::parseScenario(R"(
name: traffic
origin: {latitude: 61.4507, longitude: 23.7270}
usv: {start: {north: 0.0, east: 0.0}}
auv: {start: {north: -5.0, east: 5.0, depth: 2.0}}
obstacles:
  - {type: vessel, north: 25.0, east: -12.0, length: 8.0, width: 3.0, height: 1.5, course_deg: 90, speed: 2.0}
)",
                                              ".", "traffic.yaml");
  sim::UsvSimulation::Config cfg;  // the simulator's MRS1000: 3 cm range noise, 1 % dropouts
  sim::UsvSimulation usv(sc, cfg);
  perception::LidarTargetExtractor ex{perception::LidarConfig()};
  perception::TargetTracker tracker{perception::TrackerParams()};
  sim::PackedCloud cloud;
  const Eigen::Vector2d v(0.0, 2.0);
  int frames = 0;
  while (usv.state().t < 3.0 - 1e-9) {
    if (!usv.step().lidar) continue;
    const sim::LidarScan& scan = usv.scan();
    sim::packCloud(scan, cloud);
    const perception::LidarResult r = ex.extract(closed_loop::viewOf(cloud), perception::levelling(scan.roll, -scan.pitch));
    ASSERT_EQ(r.error, perception::CloudError::None) << r.message;
    const VehicleState& s = usv.state();  // the true pose: what is measured here is the tracker, not the navigation
    const Eigen::Isometry3d body = Eigen::Translation3d(s.position) * Eigen::AngleAxisd(s.yaw, Eigen::Vector3d::UnitZ());
    const Eigen::Isometry3d to_world = body * sim::sensorMount(cfg.lidar.mount, cfg.lidar.mount_yaw, false);
    std::vector<perception::Detection> d;
    for (const auto& g : r.targets) {
      const perception::TargetGeometry w = perception::transformed(g, to_world);
      perception::Detection det;
      det.position = w.centroid.head<2>();
      det.length = w.length;
      det.width = w.width;
      d.push_back(det);
    }
    ASSERT_TRUE(tracker.update(scan.t, d));
    ++frames;
  }
  EXPECT_EQ(frames, 37);  // 12.5 Hz for 3 s
  ASSERT_EQ(tracker.tracks().size(), 1u);
  const perception::Track& tr = tracker.tracks()[0];
  EXPECT_TRUE(tr.confirmed);
  EXPECT_LT((tr.velocity() - v).norm(), 0.2) << tr.velocity().transpose();
  // where the simulator has it now (the returns' centroid lies on its near side, 1.5 m short of its middle)
  const sim::VesselPose now = sim::vesselPose(sc.world.vessels[0], usv.state().t);
  EXPECT_LT((tr.position() - now.centre).norm(), 2.5) << tr.position().transpose() << " vs " << now.centre.transpose();
  EXPECT_GT(now.centre.y(), -12.0 + 5.9);  // and it has moved
}
