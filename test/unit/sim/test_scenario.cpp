// Scenario files: the shipped ones load; bad ones are refused with a message naming the key; the map image
// becomes an occupancy grid and shorelines the LiDAR sees.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/sim/scenario.h"
#include "offshore_gnc/sim/sensors.h"
#include "offshore_gnc/sim/simulation.h"

using namespace offshore_gnc;
using namespace offshore_gnc::sim;

namespace {
const char* kBase = R"(
name: t
origin: {latitude: 61.4507, longitude: 23.7270}
usv: {start: {north: 0.0, east: 0.0}}
auv: {start: {north: 5.0, east: 5.0, depth: 2.0}}
)";

// Expects parseScenario(text) to fail with a message that contains every `needles`.
void expectRefused(const std::string& text, const std::vector<std::string>& needles) {
  try {
    parseScenario(text, "config/scenarios", "test.yaml");
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const ConfigError& e) {
    for (const auto& n : needles) EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(Scenario, ShippedScenariosLoad) {
  const Scenario a = loadScenario("config/scenarios/pyhajarvi.yaml");
  EXPECT_EQ(a.name, "pyhajarvi");
  EXPECT_NEAR(a.origin.lat_deg, 61.4507, 1e-9);
  ASSERT_EQ(a.world.buoys.size(), 1u);
  EXPECT_NEAR(a.world.buoys[0].radius, 0.6, 1e-12);
  ASSERT_EQ(a.world.targets.size(), 1u);
  EXPECT_NEAR(a.world.targets[0].position.z(), 5.0, 1e-12);
  // the field day: 30 m^3/s through the estuary's 300 m^2 to the south, wind 3.7 m/s from SSW; a 7 m lake
  EXPECT_NEAR(a.sea.current_north, -0.1, 1e-12);
  EXPECT_NEAR(a.sea.wind_speed, 3.7, 1e-12);
  EXPECT_GT(a.sea.wave_height, 0.0);
  EXPECT_NEAR(a.world.bottom_depth, 7.0, 1e-12);
  EXPECT_NEAR(a.world.buoys[0].draft, 0.5, 1e-12);
  EXPECT_NEAR(loadScenario("config/scenarios/no_target.yaml").sea.wave_height, a.sea.wave_height, 1e-12);  // the same

  const Scenario m = loadScenario("config/scenarios/pyhajarvi_map.yaml");
  EXPECT_EQ(m.map.width, 200);
  EXPECT_EQ(m.map.height, 160);
  EXPECT_FALSE(m.world.shorelines.empty());
  EXPECT_EQ(m.world.vessels.size(), 1u);
  EXPECT_EQ(m.world.walls.size(), 1u);
}

TEST(Scenario, MapImageIsGeoReferenced) {
  const Scenario m = loadScenario("config/scenarios/pyhajarvi_map.yaml");
  EXPECT_FALSE(m.map.occupied({0.0, 0.0}));     // start: water
  EXPECT_TRUE(m.map.occupied({0.0, 90.0}));     // far east: land
  EXPECT_TRUE(m.map.occupied({-12.0, 50.0}));   // the pier
  EXPECT_TRUE(m.map.occupied({70.0, -35.0}));   // the island
  EXPECT_TRUE(m.map.occupied({99.0, -99.0}));   // north-west corner cell (row 159, col 0)
  EXPECT_EQ(m.map.data[159 * 200 + 0], 100);
  // the LiDAR sees the east shore: looking east from the start, the first return is the pier or the shore
  LidarConfig c;
  c.range_sigma = 0.0;
  Lidar lidar(c, m.world, 1);
  VehicleState s;
  s.yaw = deg2rad(90.0);
  LidarScan scan;
  lidar.scan(s, scan);
  const float r = scan.ranges[1 * scan.beams + scan.beams / 2];
  ASSERT_FALSE(std::isnan(r));
  EXPECT_GT(r, 50.0);
  EXPECT_LT(r, 64.0);
}

TEST(Scenario, RefusesUnknownMissingAndOutOfRange) {
  expectRefused(std::string(kBase) + "colour: red\n", {"'colour'", "not a known key"});
  expectRefused(std::string(kBase) + "obstacles:\n  - {type: buoy, north: 1, east: 40, radus: 1}\n",
                {"obstacles[0].radus"});
  expectRefused(std::string(kBase) + "obstacles:\n  - {type: buoy, north: 1, east: 40}\n",
                {"obstacles[0].radius", "missing"});
  expectRefused(std::string(kBase) + "obstacles:\n  - {type: buoy, north: 1, east: 40, radius: -2}\n",
                {"obstacles[0].radius", "out of range"});
  expectRefused(std::string(kBase) + "obstacles:\n  - {type: rock, north: 1, east: 40}\n", {"obstacles[0].type"});
  expectRefused(std::string(kBase) + "targets:\n  - {north: 1, east: 2, depth: .nan, radius: 0.5}\n",
                {"targets[0].depth"});
  expectRefused(std::string(kBase) + "current: {north: 9}\n", {"current/north", "out of range"});
  expectRefused(std::string(kBase) + "waves: {amplitude: 0.3}\n", {"waves.amplitude", "not a known key"});
  expectRefused(std::string(kBase) + "sea_state: gale\n", {"sea_state", "field_day"});
  expectRefused(std::string(kBase) + "bottom: {depth: 7, slope: 2}\n", {"bottom.slope"});
  expectRefused("name: t\norigin: {latitude: 61, longitude: 23}\nauv: {start: {north: 0, east: 0, depth: 1}}\n",
                {"'usv'", "missing"});
  expectRefused(std::string(kBase) + "map: {image: nothere.png, resolution: 1, north: 0, east: 0}\n",
                {"map.image", "nothere.png"});
  expectRefused("name: [\n", {"not valid YAML"});
}

TEST(Scenario, VesselsUnderWayOnACourseOrATrack) {
  const Scenario s = parseScenario(std::string(kBase) + R"(obstacles:
  - {type: vessel, north: 60, east: -40, length: 6, width: 2.5, course_deg: 90, speed: 2.0, gives_way: false}
  - {type: vessel, length: 5, width: 2, speed: 1.0, track: [{north: 30, east: 20}, {north: 30, east: 30}, {north: 40, east: 30}]}
  - {type: vessel, length: 5, width: 2, speed: 1.0, loop: true, track: [{north: -30, east: 0}, {north: -30, east: 10}]}
  - {type: vessel, north: 20, east: -20, length: 8, width: 3, yaw_deg: 45}
)",
                                   "config/scenarios", "test.yaml");
  ASSERT_EQ(s.world.vessels.size(), 4u);
  const Vessel& crossing = s.world.vessels[0];
  EXPECT_EQ(crossing.motion.kind, VesselMotion::Kind::kCourse);
  EXPECT_FALSE(crossing.motion.gives_way);
  const VesselPose c10 = vesselPose(crossing, 10.0);  // 20 m east of its start, heading east
  EXPECT_NEAR(c10.centre.x(), 60.0, 1e-9);
  EXPECT_NEAR(c10.centre.y(), -20.0, 1e-9);
  EXPECT_NEAR(c10.yaw, kPi / 2, 1e-9);

  const Vessel& track = s.world.vessels[1];
  EXPECT_EQ(track.motion.kind, VesselMotion::Kind::kTrack);
  EXPECT_TRUE(track.motion.gives_way);  // unless the file says otherwise
  EXPECT_NEAR(track.centre.x(), 30.0, 1e-9);  // it starts at the track's first point, heading along its first leg
  EXPECT_NEAR(track.yaw, kPi / 2, 1e-9);
  const VesselPose t15 = vesselPose(track, 15.0);  // 10 m along the first leg, 5 m up the second
  EXPECT_NEAR(t15.centre.x(), 35.0, 1e-9);
  EXPECT_NEAR(t15.centre.y(), 30.0, 1e-9);
  EXPECT_NEAR(t15.yaw, 0.0, 1e-9);
  const VesselPose end = vesselPose(track, 500.0);  // stopped at its last point
  EXPECT_NEAR(end.centre.x(), 40.0, 1e-9);
  EXPECT_NEAR(end.centre.y(), 30.0, 1e-9);

  const VesselPose looped = vesselPose(s.world.vessels[2], 25.0);  // 20 m round: 5 m along the first leg again
  EXPECT_NEAR(looped.centre.x(), -30.0, 1e-9);
  EXPECT_NEAR(looped.centre.y(), 5.0, 1e-9);
  const VesselPose back = vesselPose(s.world.vessels[2], 13.0);  // on the closing leg, heading west
  EXPECT_NEAR(back.centre.y(), 7.0, 1e-9);
  EXPECT_NEAR(back.yaw, -kPi / 2, 1e-9);

  const VesselPose moored = vesselPose(s.world.vessels[3], 300.0);
  EXPECT_NEAR(moored.centre.x(), 20.0, 1e-12);
  EXPECT_NEAR(moored.yaw, kPi / 4, 1e-12);
}

TEST(Scenario, RefusesAVesselUnderWayThatMakesNoSense) {
  const std::string v = std::string(kBase) + "obstacles:\n  - {type: vessel, length: 5, width: 2, ";
  expectRefused(v + "north: 50, east: 0, course_deg: 90, speed: -1}\n", {"obstacles[0].speed", "out of range"});
  expectRefused(v + "north: 50, east: 0, course_deg: 90, speed: .nan}\n", {"obstacles[0].speed", "out of range"});
  expectRefused(v + "north: 50, east: 0, course_deg: .nan, speed: 1}\n", {"obstacles[0].course_deg"});
  expectRefused(v + "north: 50, east: 0, course_deg: 90}\n", {"obstacles[0].speed", "missing"});
  expectRefused(v + "speed: 1, track: [{north: 50, east: 0}]}\n", {"obstacles[0].track", "at least 2 points"});
  expectRefused(v + "speed: 1, track: [{north: 50, east: 0}, {north: 50, east: .nan}]}\n",
                {"obstacles[0].track[1].east", "out of range"});
  expectRefused(v + "speed: 1, track: [{north: 50, east: 0}, {north: 50, east: 0}]}\n", {"obstacles[0].track", "no length"});
  expectRefused(v + "speed: 1, track: {north: 50, east: 0}}\n", {"obstacles[0].track", "list"});
  expectRefused(v + "north: 50, east: 0, speed: 1, track: [{north: 50, east: 0}, {north: 60, east: 0}]}\n",
                {"obstacles[0].north", "first point"});
  expectRefused(v + "north: 50, east: 0, speed: 1}\n", {"obstacles[0].speed", "course_deg or track"});
  expectRefused(v + "north: 50, east: 0, gives_way: false}\n", {"obstacles[0].gives_way", "under way"});
  expectRefused(v + "north: 50, east: 0, course_deg: 90, speed: 1, gives_way: perhaps}\n",
                {"obstacles[0].gives_way", "true or false"});
  expectRefused(v + "north: 50, east: 0, course_deg: 90, speed: 1, yaw_deg: 10}\n", {"obstacles[0].yaw_deg"});
  expectRefused(v + "north: 50, east: 0, course_deg: 90, speed: 1, loop: true}\n", {"obstacles[0].loop", "track"});
  expectRefused(v + "north: 50, east: 0, course_deg: 90, speed: 1, track: [{north: 50, east: 0}, {north: 60, east: 0}]}\n",
                {"obstacles[0].track", "course_deg"});
}

TEST(Scenario, RefusesImpossibleGeometry) {
  expectRefused(std::string(kBase) + "obstacles:\n  - {type: buoy, north: 0.2, east: 0.0, radius: 1}\n",
                {"usv.start", "inside"});
  expectRefused(std::string(kBase) + "walls:\n  - {north1: 3, east1: 3, north2: 3, east2: 3}\n",
                {"walls[0]", "zero length"});
  expectRefused(std::string(kBase) + "targets:\n  - {north: 1, east: 2, depth: 0.2, radius: 0.5}\n",
                {"targets[0].depth"});  // would stick out of the water
  expectRefused(std::string(kBase) + "bottom: {depth: 4}\ntargets:\n  - {north: 1, east: 2, depth: 3.8, radius: 0.5}\n",
                {"targets[0].depth", "below the bottom"});
  expectRefused(std::string(kBase) +
                    "map: {image: pyhajarvi_lake.png, resolution: 1, north: -60, east: -195}\n",  // start on land
                {"usv.start", "map"});
}

TEST(Simulation, SensorRatesAndNanCommandsRejected) {
  const Scenario sc = loadScenario("config/scenarios/pyhajarvi_map.yaml");
  UsvSimulation usv(sc, UsvSimulation::Config{});
  EXPECT_FALSE(usv.setCommand({NAN, 0, 0}));
  EXPECT_FALSE(usv.setCommand({0.5, 0, INFINITY}));
  EXPECT_EQ(usv.counters().get("rejected_commands"), 2u);
  EXPECT_TRUE(usv.setCommand({1.0, 0, 0}));
  int gps = 0, lidar = 0;
  for (int i = 0; i < 1000; ++i) {  // 10 s
    const auto& o = usv.step();
    gps += o.gps.has_value();
    lidar += o.lidar;
  }
  EXPECT_EQ(gps, 100);
  EXPECT_EQ(lidar, 125);
  EXPECT_NEAR(usv.state().t, 10.0, 1e-9);
  EXPECT_TRUE(isFinite(usv.state()));
  EXPECT_GT(usv.state().velocity.x(), 0.5);  // under way

  AuvSimulation auv(sc, AuvSimulation::Config{});
  EXPECT_FALSE(auv.setThrusters({0, 0, NAN, 0, 0}));
  EXPECT_FALSE(auv.setThrusters({0, 0, 0}));  // Girona500 has 5 thrusters
  EXPECT_EQ(auv.modelCounters().get("rejected_commands"), 2u);
  EXPECT_FALSE(auv.setRcChannels({1500, 1500, 1500}));
  EXPECT_EQ(auv.counters().get("rejected_commands"), 1u);
  EXPECT_TRUE(auv.setThrusters({-1, -1, 0, 0, 0}));  // eq. 3.18: a positive surge command pushes astern
  int sonar = 0, depth = 0, ahrs = 0;
  for (int i = 0; i < 1000; ++i) {
    const auto& o = auv.step();
    sonar += o.sonar;
    depth += o.depth.has_value();
    ahrs += o.ahrs.has_value();
  }
  EXPECT_EQ(sonar, 200);
  EXPECT_EQ(depth, 100);
  EXPECT_EQ(ahrs, 500);
  EXPECT_GT(auv.state().velocity.x(), 0.2);
}

TEST(Simulation, RcChannelsAndMixer) {
  EXPECT_FALSE(fromRcChannels({1500, 1500, 1500, 1500, 2500, 1500}));
  const auto r = fromRcChannels({1500, 1500, 1700, 1300, 1900, 1500});
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->heave, 0.5, 1e-12);
  EXPECT_NEAR(r->yaw, -0.5, 1e-12);
  EXPECT_NEAR(r->surge, 1.0, 1e-12);
  // the mixer drives the vehicle the commanded way: the wrench of the mixed commands has the input's signs
  for (const auto& p : {models::AuvParams::girona500(), models::AuvParams::aColor()}) {
    const models::AuvModel m(p);
    for (int axis = 0; axis < 4; ++axis) {
      AuvCommand c;
      (axis == 0 ? c.surge : axis == 1 ? c.sway : axis == 2 ? c.heave : c.yaw) = 0.5;
      const Eigen::VectorXd u = mixToThrusters(m.tcm(), c);
      Eigen::VectorXd f(u.size());
      for (int i = 0; i < u.size(); ++i) f[i] = m.thrust(i, u[i]);
      const Eigen::Vector4d w = m.tcm() * f;
      EXPECT_GT(w[axis], 0.0) << "axis " << axis;
    }
  }
  // aColor through RC channels: full forward moves the vehicle forward
  const Scenario sc = loadScenario("config/scenarios/pyhajarvi.yaml");
  AuvSimulation::Config cfg;
  cfg.auv = models::AuvParams::aColor();
  AuvSimulation a(sc, cfg);
  EXPECT_TRUE(a.setRcChannels({1500, 1500, 1500, 1500, 1900, 1500}));
  for (int i = 0; i < 500; ++i) a.step();
  EXPECT_GT(a.state().velocity.x(), 0.1);
}
