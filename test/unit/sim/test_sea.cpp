// What the sea does to the sensors, each effect against its parameter over many frames or pings: the mounts'
// wave motion, whitecap and spray returns and dropouts on the LiDAR; surface and bottom reverberation, mooring
// lines, hull undersides and volume clutter on the sonar (docs/simulation.md, "The LiDAR on the water", "The
// sonar in the water").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/sim/sensors.h"
#include "offshore_gnc/sim/simulation.h"

using namespace offshore_gnc;
using namespace offshore_gnc::sim;

namespace {
struct Moments {
  double n = 0, s = 0, s2 = 0;
  void add(double v) { ++n, s += v, s2 += v * v; }
  double mean() const { return s / n; }
  double sd() const { return std::sqrt(std::max(0.0, s2 / n - mean() * mean())); }
};
int returns(const LidarScan& s, int layer = -1) {
  int n = 0;
  for (int l = 0; l < s.layers; ++l)
    if (layer < 0 || l == layer)
      for (int b = 0; b < s.beams; ++b) n += std::isfinite(s.ranges[std::size_t(l) * s.beams + b]);
  return n;
}
models::EnvironmentParams windOnly(double speed) {
  models::EnvironmentParams p;
  p.wind_speed = speed;
  return p;
}
}  // namespace

TEST(SeaOnTheLidar, TheMountRollsPitchesAndHeavesWithTheHullAndItsImuReportsIt) {
  Scenario sc;
  sc.sea = models::seaState("moderate");
  UsvSimulation::Config cfg;
  cfg.lidar.sea.spray_rate = 0.0;
  UsvSimulation sim(sc, cfg);
  Moments roll, pitch, imu_error, heave;
  for (int k = 0; k < 60000; ++k) {  // 600 s at rest
    const auto& o = sim.step();
    if (!o.lidar) continue;
    const VehicleState& s = sim.state();
    roll.add(s.roll);
    pitch.add(s.pitch);
    heave.add(s.position.z());
    imu_error.add(sim.scan().roll - s.roll);  // the mount has no yaw: the sensor's roll is the hull's
  }
  // Hs 1 m, Tp 5 s (39 m waves, slopes of some 5 deg) on the 8 m x 2.5 m hull: the drifting boat turns with the
  // wind, its roll and pitch share the tilt as it does
  EXPECT_GT(std::hypot(roll.sd(), pitch.sd()), deg2rad(2.0));
  EXPECT_NEAR(4 * heave.sd(), 1.0, 0.35);  // it heaves with the waves, a little less (averaged over its length)
  EXPECT_NEAR(imu_error.sd(), deg2rad(0.2), deg2rad(0.03));  // the IMU's noise, nothing else
  EXPECT_NEAR(imu_error.mean(), 0.0, deg2rad(0.02));
}

TEST(SeaOnTheLidar, WhitecapsReturnTheirFractionOfTheBeamsOnTheWaterAndLayersSweepIt) {
  // A flat sea under a gale (no waves: the fraction alone) and under a breeze; the -2.5 deg layer meets the water
  // 22.9 m away on every beam, the others never.
  for (const double wind : {20.0, 6.7}) {
    const models::Environment env(windOnly(wind));
    LidarConfig c;
    c.sea.dropout = 0.0;
    c.sea.spray_rate = 0.0;
    c.mount = {0.0, 0.0, -1.0};
    Lidar lidar(c, World{}, 5, &env);
    LidarScan s;
    Moments fraction;
    int upper = 0;
    VehicleState v;
    for (int k = 0; k < 400; ++k) {  // frames 2.9 s apart: each finds the whitecaps anew
      v.t = 2.9 * k;
      v.position.x() = 7.0 * k;  // and over other water
      lidar.scan(v, s);
      fraction.add(double(returns(s, 0)) / s.beams);
      upper += returns(s) - returns(s, 0);
    }
    EXPECT_NEAR(fraction.mean(), models::whitecapFraction(wind), 0.25 * models::whitecapFraction(wind) + 0.001)
        << "wind " << wind;
    EXPECT_EQ(upper, 0);
  }
  // In the moderate sea the hull's pitch and roll bring the 0 deg layer down onto the water too.
  Scenario sc;
  sc.sea = models::seaState("moderate");
  sc.sea.wind_speed = 20.0;  // whitecaps enough to see where the layers meet the water
  UsvSimulation::Config cfg;
  cfg.lidar.sea.spray_rate = 0.0;
  UsvSimulation sim(sc, cfg);
  int level = 0;
  for (int k = 0; k < 30000; ++k)
    if (sim.step().lidar) level += returns(sim.scan(), 1);
  EXPECT_GT(level, 100);
}

TEST(SeaOnTheLidar, SprayReturnsArePoissonAboutTheBowAndGrowWithTheSeaAndSpeed) {
  models::EnvironmentParams p;
  p.wave_height = 1.0;  // one unit of sea
  p.wave_period = 5.0;
  const models::Environment env(p);
  LidarConfig c;
  c.sea.dropout = 0.0;
  Lidar lidar(c, World{}, 7, &env);
  LidarScan s;
  Moments count;
  VehicleState v;
  for (int k = 0; k < 2000; ++k) {
    v.t = 0.08 * k;
    lidar.scan(v, s);
    count.add(returns(s));
    for (int l = 0; l < s.layers; ++l)
      for (int b = 0; b < s.beams; ++b) {
        const float r = s.ranges[std::size_t(l) * s.beams + b];
        if (!std::isfinite(r)) continue;
        EXPECT_LE(r, c.sea.spray_range + 1e-6);
        EXPECT_LE(std::abs(s.azimuth[b]), c.sea.spray_sector / 2 + c.step);
      }
  }
  EXPECT_NEAR(count.mean(), c.sea.spray_rate, 0.05 * c.sea.spray_rate);
  EXPECT_NEAR(count.sd() * count.sd(), count.mean(), 0.2 * count.mean());  // Poisson: variance = mean
  // at 4 m/s in calm water as much again (the bow's own spray)
  Lidar calm(c, World{}, 7, nullptr);
  v.velocity.x() = 4.0;
  Moments fast;
  for (int k = 0; k < 500; ++k) {
    calm.scan(v, s);
    fast.add(returns(s));
  }
  EXPECT_NEAR(fast.mean(), c.sea.spray_rate, 0.1 * c.sea.spray_rate);
}

TEST(SeaOnTheLidar, DropoutsLoseTheirShareOfTheReturns) {
  World w;
  w.shorelines.push_back({{30, -100}, {30, 100}, {40, 100}, {40, -100}});  // a shore 30 m ahead
  LidarConfig c;
  c.sea.dropout = 0.05;
  Lidar lidar(c, w, 9);
  c.sea.dropout = 0.0;
  Lidar all(c, w, 9);
  LidarScan s;
  all.scan(VehicleState{}, s);
  const int full = returns(s);
  long kept = 0;
  for (int k = 0; k < 50; ++k) {
    lidar.scan(VehicleState{}, s);
    kept += returns(s);
  }
  EXPECT_NEAR(1.0 - double(kept) / (50.0 * full), 0.05, 0.005);
}

namespace {
// Mean intensity per bin over `pings` beams straight ahead (head angle 0) of a head at `depth`.
std::vector<double> meanBeam(const SonarConfig& c, const World& w, const models::Environment* env, double depth,
                             int pings) {
  Sonar sonar(c, w, 11, env);
  VehicleState s;
  s.position.z() = depth;
  std::vector<double> sum(c.bins, 0.0);
  int n = 0;
  SonarBeamReading b;
  for (int k = 0; n < pings; ++k) {
    s.t = 0.05 * k;
    sonar.ping(s, b);
    if (std::abs(angleDiff(b.bearing, 0.0)) > c.step / 2) continue;
    for (int i = 0; i < c.bins; ++i) sum[i] += b.intensities[i];
    ++n;
  }
  for (double& v : sum) v /= n;
  return sum;
}
SonarConfig levelHead() {
  SonarConfig c;
  c.mount = Eigen::Vector3d::Zero();
  c.tilt = 0.0;
  c.water.clutter_density = 0.0;
  return c;
}
}  // namespace

TEST(SeaOnTheSonar, SurfaceAndBottomReverberationWhereTheVerticalBeamReachesThem) {
  // A level head 2 m deep: at 9 m the surface is 12.8 deg up (inside the 35 deg beam), at 3 m it is 42 deg up.
  const SonarConfig c = levelHead();
  const models::Environment wind(windOnly(8.0));
  const auto calm = meanBeam(c, World{}, nullptr, 2.0, 300);
  const auto rough = meanBeam(c, World{}, &wind, 2.0, 300);
  Sonar probe(c, World{}, 1);
  const int near = probe.binOfRange(3.0), far = probe.binOfRange(9.0);
  // the mean at 9 m: speckle plus surface_reverb x U^2 x the two-way pattern at 12.8 deg x attenuation
  const double x = std::asin(2.0 / 9.0) / (0.5 * c.vertical_width);
  const double expected = c.noise_level + c.water.surface_reverb * 64.0 * std::pow(10.0, -0.6 * x * x) * std::exp(-0.27);
  EXPECT_NEAR(rough[far], expected, 0.15 * expected);
  EXPECT_NEAR(calm[far], c.noise_level, 0.15 * c.noise_level);
  EXPECT_NEAR(rough[near], c.noise_level, 0.2 * c.noise_level);  // the surface is out of the beam there
  // a bottom 3 m below: its reverberation rises as the beam reaches it
  World bottom;
  bottom.bottom_depth = 5.0;
  const auto b = meanBeam(c, bottom, nullptr, 2.0, 300);
  EXPECT_GT(b[far], 2.0 * c.noise_level);
  EXPECT_NEAR(b[near], c.noise_level, 0.2 * c.noise_level);
  // tilted 15 deg down (the default) the surface stays out of the beam, the bottom comes nearer
  SonarConfig tilted = c;
  tilted.tilt = deg2rad(15.0);
  EXPECT_LT(meanBeam(tilted, World{}, &wind, 2.0, 300)[far], 0.4 * rough[far]);
  EXPECT_GT(meanBeam(tilted, bottom, nullptr, 2.0, 300)[probe.binOfRange(6.0)], 2.0 * b[probe.binOfRange(6.0)]);
}

TEST(SeaOnTheSonar, AMooringLineEchoesInOneOrTwoBeamsAndAHullFromBelow) {
  World w;
  w.buoys.push_back({{8.0, 0.0}, 0.6, 1.0, 0.5});  // 8 m ahead, moored to a bottom 6 m down
  w.bottom_depth = 6.0;
  SonarConfig c = levelHead();
  c.noise_level = 0.0;
  c.near_field = 0.0;
  Sonar sonar(c, w, 13);
  VehicleState s;
  s.position.z() = 2.5;  // the buoy's underside is 15 deg up: in the beam, 7.7 m away
  SonarBeamReading b;
  int line_beams = 0, hull_beams = 0;
  for (int k = 0; k < 50; ++k) {  // one sweep
    sonar.ping(s, b);
    line_beams += b.intensities[sonar.binOfRange(8.0)] > 50;
    hull_beams += b.intensities[sonar.binOfRange(std::hypot(7.4, 2.0))] > 100;
  }
  EXPECT_GE(line_beams, 1);
  EXPECT_LE(line_beams, 2);  // thinner than the 3 deg beam
  EXPECT_GE(hull_beams, 3);  // 1.2 m wide: 8.6 deg plus the beam
}

TEST(SeaOnTheSonar, VolumeClutterHasItsStatedDensityAndFalseAlarms) {
  SonarConfig c = levelHead();
  c.water.clutter_density = 0.02;
  c.noise_level = 0.0;
  c.near_field = 0.0;
  Sonar sonar(c, World{}, 17);
  SonarBeamReading b;
  Moments scatterers;
  int alarms = 0;
  const int pings = 20000;
  for (int k = 0; k < pings; ++k) {
    sonar.ping(VehicleState{}, b);
    scatterers.add(std::count_if(b.intensities.begin(), b.intensities.end(), [](std::uint8_t v) { return v > 0; }));
    alarms += *std::max_element(b.intensities.begin(), b.intensities.end()) > 90;
  }
  // per ping: density x beam width x vertical width x range^3 / 3 (0.21 at the defaults) scatterers, and those
  // above the detection threshold 90 of their exponential intensities (mean 60): 22 %
  const double mean = c.water.clutter_density * c.beam_width * c.vertical_width * std::pow(c.range, 3) / 3.0;
  EXPECT_NEAR(scatterers.mean(), mean, 0.08 * mean);
  EXPECT_NEAR(double(alarms) / pings, mean * std::exp(-90.0 / c.water.clutter_echo), 0.2 * mean * 0.22);
}
