// Sensor simulators: geometry of returns, NaN for no return, sonar echo bins, noise-free readings, seeds, the DVL's
// noise and rate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/sim/sensors.h"
#include "offshore_gnc/sim/simulation.h"

using namespace offshore_gnc;
using namespace offshore_gnc::sim;

namespace {
LidarConfig quietLidar() {
  LidarConfig c;
  c.range_sigma = 0.0;
  c.sea.dropout = 0.0;  // geometry only: every return kept
  c.mount = {0.0, 0.0, -1.0};  // 1 m above the water, at the vehicle's origin
  return c;
}
int beamOf(const LidarScan& s, double az) {
  return static_cast<int>(std::lround((az - s.azimuth.front()) / (s.azimuth[1] - s.azimuth[0])));
}
float rangeAt(const LidarScan& s, int layer, double az) { return s.ranges[layer * s.beams + beamOf(s, az)]; }
}  // namespace

TEST(Lidar, GeometryOfTheMrs1000) {
  World w;
  Lidar lidar(quietLidar(), w, 1);
  LidarScan s;
  lidar.scan(VehicleState{}, s);
  EXPECT_EQ(s.layers, 4);
  EXPECT_EQ(s.beams, 1101);  // 275 deg / 0.25 deg + 1
  EXPECT_NEAR(rad2deg(s.azimuth.front()), -137.5, 1e-9);
  EXPECT_NEAR(rad2deg(s.azimuth.back()), 137.5, 1e-6);
  EXPECT_NEAR(rad2deg(s.elevation.back() - s.elevation.front()), 7.5, 1e-4);
  // empty world: every beam is "no return"
  EXPECT_TRUE(std::all_of(s.ranges.begin(), s.ranges.end(), [](float r) { return std::isnan(r); }));
}

TEST(Lidar, BuoyAppearsAtItsRangeAndBearing) {
  World w;
  w.buoys.push_back({{0.0, 20.0}, 0.5, 3.0});  // 20 m east
  Lidar lidar(quietLidar(), w, 1);
  LidarScan s;
  lidar.scan(VehicleState{}, s);  // heading north: the buoy is 90 deg to starboard
  const double az = deg2rad(90.0);
  for (int l = 0; l < 4; ++l) EXPECT_NEAR(rangeAt(s, l, az) * std::cos(s.elevation[l]), 19.5, 1e-4) << "layer " << l;
  const Eigen::Vector3d p = s.pointFrd(1, beamOf(s, az));
  EXPECT_NEAR(p.x(), 0.0, 1e-3);
  EXPECT_NEAR(p.y(), 19.5, 1e-3);
  EXPECT_TRUE(std::isnan(rangeAt(s, 1, 0.0)));  // straight ahead: nothing
  EXPECT_TRUE(std::isnan(rangeAt(s, 1, deg2rad(80.0))));

  VehicleState east;
  east.yaw = deg2rad(90.0);  // now the buoy is dead ahead
  lidar.scan(east, s);
  EXPECT_NEAR(rangeAt(s, 1, 0.0), 19.5, 1e-4);
  EXPECT_TRUE(std::isnan(rangeAt(s, 1, az)));
}

TEST(Lidar, UpperLayerPassesOverALowBuoyAndDownLayerEndsOnWater) {
  World w;
  w.buoys.push_back({{20.0, 0.0}, 0.5, 1.0});  // 1 m high, sensor 1 m above water
  Lidar lidar(quietLidar(), w, 1);
  LidarScan s;
  lidar.scan(VehicleState{}, s);
  EXPECT_FALSE(std::isnan(rangeAt(s, 0, 0.0)));  // -2.5 deg: hits the buoy before the water (22.9 m)
  EXPECT_FALSE(std::isnan(rangeAt(s, 1, 0.0)));
  EXPECT_TRUE(std::isnan(rangeAt(s, 3, 0.0)));   // +5 deg: 2.7 m up at the buoy, over its top

  World far;
  far.buoys.push_back({{40.0, 0.0}, 0.5, 1.0});  // beyond the -2.5 deg layer's water intersection
  Lidar l2(quietLidar(), far, 1);
  l2.scan(VehicleState{}, s);
  EXPECT_TRUE(std::isnan(rangeAt(s, 0, 0.0)));
  EXPECT_NEAR(rangeAt(s, 1, 0.0), 39.5, 1e-4);
}

TEST(Lidar, OutOfRangeAndShorelinesAndVessels) {
  World w;
  w.buoys.push_back({{100.0, 0.0}, 0.5, 3.0});  // beyond 64 m
  w.shorelines.push_back({{-10, -30}, {10, -30}, {10, -40}, {-10, -40}});  // land 30 m to the west
  Vessel v;
  v.centre = {-15.0, 0.0};  // astern-ish, outside the 275 deg aperture? no: 180 deg is in the 85 deg blind sector
  w.vessels.push_back(v);
  Lidar lidar(quietLidar(), w, 1);
  LidarScan s;
  lidar.scan(VehicleState{}, s);
  EXPECT_TRUE(std::isnan(rangeAt(s, 1, 0.0)));
  EXPECT_NEAR(rangeAt(s, 3, deg2rad(-90.0)) * std::cos(s.elevation[3]), 30.0, 1e-4);  // land is high
  const int n = std::count_if(s.ranges.begin(), s.ranges.end(), [](float r) { return !std::isnan(r); });
  EXPECT_GT(n, 0);
  VehicleState south;
  south.yaw = kPi;  // turn around: the vessel (8 m x 3 m box, long axis north) is 11 m ahead
  lidar.scan(south, s);
  EXPECT_NEAR(rangeAt(s, 1, 0.0), 11.0, 1e-4);
}

TEST(Lidar, AVesselUnderWayIsSeenWhereItIsAtTheFramesTime) {
  World w;
  Vessel v;  // 20 m ahead, 10 m to port, crossing to starboard at 2 m/s
  v.centre = {20.0, -10.0};
  v.length = 6.0;
  v.width = 2.0;
  v.motion.kind = VesselMotion::Kind::kCourse;
  v.motion.course = kPi / 2;
  v.motion.speed = 2.0;
  w.vessels.push_back(v);
  Lidar lidar(quietLidar(), w, 1);
  LidarScan s;
  VehicleState x;  // heading north; azimuth clockwise from the bow
  lidar.scan(x, s);
  EXPECT_NEAR(rangeAt(s, 1, std::atan2(-10.0, 19.0)), std::hypot(19.0, 10.0), 0.05);  // its near side, 1 m closer
  EXPECT_TRUE(std::isnan(rangeAt(s, 1, 0.0)));  // nothing dead ahead yet
  x.t = 5.0;  // 10 m on: across the bow
  lidar.scan(x, s);
  EXPECT_NEAR(rangeAt(s, 1, 0.0), 19.0, 1e-4);
  EXPECT_TRUE(std::isnan(rangeAt(s, 1, std::atan2(-10.0, 19.0))));
}

TEST(Lidar, NoiseIsDeterministicForASeed) {
  World w;
  w.shorelines.push_back({{30, -100}, {30, 100}, {40, 100}, {40, -100}});
  LidarConfig c = quietLidar();
  c.range_sigma = 0.05;
  Lidar a(c, w, 42), b(c, w, 42), other(c, w, 43);
  LidarScan sa, sb, so;
  a.scan(VehicleState{}, sa);
  b.scan(VehicleState{}, sb);
  other.scan(VehicleState{}, so);
  ASSERT_EQ(sa.ranges.size(), sb.ranges.size());
  for (std::size_t i = 0; i < sa.ranges.size(); ++i)
    if (!std::isnan(sa.ranges[i])) {
      EXPECT_EQ(sa.ranges[i], sb.ranges[i]);
    }
  const float r = rangeAt(sa, 1, 0.0), ro = rangeAt(so, 1, 0.0);
  EXPECT_NE(r, ro);
  EXPECT_NEAR(r, 30.0, 0.3);
}

TEST(Lidar, RejectsBadConfig) {
  LidarConfig c;
  c.max_range = 0.1;  // below min_range
  EXPECT_THROW(Lidar(c, World{}, 1), ConfigError);
  c = LidarConfig{};
  c.layer_elevation.pop_back();
  EXPECT_THROW(Lidar(c, World{}, 1), ConfigError);
}

namespace {
SonarConfig quietSonar() {
  SonarConfig c;
  c.mount = Eigen::Vector3d::Zero();
  c.water.clutter_density = 0.0;  // geometry only: no volume clutter
  c.tilt = 0.0;                   // a level head
  return c;
}
// Pings until the head points at `angle` (signed, clockwise from forward) and returns that beam.
SonarBeamReading beamAt(Sonar& sonar, const VehicleState& s, double angle) {
  SonarBeamReading b;
  for (int i = 0; i < 200; ++i) {
    sonar.ping(s, b);
    if (std::abs(angleDiff(b.bearing, angle)) < sonar.config().step / 2) return b;
  }
  ADD_FAILURE() << "head never reached " << angle;
  return b;
}
int peakBin(const SonarBeamReading& b, int from) {
  return static_cast<int>(std::max_element(b.intensities.begin() + from, b.intensities.end()) - b.intensities.begin());
}
}  // namespace

TEST(Sonar, TargetEchoAtItsBin) {
  World w;
  w.targets.push_back({{5.0, 0.0, 2.0}, 0.3});  // 5 m ahead at the head's depth
  Sonar sonar(quietSonar(), w, 3);
  VehicleState s;
  s.position.z() = 2.0;
  const auto b = beamAt(sonar, s, 0.0);
  ASSERT_EQ(b.intensities.size(), 200u);
  EXPECT_NEAR(b.range_resolution, 0.05, 1e-12);
  const int far_from = sonar.binOfRange(2.0);
  EXPECT_NEAR(peakBin(b, far_from), sonar.binOfRange(4.7), 1);
  EXPECT_GT(b.intensities[peakBin(b, far_from)], 150);
  // a beam 30 deg off: no echo above the speckle beyond the near field
  Sonar sonar2(quietSonar(), w, 3);
  const auto off = beamAt(sonar2, s, deg2rad(30.0));
  EXPECT_LT(off.intensities[peakBin(off, far_from)], 120);
}

TEST(Sonar, WallEchoAndNearFieldClutter) {
  World w;
  w.walls.push_back({{8.0, -20.0}, {8.0, 20.0}});
  Sonar sonar(quietSonar(), w, 4);
  const auto b = beamAt(sonar, VehicleState{}, 0.0);
  const int from = sonar.binOfRange(2.0);
  EXPECT_NEAR(peakBin(b, from), sonar.binOfRange(8.0), 1);
  double near = 0, mid = 0;
  for (int i = 0; i < sonar.binOfRange(1.0); ++i) near += b.intensities[i];
  for (int i = sonar.binOfRange(3.0); i < sonar.binOfRange(7.0); ++i) mid += b.intensities[i];
  near /= sonar.binOfRange(1.0);
  mid /= sonar.binOfRange(7.0) - sonar.binOfRange(3.0);
  EXPECT_GT(near, 2.0 * mid);
  EXPECT_GT(mid, 1.0);  // speckle, not silence
}

TEST(Sonar, SectorScanBackAndForthWithStatusBits) {
  Sonar sonar(quietSonar(), World{}, 5);
  SonarBeamReading b;
  int reversals = 0;
  double lo = 10, hi = -10;
  bool seen_cw = false, seen_ccw = false;
  for (int i = 0; i < 150; ++i) {
    sonar.ping(VehicleState{}, b);
    const double a = angleDiff(b.bearing, 0.0);
    lo = std::min(lo, a);
    hi = std::max(hi, a);
    EXPECT_TRUE(b.head_status & kHeadReady);
    EXPECT_TRUE(b.head_status & kMotorOn);
    EXPECT_FALSE(b.head_status & kFault);
    (b.head_status & kScanCw ? seen_cw : seen_ccw) = true;
    if (b.head_status & kSectorReverse) ++reversals;
    EXPECT_GE(b.bearing, 0.0);
    EXPECT_LT(b.bearing, 2 * kPi);
  }
  EXPECT_NEAR(rad2deg(lo), -45.0, 1.8);
  EXPECT_NEAR(rad2deg(hi), 45.0, 1.8);
  EXPECT_TRUE(seen_cw && seen_ccw);
  EXPECT_GE(reversals, 2);  // 150 beams of 1.8 deg over a 90 deg sector: 50 beams per sweep
}

TEST(GpsCompass, FixAndHeading) {
  GpsCompassConfig c;
  c.position_sigma = c.position_white_sigma = c.altitude_sigma = c.heading_sigma = 0.0;
  c.antenna = {1.0, 0.0, -2.0};
  geo::LocalNed frame(geo::kPyhajarviOrigin);
  GpsCompass gps(c, frame, 1);
  VehicleState s;
  s.position = {100.0, -50.0, 0.0};
  s.yaw = deg2rad(90.0);
  const auto r = gps.measure(s);
  const Eigen::Vector3d ned = frame.toNed(r.fix);
  EXPECT_NEAR(ned.x(), 100.0, 1e-6);
  EXPECT_NEAR(ned.y(), -49.0, 1e-6);  // antenna 1 m forward, vessel heading east
  EXPECT_NEAR(r.fix.alt_m, 2.0, 2e-3);  // + earth curvature over 112 m (d^2 / 2R)
  EXPECT_NEAR(r.heading, deg2rad(90.0), 1e-12);
}

TEST(GpsCompass, DopplerVelocityAndRateOfTurnAtTheAntenna) {
  GpsCompassConfig c;
  c.position_sigma = c.position_white_sigma = c.altitude_sigma = c.heading_sigma = 0.0;
  c.velocity_sigma = c.rate_sigma = 0.0;
  c.antenna = {2.0, 0.5, -2.5};
  geo::LocalNed frame(geo::kPyhajarviOrigin);
  GpsCompass gps(c, frame, 1);
  VehicleState s;
  s.yaw = deg2rad(40.0);
  s.velocity = {2.0, 0.3, 0.0};
  s.angular_rate.z() = 0.1;
  const auto r = gps.measure(s);
  // independent check: centred difference of the antenna's NED position under the same rigid-body motion
  auto antenna_at = [&](double t) {
    const double yaw = s.yaw + s.angular_rate.z() * t;  // constant body velocity: integrate it exactly enough
    Eigen::Vector2d p = Eigen::Vector2d::Zero();
    const int n = 200;
    for (int i = 0; i < n; ++i) {
      const double y = s.yaw + s.angular_rate.z() * (t * (i + 0.5) / n);
      p += t / n * Eigen::Vector2d(std::cos(y) * 2.0 - std::sin(y) * 0.3, std::sin(y) * 2.0 + std::cos(y) * 0.3);
    }
    return Eigen::Vector2d(p.x() + std::cos(yaw) * 2.0 - std::sin(yaw) * 0.5,
                           p.y() + std::sin(yaw) * 2.0 + std::cos(yaw) * 0.5);
  };
  const double h = 1e-3;
  const Eigen::Vector2d v = (antenna_at(h) - antenna_at(-h)) / (2 * h);
  EXPECT_NEAR((r.velocity_ned - v).norm(), 0.0, 1e-6);
  EXPECT_NEAR(r.rate_of_turn, 0.1, 1e-12);
}

TEST(GpsCompass, PositionErrorIsSlowGaussMarkov) {
  GpsCompassConfig c;
  c.position_sigma = 0.3;
  c.position_tau = 60.0;
  c.position_white_sigma = c.altitude_sigma = c.heading_sigma = 0.0;
  c.jump_interval = c.outage_interval = 0.0;  // the slow error alone (jumps: test_nav_sensors.cpp)
  geo::LocalNed frame(geo::kPyhajarviOrigin);
  GpsCompass gps(c, frame, 7);
  VehicleState s;
  std::vector<double> e;  // north error at 10 Hz over 600 correlation times
  for (int i = 0; i < 360000; ++i) {
    s.t = 0.1 * i;
    e.push_back(frame.toNed(gps.measure(s).fix).x());
  }
  auto corr = [&](std::size_t lag) {
    double num = 0, den = 0;
    for (std::size_t i = 0; i + lag < e.size(); ++i) num += e[i] * e[i + lag];
    for (double x : e) den += x * x;
    return num / den * e.size() / (e.size() - lag);
  };
  double var = 0;
  for (double x : e) var += x * x;
  EXPECT_NEAR(std::sqrt(var / e.size()), 0.3, 0.045);   // stationary 1-sigma
  EXPECT_NEAR(corr(1), std::exp(-0.1 / 60.0), 0.005);   // fix to fix: almost the same error
  EXPECT_NEAR(corr(600), std::exp(-1.0), 0.12);         // one correlation time apart
}

TEST(DepthAndAhrs, PhysicalReadings) {
  DepthConfig dc;
  dc.sigma_pa = 0;
  DepthSensor d(dc, 1);
  VehicleState s;
  s.position.z() = 10.0;
  EXPECT_NEAR(d.measure(s).pressure_pa, 101325.0 + 1000.0 * 9.80665 * 10.0, 1e-6);
  EXPECT_NEAR(d.depthOf(d.measure(s).pressure_pa), 10.0, 1e-9);
  AhrsConfig ac;
  ac.attitude_sigma = ac.heading_sigma = ac.gyro_sigma = ac.accel_sigma = 0;
  ac.heading_bias_sigma = ac.heading_drift_sigma = 0;
  Ahrs ahrs(ac, 1);
  s.yaw = 1.0;
  const auto r = ahrs.measure(s, Eigen::Vector3d::Zero());
  EXPECT_NEAR(r.specific_force.z(), -9.80665, 1e-9);  // at rest, level: the reaction to gravity, up
  EXPECT_NEAR(r.yaw, 1.0, 1e-12);
}

TEST(InsEstimate, DriftGrowsLikeARandomWalk) {
  InsConfig c;
  c.position_sigma = 0;
  InsEstimate ins(c, 9);
  VehicleState s;
  double sum_sq = 0;
  for (int i = 0; i <= 3600; ++i) {
    s.t = i;
    ins.estimate(s);
  }
  sum_sq = ins.drift().squaredNorm();
  // expected |drift|^2 = 2 * 0.02^2 * 3600 = 2.88 m^2; accept a wide band for one realisation
  EXPECT_GT(sum_sq, 0.01);
  EXPECT_LT(sum_sq, 30.0);
}

namespace {
DvlConfig unbiased() {  // the noise alone (the run's bias: test_nav_sensors.cpp)
  DvlConfig c;
  c.scale_sigma = c.misalignment_sigma = c.offset_sigma = 0.0;
  return c;
}
// Sample mean and SD (n - 1) of each body axis of n DVL readings of one state.
void dvlStats(Dvl& dvl, const VehicleState& s, int n, Eigen::Vector3d& mean, Eigen::Vector3d& sd) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum_sq = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d e = dvl.measure(s)->velocity - s.velocity;
    sum += e;
    sum_sq += e.cwiseProduct(e);
  }
  mean = sum / n;
  sd = ((sum_sq - n * mean.cwiseProduct(mean)) / (n - 1)).cwiseSqrt();
}
}  // namespace

TEST(Dvl, BodyVelocityOverGroundWithItsNoise) {
  VehicleState s;
  s.t = 12.5;
  s.yaw = deg2rad(60.0);  // body frame: the heading does not enter
  s.velocity = {1.2, -0.3, 0.1};
  const int n = 40000;
  for (double sigma : {0.02, 0.1}) {
    DvlConfig c = unbiased();
    c.velocity_sigma = sigma;
    Dvl dvl(c, 11);
    const DvlReading r = *dvl.measure(s);
    EXPECT_EQ(r.t, 12.5);
    EXPECT_EQ(r.velocity_sigma, sigma);
    Eigen::Vector3d mean, sd;
    dvlStats(dvl, s, n, mean, sd);
    for (int k = 0; k < 3; ++k) {
      // standard errors: mean sigma / sqrt(n) (0.5 % of sigma), SD sigma / sqrt(2 n) (0.35 %)
      EXPECT_NEAR(mean[k], 0.0, 5 * sigma / std::sqrt(n)) << "axis " << k << ", sigma " << sigma;
      EXPECT_NEAR(sd[k], sigma, 0.02 * sigma) << "axis " << k << ", sigma " << sigma;
    }
  }
  EXPECT_EQ(DvlConfig{}.velocity_sigma, 0.02);  // the defaults: 0.02 m/s at 5 Hz
  EXPECT_EQ(DvlConfig{}.rate_hz, 5.0);
  // noise-free: exactly the true body velocity
  DvlConfig quiet = unbiased();
  quiet.velocity_sigma = 0.0;
  Dvl exact(quiet, 1);
  EXPECT_EQ(exact.measure(s)->velocity, s.velocity);
  // one seed, one noise sequence
  Dvl a(DvlConfig{}, 5), b(DvlConfig{}, 5), other(DvlConfig{}, 6);
  const Eigen::Vector3d va = a.measure(s)->velocity;
  EXPECT_EQ(va, b.measure(s)->velocity);
  EXPECT_NE(va, other.measure(s)->velocity);
  DvlConfig bad;
  bad.velocity_sigma = -0.1;
  EXPECT_THROW(Dvl(bad, 1), ConfigError);
  bad = DvlConfig{};
  bad.rate_hz = 0.0;
  EXPECT_THROW(Dvl(bad, 1), ConfigError);
}

TEST(Dvl, AtItsRateOnTheGirona500AndNotOnTheAColor) {
  const Scenario sc;  // open water at the default origin
  AuvSimulation::Config cfg;
  ASSERT_EQ(cfg.dvl.rate_hz, 5.0);
  AuvSimulation g(sc, cfg);
  EXPECT_TRUE(g.hasDvl());
  EXPECT_TRUE(g.setThrusters({-1, -1, 0, 0, 0}));  // under way: the readings follow the true velocity
  int dvl = 0;
  double last_t = 0.0;
  for (int i = 0; i < 1000; ++i) {  // 10 s at dt 0.01
    const auto& o = g.step();
    if (!o.dvl) continue;
    ++dvl;
    EXPECT_NEAR(o.dvl->t - last_t, 0.2, 1e-9);
    last_t = o.dvl->t;
    EXPECT_EQ(o.dvl->t, g.state().t);
    EXPECT_LT((o.dvl->velocity - g.state().velocity).norm(), 6 * cfg.dvl.velocity_sigma);
  }
  EXPECT_EQ(dvl, 50);
  EXPECT_GT(g.state().velocity.x(), 0.2);

  cfg.dvl.rate_hz = 2.0;  // configurable
  AuvSimulation slow(sc, cfg);
  dvl = 0;
  for (int i = 0; i < 1000; ++i) dvl += slow.step().dvl.has_value();
  EXPECT_EQ(dvl, 20);

  cfg.auv = models::AuvParams::aColor();  // no DVL on the aColor
  AuvSimulation a(sc, cfg);
  EXPECT_FALSE(a.hasDvl());
  dvl = 0;
  for (int i = 0; i < 1000; ++i) dvl += a.step().dvl.has_value();
  EXPECT_EQ(dvl, 0);
}

TEST(Faults, TheSimulationsSilenceEachSensorOnlyWhileItsFaultLasts) {
  const Scenario sc;
  UsvSimulation::Config ucfg;
  ucfg.faults = FaultPlan::parse("gps@2+3 lidar@4+2");
  UsvSimulation usv(sc, ucfg);
  int gps_in = 0, gps_out = 0, lidar_in = 0, lidar_out = 0;
  for (int i = 0; i < 800; ++i) {  // 8 s
    const auto& o = usv.step();
    const double t = usv.state().t;
    const bool gps_fault = t >= 2.0 && t < 5.0, lidar_fault = t >= 4.0 && t < 6.0;
    if (o.gps) ++(gps_fault ? gps_in : gps_out);
    if (o.lidar) ++(lidar_fault ? lidar_in : lidar_out);
  }
  EXPECT_EQ(gps_in, 0);
  EXPECT_GE(gps_out, 45);  // 10 Hz over the other 5 s
  EXPECT_EQ(lidar_in, 0);
  EXPECT_GT(lidar_out, 0);

  AuvSimulation::Config acfg;
  acfg.faults = FaultPlan::parse("sonar@1+1 depth@3+1 dvl@5+1");
  AuvSimulation auv(sc, acfg);
  int silenced = 0, sonar_back = 0, depth_back = 0, dvl_back = 0;
  for (int i = 0; i < 800; ++i) {
    const auto& o = auv.step();
    const double t = auv.state().t;
    const bool sonar_f = t >= 1 && t < 2, depth_f = t >= 3 && t < 4, dvl_f = t >= 5 && t < 6;
    silenced += (sonar_f && o.sonar) + (depth_f && o.depth.has_value()) + (dvl_f && o.dvl.has_value());
    if (t >= 6.0) sonar_back += o.sonar, depth_back += o.depth.has_value(), dvl_back += o.dvl.has_value();
  }
  EXPECT_EQ(silenced, 0);
  EXPECT_GT(sonar_back, 0);  // each is back after its fault
  EXPECT_GT(depth_back, 0);
  EXPECT_GT(dvl_back, 0);
}

// The propulsion faults as the CAN gateway would see them (there is no bus in simulation): the port unit stops
// (its jet idles with the bucket neutral, its status frames stop, it is reported not answering after the gateway's
// jet_timeout), or the bus goes off (both units stop, the NMEA 2000 GPS-compass is silent, the bus state says so
// at once); the last command reaches the jets again when the fault ends.
TEST(Faults, AStoppedUnitOrABusOffStopsItsJetsAndIsReportedAsTheGatewayWould) {
  const Scenario sc;
  UsvSimulation::Config cfg;
  cfg.faults = FaultPlan::parse("jet@5+5 bus_off@15+5");
  UsvSimulation usv(sc, cfg);
  ASSERT_TRUE(usv.setCommand({0.5, 0.0, 0.0}));
  int reports = 0, port_status_in = 0, gps_in = 0, starboard_status = 0;
  double port_silent_at = NAN, port_back_at = NAN, bus_off_at = NAN, bus_on_at = NAN;
  for (int i = 0; i < 2500; ++i) {  // 25 s
    const auto& o = usv.step();
    const double t = usv.state().t;
    const GatewayReport& g = usv.gateway();
    if (o.gateway_changed) {
      ++reports;
      if (!g.answering[0] && std::isnan(port_silent_at)) port_silent_at = t;
      if (g.answering[0] && !std::isnan(port_silent_at) && std::isnan(port_back_at)) port_back_at = t;
      if (g.bus_off && std::isnan(bus_off_at)) bus_off_at = t;
      if (!g.bus_off && !std::isnan(bus_off_at) && std::isnan(bus_on_at)) bus_on_at = t;
    }
    const bool jet_f = t >= 5.0 && t < 10.0, bus_f = t >= 15.0 && t < 20.0;
    port_status_in += (jet_f || bus_f) && o.jet_status[0];
    starboard_status += !bus_f && o.jet_status[1];
    gps_in += bus_f && o.gps.has_value();
    if (std::abs(t - 9.99) < 1e-6) {  // the port jet has idled, its bucket neutral; the starboard one pushes on
      EXPECT_NEAR(usv.model().jet(0).rpm, cfg.usv.rpm_min, 50.0);
      EXPECT_NEAR(usv.model().jet(0).bucket, 0.0, 1e-9);
      EXPECT_GT(usv.model().jet(1).rpm, cfg.usv.rpm_min + 200.0);
      EXPECT_GT(usv.model().jet(1).bucket, 0.5);
    }
    if (std::abs(t - 19.99) < 1e-6) {  // both idle
      for (int j = 0; j < 2; ++j) EXPECT_NEAR(usv.model().jet(j).bucket, 0.0, 1e-9) << j;
    }
  }
  EXPECT_NEAR(port_silent_at, 5.0 + cfg.jet_timeout, 0.011);
  EXPECT_NEAR(port_back_at, 10.0, 0.011);
  EXPECT_NEAR(bus_off_at, 15.0, 0.011);
  EXPECT_NEAR(bus_on_at, 20.0, 0.011);
  EXPECT_EQ(reports, 1 + 2 + 3);  // the first step; port silent, back; bus off, both silent, bus on (both answer)
  EXPECT_EQ(port_status_in, 0);
  EXPECT_EQ(gps_in, 0);
  EXPECT_GT(starboard_status, 150);  // 10 Hz outside the bus-off
  // the last command reaches both jets again
  EXPECT_GT(usv.model().jet(0).rpm, cfg.usv.rpm_min + 200.0);
  EXPECT_NEAR(usv.model().jet(0).bucket, usv.model().jet(1).bucket, 1e-9);
}

// The collision fault: nothing while the USV is still, then a barge broadside across its course, where its bow
// reaches it in the configured time at its speed, the first time it is under way in the window; gone at the end.
TEST(Faults, TheCollisionObstacleAppearsAheadOnceUnderWayAndGoesAtTheEnd) {
  const Scenario sc;  // open water, heading north
  UsvSimulation::Config cfg;
  cfg.lidar.range_sigma = 0.0;
  cfg.faults = FaultPlan::parse("collision@2+40");
  UsvSimulation usv(sc, cfg);
  double appeared = NAN, gone = NAN;
  for (int i = 0; i < 5000 && std::isnan(gone); ++i) {
    if (i == 500) {
      ASSERT_TRUE(usv.setCommand({1.0, 0.0, 0.0}));  // still for 5 s, then full ahead
    }
    usv.step();
    const double t = usv.state().t;
    if (usv.faultObstacle() && std::isnan(appeared)) {
      appeared = t;
      const double speed = usv.state().velocity.head<2>().norm();
      EXPECT_GE(speed, cfg.collision.min_speed);
      EXPECT_LT(speed, cfg.collision.min_speed + 0.05);  // at the first moment under way
      const Vessel& b = *usv.faultObstacle();
      EXPECT_NEAR(std::abs(std::sin(b.yaw - usv.state().yaw)), 1.0, 0.02);  // broadside across the course
      const double face = cfg.usv.length / 2 + speed * cfg.collision.time_ahead;  // 4 + 6 x 0.8 m
      EXPECT_NEAR((b.centre - usv.state().position.head<2>()).norm(), face + b.width / 2, 1e-6);
    }
    if (!usv.faultObstacle() && !std::isnan(appeared)) gone = t;
  }
  ASSERT_FALSE(std::isnan(appeared));
  EXPECT_GT(appeared, 5.0);
  EXPECT_NEAR(gone, 42.0, 0.011);

  // the LiDAR sees it ahead at that distance while it is there, and not before or after
  UsvSimulation::Config still = cfg;
  still.collision.min_speed = 0.0;  // "under way" from the start: there at once, at the bow
  UsvSimulation seen(sc, still);
  float ahead = NAN;
  for (int i = 0; i < 300 && std::isnan(ahead); ++i)
    if (seen.step().lidar && seen.state().t > 2.0) ahead = rangeAt(seen.scan(), 1, 0.0);  // level layer, dead ahead
  EXPECT_NEAR(ahead, cfg.usv.length / 2 - cfg.lidar.mount.x(), 0.05);
  UsvSimulation before(sc, still);
  float nothing = 0.0f;
  for (int i = 0; i < 150; ++i)
    if (before.step().lidar) nothing = rangeAt(before.scan(), 1, 0.0);
  EXPECT_TRUE(std::isnan(nothing));  // before its window: open water
}

// The nav fault silences the navigation's own inputs: the AHRS, the DVL and the INS-like estimate.
TEST(Faults, TheNavFaultSilencesTheAhrsTheDvlAndTheEstimate) {
  const Scenario sc;
  AuvSimulation::Config cfg;
  cfg.faults = FaultPlan::parse("nav@2+2");
  AuvSimulation auv(sc, cfg);
  int in = 0, ahrs_out = 0, dvl_out = 0, odom_out = 0, depth_in = 0;
  for (int i = 0; i < 600; ++i) {
    const auto& o = auv.step();
    const double t = auv.state().t;
    const bool f = t >= 2.0 && t < 4.0;
    if (f) in += o.ahrs.has_value() + o.dvl.has_value() + o.odom.has_value(), depth_in += o.depth.has_value();
    else ahrs_out += o.ahrs.has_value(), dvl_out += o.dvl.has_value(), odom_out += o.odom.has_value();
  }
  EXPECT_EQ(in, 0);
  EXPECT_GT(depth_in, 0);  // the depth sensor is not the navigation's: it goes on
  EXPECT_GT(ahrs_out, 0);
  EXPECT_GT(dvl_out, 0);
  EXPECT_GT(odom_out, 0);
}
