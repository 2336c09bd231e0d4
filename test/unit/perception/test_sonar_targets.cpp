// Sonar target detection (paper Algorithms 1-2) on synthetic sweeps, with the vehicle moving during a sweep.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/perception/sonar_image.h"
#include "offshore_gnc/perception/sonar_targets.h"
#include "perception/synthetic_scenes.h"

using namespace offshore_gnc;
using namespace offshore_gnc::perception;

namespace {

constexpr double kRes = 0.1;   // m per bin
constexpr int kBins = 300;     // 30 m
const double kStep = deg2rad(0.9);
constexpr double kBeamDt = 0.05;  // s per beam: 20 s per full turn

struct Pose2 { Eigen::Vector2d p; double yaw; };  // NED: x north, y east, yaw clockwise from north

Eigen::Isometry3d iso(const Pose2& v) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(v.p.x(), v.p.y(), 5.0);  // 5 m deep
  t.linear() = Eigen::AngleAxisd(v.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return t;
}

struct Sim {
  std::vector<scenes::Circle> circles;
  std::vector<scenes::Wall> walls;
  std::function<Pose2(double)> pose = [](double) { return Pose2{{0, 0}, 0}; };
  std::vector<SonarSweep> sweeps;
  double t = 0;

  void beam(SonarTargetExtractor& ex, double bearing, std::uint16_t status = kHeadReady | kMotorOn) {
    const Pose2 v = pose(t);
    const auto bins = scenes::sonarBins(circles, walls, v.p, v.yaw + bearing, kRes, kBins);
    SonarBeamView b;
    b.stamp = t;
    b.bearing = wrapTwoPi(bearing);
    b.beam_width = kStep;  // sonarBins casts a ray: a beam as wide as one step (the extractor takes it off widths)
    b.range_resolution = kRes;
    b.range_offset = 0.0;
    b.status = status;
    b.bins = bins.data();
    b.num_bins = bins.size();
    ex.addBeam(b, iso(v));
    if (ex.sweepReady()) sweeps.push_back(ex.takeSweep());
    t += kBeamDt;
  }
  // Continuous clockwise turns starting at `start`.
  void turns(SonarTargetExtractor& ex, double start, int n_turns) {
    const int n = static_cast<int>(std::lround(2 * kPi / kStep));
    for (int k = 0; k < n * n_turns + 1; ++k) beam(ex, start + k * kStep);
  }
};

double distanceToCircle(const Eigen::Vector3d& p, const scenes::Circle& c) {
  return std::abs(std::hypot(p.x() - c.x, p.y() - c.y) - c.r);
}

}  // namespace

TEST(SonarTargets, StaticVehicleFindsTwoTargets) {
  SonarTargetExtractor ex(SonarConfig{});
  Sim sim;
  sim.circles = {{10.0, 5.0, 0.6}, {-8.0, -12.0, 1.0}};
  sim.turns(ex, 0.0, 1);
  ASSERT_EQ(sim.sweeps.size(), 1u);
  const auto& s = sim.sweeps[0];
  EXPECT_TRUE(s.full_turn);
  EXPECT_NEAR(s.swept_angle, 2 * kPi, 2 * kStep);
  ASSERT_EQ(s.targets.size(), 2u);
  for (const auto& c : sim.circles) {
    const SonarTarget* best = nullptr;
    for (const auto& t : s.targets)
      if (!best || std::hypot(t.geometry.centroid.x() - c.x, t.geometry.centroid.y() - c.y) <
                       std::hypot(best->geometry.centroid.x() - c.x, best->geometry.centroid.y() - c.y))
        best = &t;
    ASSERT_NE(best, nullptr);
    // Positions within one bin plus the beam's angular quantisation.
    EXPECT_LT(distanceToCircle(best->geometry.origin, c), 0.6);
    EXPECT_LT(distanceToCircle(best->geometry.nearest, c), 0.15);
    EXPECT_NEAR(best->geometry.range, std::hypot(c.x, c.y) - c.r, 0.15);
    EXPECT_NEAR(best->geometry.nearest.z(), 5.0, 1e-9);  // at the vehicle's depth
    EXPECT_NEAR(angleDiff(best->geometry.bearing, std::atan2(c.y, c.x)), 0.0, 0.05);
    EXPECT_GE(best->geometry.num_points, 3u);
  }
}

// A quay wall 10 m north and a target: the wall's runs lie along the wall the sweep's detections trace (issue 32:
// the harbour scenario's sonar took pieces of its quay for the target), so they are dropped; the target stays.
TEST(SonarTargets, PiecesOfAWallAreNotTargets) {
  for (const double margin : {0.0, 0.5}) {
    SonarConfig cfg;
    cfg.wall_margin = margin;
    SonarTargetExtractor ex(cfg);
    Sim sim;
    sim.circles = {{-6.0, -8.0, 0.6}};
    sim.walls = {{{10.0, -12.0}, {10.0, 12.0}}};
    sim.turns(ex, kPi / 2, 1);
    ASSERT_EQ(sim.sweeps.size(), 1u);
    int on_wall = 0, at_target = 0;
    for (const auto& t : sim.sweeps[0].targets) {
      on_wall += std::abs(t.geometry.centroid.x() - 10.0) < 0.5;
      at_target += std::hypot(t.geometry.centroid.x() + 6.0, t.geometry.centroid.y() + 8.0) < 1.0;
    }
    EXPECT_EQ(at_target, 1) << "margin " << margin;
    if (margin > 0.0) {
      EXPECT_EQ(on_wall, 0);
      EXPECT_GE(ex.counters().get("wall_pieces"), 1u);
    } else {
      EXPECT_GE(on_wall, 1);  // without the rule the wall is a target
    }
  }
}

TEST(SonarTargets, VehicleMotionDuringTheSweepIsCompensated) {
  // The vehicle moves north at 0.5 m/s and turns 20 degrees during the 20 s sweep: 10 m of travel, so a
  // sweep positioned with one pose would be metres off.
  SonarTargetExtractor ex(SonarConfig{});
  Sim sim;
  sim.circles = {{4.0, 12.0, 0.8}, {-10.0, -6.0, 0.8}};
  sim.pose = [](double t) { return Pose2{{0.5 * t, 0.0}, deg2rad(1.0) * t}; };
  sim.turns(ex, 0.0, 1);
  ASSERT_EQ(sim.sweeps.size(), 1u);
  ASSERT_GE(sim.sweeps[0].targets.size(), 2u);
  for (const auto& c : sim.circles) {
    double d = 1e9;
    for (const auto& t : sim.sweeps[0].targets) d = std::min(d, distanceToCircle(t.geometry.nearest, c));
    EXPECT_LT(d, 0.15) << "circle at " << c.x << ", " << c.y;
  }
  for (const auto& t : sim.sweeps[0].targets) {
    double d = 1e9;
    for (const auto& c : sim.circles) d = std::min(d, distanceToCircle(t.geometry.nearest, c));
    EXPECT_LT(d, 0.15) << "target at " << t.geometry.nearest.transpose();
  }
  // Every detection lies on an object's surface: positioned with the pose at its own time.
  for (const auto& d : sim.sweeps[0].detections) {
    double e = 1e9;
    for (const auto& c : sim.circles) e = std::min(e, distanceToCircle(d.point, c));
    EXPECT_LT(e, 0.15);
  }
}

TEST(SonarTargets, TargetAcrossTheZeroBearingIsOneTarget) {
  for (double start : {0.0, deg2rad(90.0), deg2rad(-1.8)}) {
    SonarTargetExtractor ex(SonarConfig{});
    Sim sim;
    sim.circles = {{12.0, 0.0, 1.0}};  // dead ahead: bearings ~355..5 degrees
    sim.turns(ex, start, 1);
    ASSERT_EQ(sim.sweeps.size(), 1u);
    ASSERT_EQ(sim.sweeps[0].targets.size(), 1u) << "start " << start;
    const auto& g = sim.sweeps[0].targets[0].geometry;
    EXPECT_NEAR(g.origin.y(), 0.0, 0.2);
    EXPECT_NEAR(angleDiff(g.bearing, 0.0), 0.0, 0.03);
    EXPECT_GE(g.num_points, 8u);
  }
}

TEST(SonarTargets, SectorScanReversalEndsTheSweep) {
  for (bool status_bit : {true, false}) {
    SonarTargetExtractor ex(SonarConfig{});
    Sim sim;
    sim.circles = {{10.0, 2.0, 0.6}};
    const int n = 100;  // 90 degree sector, +-45 around forward
    for (int sweep = 0; sweep < 4; ++sweep) {
      for (int k = 0; k <= n; ++k) {
        const int i = (sweep % 2 == 0) ? k : n - k;
        if (sweep > 0 && k == 0) continue;  // the end beam is not repeated
        std::uint16_t st = kHeadReady | kMotorOn | (sweep % 2 == 0 ? kScanCw : 0);
        if (status_bit && k == 1 && sweep > 0) st |= kSectorReverse;
        sim.beam(ex, deg2rad(-45.0) + i * kStep, st);
      }
    }
    ex.flush();
    if (ex.sweepReady()) sim.sweeps.push_back(ex.takeSweep());
    ASSERT_EQ(sim.sweeps.size(), 4u) << (status_bit ? "status bit" : "observed");
    for (const auto& s : sim.sweeps) {
      EXPECT_FALSE(s.full_turn);
      ASSERT_EQ(s.targets.size(), 1u);
      EXPECT_LT(distanceToCircle(s.targets[0].geometry.nearest, sim.circles[0]), 0.15);
    }
  }
}

TEST(SonarTargets, MinimumRangeThresholdAndHeadStatus) {
  SonarConfig cfg;
  SonarTargetExtractor ex(cfg);
  std::vector<std::uint8_t> bins(100, 10);
  bins[5] = 255;   // 0.5 m: inside the 1.5 m minimum range (the vehicle's own frame)
  bins[40] = 150;  // 4.0 m
  SonarBeamView b;
  b.bearing = 1.0; b.range_resolution = 0.1; b.bins = bins.data(); b.num_bins = bins.size();
  b.status = kHeadReady;
  double r = 0;
  std::uint8_t i = 0;
  ASSERT_TRUE(ex.detect(b, r, i));
  EXPECT_NEAR(r, 4.0, 1e-9);
  EXPECT_EQ(i, 150);
  bins[40] = 50;  // below the threshold
  EXPECT_FALSE(ex.detect(b, r, i));

  bins[40] = 150;
  b.status = kHeadReady | kFault;
  EXPECT_EQ(ex.addBeam(b, Eigen::Isometry3d::Identity()), SonarTargetExtractor::BeamStatus::HeadNotReady);
  b.status = kHeadReady | kCentring;
  EXPECT_EQ(ex.addBeam(b, Eigen::Isometry3d::Identity()), SonarTargetExtractor::BeamStatus::HeadNotReady);
  b.status = 0;
  EXPECT_EQ(ex.addBeam(b, Eigen::Isometry3d::Identity()), SonarTargetExtractor::BeamStatus::HeadNotReady);
  EXPECT_EQ(ex.counters().get("head_not_ready"), 3u);
  b.status = kHeadReady;
  EXPECT_EQ(ex.addBeam(b, Eigen::Isometry3d::Identity()), SonarTargetExtractor::BeamStatus::Detection);
}

TEST(SonarTargets, BadBeamsAreRejectedAndCounted) {
  SonarTargetExtractor ex(SonarConfig{});
  std::vector<std::uint8_t> bins(100, 20);
  bins[50] = 200;  // an echo on the speckle (a uniform 200 would be background to the CFAR, not an echo)
  SonarBeamView b;
  b.bearing = 1.0; b.range_resolution = 0.1; b.bins = bins.data(); b.num_bins = 0;
  using S = SonarTargetExtractor::BeamStatus;
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  EXPECT_EQ(ex.addBeam(b, I), S::Rejected);
  b.num_bins = bins.size();
  for (double bad : {7.0, -0.1, std::nan("")}) {
    b.bearing = bad;
    EXPECT_EQ(ex.addBeam(b, I), S::Rejected);
  }
  b.bearing = 1.0;
  b.range_resolution = 0.0;
  EXPECT_EQ(ex.addBeam(b, I), S::Rejected);
  b.range_resolution = 0.1;
  Eigen::Isometry3d nan_pose = I;
  nan_pose.translation().x() = std::nan("");
  EXPECT_EQ(ex.addBeam(b, nan_pose), S::Rejected);
  EXPECT_EQ(ex.counters().get("empty_beam"), 1u);
  EXPECT_EQ(ex.counters().get("bad_bearing"), 3u);
  EXPECT_EQ(ex.counters().get("bad_beam_geometry"), 1u);
  EXPECT_EQ(ex.counters().get("bad_pose"), 1u);
  EXPECT_EQ(ex.addBeam(b, I), S::Detection);
}

TEST(SonarImage, PolarToCartesianPutsEchoesWhereTheyAre) {
  SonarImage img(20.0, 100);  // 0.2 m per pixel
  std::vector<std::uint8_t> bins(200, 0);
  bins[100] = 255;  // 10 m at 0.1 m per bin
  img.addBeam(0.0, deg2rad(3.0), 0.1, 0.0, bins.data(), bins.size());           // forward: up
  img.addBeam(deg2rad(90.0), deg2rad(3.0), 0.1, 0.0, bins.data(), bins.size());  // starboard: right
  const cv::Mat m = img.render();
  ASSERT_EQ(m.rows, 201);
  ASSERT_EQ(m.type(), CV_8UC1);
  EXPECT_GT(m.at<std::uint8_t>(100 - 50, 100), 100);  // 10 m ahead = 50 px up
  EXPECT_GT(m.at<std::uint8_t>(100, 100 + 50), 100);  // 10 m starboard = 50 px right
  EXPECT_EQ(m.at<std::uint8_t>(100 + 50, 100), 0);    // nothing astern
  EXPECT_EQ(m.at<std::uint8_t>(100, 100 - 50), 0);    // nothing to port
}
