// The navigation sensors' field effects and their statistics: the GPS-compass's jumps and outages, the AHRS's
// heading bias and drift, the DVL's bias and bottom lock (docs/simulation.md, "Sensor models").
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/sim/sensors.h"
#include "offshore_gnc/sim/simulation.h"

using namespace offshore_gnc;
using namespace offshore_gnc::sim;

namespace {
double sd(const std::vector<double>& v) {
  double m = 0, q = 0;
  for (double x : v) m += x / v.size();
  for (double x : v) q += (x - m) * (x - m);
  return std::sqrt(q / (v.size() - 1));
}
double mean(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m += x / v.size();
  return m;
}
}  // namespace

TEST(GpsCompass, JumpsStepTheFixAndHoldForTheirDuration) {
  GpsCompassConfig c;
  c.position_sigma = c.position_white_sigma = c.altitude_sigma = 0.0;
  c.outage_interval = 0.0;
  c.jump_interval = 60.0;
  c.jump_sigma = 0.5;
  c.jump_duration = 10.0;
  const geo::LocalNed frame(geo::kPyhajarviOrigin);
  GpsCompass gps(c, frame, 3);
  VehicleState s;
  s.position = {20.0, -10.0, 0.0};
  const Eigen::Vector3d antenna = s.position + c.antenna;
  const double dt = 0.5, span = 2e5;
  int in_jump = 0, n = 0;
  std::vector<double> offsets, durations;
  double started = 0.0;
  Eigen::Vector2d last = Eigen::Vector2d::Zero();
  for (s.t = 0.0; s.t < span; s.t += dt, ++n) {
    const auto r = gps.measure(s);
    const Eigen::Vector2d j = gps.jump();
    if (n % 997 == 0) {  // the fix carries the jump (and nothing else here)
      EXPECT_LT((frame.toNed(r.fix).head<2>() - antenna.head<2>() - j).norm(), 1e-6);
    }
    if (!j.isZero()) ++in_jump;
    if (j != last) {  // a jump ended, began, or both (the next may begin as one ends)
      if (!last.isZero()) durations.push_back(s.t - started);
      if (!j.isZero()) {
        started = s.t;
        offsets.insert(offsets.end(), {j.x(), j.y()});
      }
    }
    last = j;
  }
  // a jump holds 10 s on average, the next comes 60 s after: 1/7 of the time in a jump (about 2900 jumps)
  EXPECT_NEAR(static_cast<double>(in_jump) / n, 10.0 / 70.0, 0.01);
  EXPECT_NEAR(mean(durations), 10.0, 0.6);  // standard error 0.19 s
  EXPECT_NEAR(sd(offsets), 0.5, 0.025);     // standard error 0.005 m
  EXPECT_NEAR(mean(offsets), 0.0, 0.03);
}

TEST(GpsCompass, OutagesSilenceTheReceiverForUpToTheirDuration) {
  GpsCompassConfig c;
  c.jump_interval = 0.0;
  c.outage_interval = 100.0;
  c.outage_duration = 2.0;
  GpsCompass gps(c, geo::LocalNed(geo::kPyhajarviOrigin), 5);
  VehicleState s;
  const double dt = 0.1;
  int invalid = 0, n = 0;
  std::vector<double> lengths;
  double since = -1.0;
  for (s.t = 0.0; s.t < 1e5; s.t += dt, ++n) {
    const bool valid = gps.measure(s).valid;
    invalid += !valid;
    if (!valid && since < 0.0) since = s.t;
    if (valid && since >= 0.0) {
      lengths.push_back(s.t - since);
      since = -1.0;
    }
  }
  ASSERT_GT(lengths.size(), 800u);  // about 990
  // uniform 0.2 .. 2 s (mean 1.1 s), seen at 10 Hz: each outage within a sample of its bounds
  for (double l : lengths) {
    EXPECT_GE(l, 0.2 - 1e-9);
    EXPECT_LE(l, 2.0 + dt + 1e-9);
  }
  EXPECT_NEAR(mean(lengths), 1.1 + dt / 2, 0.06);
  EXPECT_NEAR(static_cast<double>(invalid) / n, 1.1 / 101.1, 0.0015);
  // the simulation drops the readings of an outage, as the `gps` fault does
  UsvSimulation::Config cfg;
  cfg.gps.outage_interval = 5.0;
  UsvSimulation usv(Scenario{}, cfg);
  int fixes = 0;
  for (int i = 0; i < 12000; ++i) fixes += usv.step().gps.has_value();  // 120 s at 10 Hz
  EXPECT_LT(fixes, 1200 - 100);  // about 1200 * 1.1 / 6.1 = 216 missing
  EXPECT_GT(fixes, 1200 - 350);
}

TEST(GpsCompass, TheFieldsEffectsAreOnByDefault) {
  const GpsCompassConfig c;
  EXPECT_GT(c.jump_interval, 0.0);
  EXPECT_GT(c.jump_sigma, 0.0);
  EXPECT_GT(c.outage_interval, 0.0);
  EXPECT_LE(c.outage_duration, 2.0);  // short: below the USV supervisor's gps_timeout (3 s)
  GpsCompassConfig bad;
  bad.outage_duration = 0.1;
  EXPECT_THROW(GpsCompass(bad, geo::LocalNed(geo::kPyhajarviOrigin), 1), ConfigError);
}

TEST(Ahrs, HeadingBiasPerRunAndSlowDrift) {
  // Across runs (seeds): the heading error averaged over 10 s is the run's bias plus the drift then.
  AhrsConfig c;
  std::vector<double> bias_drift, first;
  for (std::uint64_t seed = 1; seed <= 2000; ++seed) {
    Ahrs ahrs(c, seed);
    VehicleState s;
    double sum = 0.0;
    for (int i = 0; i < 500; ++i) {
      s.t = 0.02 * i;
      sum += ahrs.measure(s, Eigen::Vector3d::Zero()).yaw;
    }
    bias_drift.push_back(sum / 500);
    first.push_back(ahrs.headingError());
  }
  const double expected = std::hypot(c.heading_bias_sigma, c.heading_drift_sigma);  // 0.86 deg
  EXPECT_NEAR(sd(bias_drift), expected, 0.05 * expected);
  EXPECT_NEAR(mean(bias_drift), 0.0, 0.1 * expected);
  // in all, about the data sheet's 1 deg RMS
  EXPECT_NEAR(rad2deg(std::hypot(expected, c.heading_sigma)), 1.0, 0.05);
  // Within one run: the drift is a first-order Gauss-Markov process about the bias.
  Ahrs ahrs(c, 17);
  VehicleState s;
  std::vector<double> d;
  for (int i = 0; i < 200000; ++i) {  // 1 Hz over 670 correlation times
    s.t = i;
    ahrs.measure(s, Eigen::Vector3d::Zero());
    d.push_back(ahrs.headingError());
  }
  const double m = mean(d);  // the bias
  double var = 0, lag = 0;
  for (std::size_t i = 0; i < d.size(); ++i) var += (d[i] - m) * (d[i] - m);
  for (std::size_t i = 0; i + 300 < d.size(); ++i) lag += (d[i] - m) * (d[i + 300] - m);
  EXPECT_NEAR(std::sqrt(var / d.size()), c.heading_drift_sigma, 0.1 * c.heading_drift_sigma);
  EXPECT_NEAR(lag / var, std::exp(-1.0), 0.1);  // one correlation time apart
}

TEST(Dvl, TheRunsBiasHasItsSpreadAndEntersAsModelled) {
  DvlConfig c;
  std::vector<double> scale, misalignment, offset;
  for (std::uint64_t seed = 1; seed <= 4000; ++seed) {
    Dvl dvl(c, seed);
    scale.push_back(dvl.scale());
    misalignment.push_back(dvl.misalignment());
    for (int k = 0; k < 3; ++k) offset.push_back(dvl.offset()[k]);
  }
  EXPECT_NEAR(sd(scale), c.scale_sigma, 0.05 * c.scale_sigma);
  EXPECT_NEAR(sd(misalignment), c.misalignment_sigma, 0.05 * c.misalignment_sigma);
  EXPECT_NEAR(sd(offset), c.offset_sigma, 0.05 * c.offset_sigma);
  // noise-free: the reading is (1 + scale) R_z(misalignment) v + offset
  c.velocity_sigma = 0.0;
  Dvl dvl(c, 9);
  VehicleState s;
  s.position.z() = 3.0;
  s.velocity = {0.5, 0.1, -0.05};
  const Eigen::Vector3d expected =
      (1.0 + dvl.scale()) * (Eigen::AngleAxisd(dvl.misalignment(), Eigen::Vector3d::UnitZ()) * s.velocity) + dvl.offset();
  const auto r = dvl.measure(s);
  ASSERT_TRUE(r);
  EXPECT_LT((r->velocity - expected).norm(), 1e-12);
  EXPECT_NEAR(r->altitude, c.bottom_depth - 3.0, 1e-12);
  // at 0.5 m/s the bias is millimetres per second: what the data sheets' long-term accuracy allows
  EXPECT_LT((r->velocity - s.velocity).norm(), 0.03);
}

TEST(Dvl, BottomLockOnlyBetweenItsAltitudes) {
  DvlConfig c;
  c.bottom_depth = 100.0;
  Dvl dvl(c, 1);
  VehicleState s;
  for (const auto& [depth, lock] : {std::pair{10.0, false}, {24.9, false}, {25.1, true}, {60.0, true}, {99.8, false}}) {
    s.position.z() = depth;  // altitude 100 - depth: lock between 0.3 and 75 m
    EXPECT_EQ(dvl.measure(s).has_value(), lock) << depth;
  }
  // the default: a 10 m lake bottom under an AUV at the surface or at its 3 m mission depth keeps the lock
  EXPECT_TRUE(Dvl(DvlConfig{}, 1).measure(VehicleState{}));
  // the simulation passes on what the DVL gives
  AuvSimulation::Config cfg;
  cfg.dvl.bottom_depth = 200.0;  // deep water: out of reach at the surface
  AuvSimulation deep(Scenario{}, cfg);
  int readings = 0;
  for (int i = 0; i < 500; ++i) readings += deep.step().dvl.has_value();
  EXPECT_EQ(readings, 0);
  DvlConfig bad;
  bad.min_altitude = 80.0;  // above max_altitude
  EXPECT_THROW(Dvl(bad, 1), ConfigError);
}

TEST(SurfaceGps, FixesOnlyAtTheSurfaceWithTheirNoise) {
  // The Girona500's GPS: a fix while the antenna is out of the water, white noise of `sigma` on each horizontal
  // axis about the true position, in the site's frame.
  const geo::LocalNed site(geo::LatLonAlt{61.45, 23.73, 0.0});
  SurfaceGpsConfig c;
  SurfaceGps gps(c, site, 3);
  VehicleState s;
  s.position = Eigen::Vector3d(20.0, -5.0, 0.1);
  std::vector<double> n, e;
  for (int i = 0; i < 4000; ++i) {
    const auto r = gps.measure(s);
    ASSERT_TRUE(r.has_value());
    const Eigen::Vector3d ned = site.toNed(r->fix);
    n.push_back(ned.x());
    e.push_back(ned.y());
  }
  EXPECT_NEAR(mean(n), 20.0, 0.1);
  EXPECT_NEAR(mean(e), -5.0, 0.1);
  EXPECT_NEAR(sd(n), c.sigma, 0.1 * c.sigma);
  EXPECT_NEAR(sd(e), c.sigma, 0.1 * c.sigma);
  s.position.z() = c.max_depth + 0.05;  // the antenna under water
  EXPECT_FALSE(gps.measure(s).has_value());
  // the simulation gives it on a Girona500 at the surface, at its rate, and never on the aColor
  Scenario sc;
  sc.auv.depth = 0.0;
  AuvSimulation::Config cfg;
  AuvSimulation g500(sc, cfg);
  cfg.auv = models::AuvParams::aColor();
  AuvSimulation acolor(sc, cfg);
  int g = 0, a = 0;
  for (int i = 0; i < 1000; ++i) {  // 10 s
    g += g500.step().gps.has_value();
    a += acolor.step().gps.has_value();
  }
  EXPECT_NEAR(g, 10, 1);
  EXPECT_EQ(a, 0);
}
