// Split-and-merge wall detection (Publication II) on synthetic sonar sweeps of a tank and of single walls.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/perception/sonar_targets.h"
#include "perception/synthetic_scenes.h"
#include "offshore_gnc/perception/wall_detection.h"

using namespace offshore_gnc;
using namespace offshore_gnc::perception;

namespace {

// One full clockwise turn of a static sonar at `o`, starting at bearing `start`; Algorithm 1 per beam.
std::vector<Eigen::Vector2d> sweepPoints(const std::vector<scenes::Wall>& walls, const Eigen::Vector2d& o,
                                         double start, double noise = 0.0) {
  SonarTargetExtractor ex(SonarConfig{});
  std::vector<Eigen::Vector2d> pts;
  std::uint32_t seed = 7;
  const int n = 400;
  for (int k = 0; k < n; ++k) {
    const double b = wrapTwoPi(start + 2 * kPi * k / n);
    const auto bins = scenes::sonarBins({}, walls, o, b, 0.05, 600);
    SonarBeamView v;
    v.bearing = b; v.range_resolution = 0.05; v.bins = bins.data(); v.num_bins = bins.size();
    double r;
    std::uint8_t i;
    if (!ex.detect(v, r, i)) continue;
    seed = seed * 1664525u + 1013904223u;
    r += noise * ((seed >> 8) / double(1 << 24) - 0.5);
    pts.emplace_back(o.x() + r * std::cos(b), o.y() + r * std::sin(b));
  }
  return pts;
}

double lineDist(const WallSegment& s, const Eigen::Vector2d& p) {
  const Eigen::Vector2d u = (s.b - s.a).normalized();
  return std::abs(u.x() * (p.y() - s.a.y()) - u.y() * (p.x() - s.a.x()));
}

}  // namespace

TEST(WallDetection, TankGivesFourWallsAndAPathAlongTheLongest) {
  // 20 m (north) x 10 m (east) tank, vehicle off-centre.
  const Eigen::Vector2d c[4] = {{0, 0}, {20, 0}, {20, 10}, {0, 10}};
  std::vector<scenes::Wall> walls;
  for (int i = 0; i < 4; ++i) walls.push_back({c[i], c[(i + 1) % 4]});
  const Eigen::Vector2d vehicle(6.0, 3.0);
  WallConfig cfg;
  const auto segs = extractWalls(sweepPoints(walls, vehicle, 0.3, 0.05), cfg);
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_NEAR(segs[0].length(), 20.0, 0.6);
  EXPECT_NEAR(segs[1].length(), 20.0, 0.6);
  EXPECT_NEAR(segs[2].length(), 10.0, 0.6);
  EXPECT_NEAR(segs[3].length(), 10.0, 0.6);
  for (const auto& s : segs) EXPECT_LT(s.rms, 0.05);

  const WallPath p = planWallPath(segs, vehicle, 0.0 /* heading north */, cfg);
  ASSERT_TRUE(p.ok);
  // The longest walls are y = 0 and y = 10; either way the waypoints are 2 m inside it, 2 m apart, northwards.
  const double wall_y = std::abs(p.wall.a.y()) < 1.0 ? 0.0 : 10.0;
  EXPECT_NEAR(std::abs(p.wp1.y() - wall_y), cfg.offset, 0.1);
  EXPECT_NEAR(std::abs(p.wp2.y() - wall_y), cfg.offset, 0.1);
  EXPECT_NEAR((p.wp2 - p.wp1).norm(), 2.0, 1e-9);
  EXPECT_GT(p.wp2.x() - p.wp1.x(), 1.9);  // ahead, along the heading
  EXPECT_NEAR(p.wp1.x(), vehicle.x(), 0.1);  // abeam of the vehicle
  EXPECT_GT(p.wp1.y(), 0.0);                  // inside the tank
  EXPECT_LT(p.wp1.y(), 10.0);
}

TEST(WallDetection, SingleWall) {
  const std::vector<scenes::Wall> walls = {{{8.0, -12.0}, {8.0, 12.0}}};
  WallConfig cfg;
  const auto segs = extractWalls(sweepPoints(walls, {0, 0}, 1.0), cfg);
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_LT(lineDist(segs[0], {8.0, 0.0}), 0.05);
  EXPECT_LT(lineDist(segs[0], {8.0, 5.0}), 0.05);
  const WallPath p = planWallPath(segs, {0, 0}, kPi / 2 /* heading east */, cfg);
  ASSERT_TRUE(p.ok);
  EXPECT_NEAR(p.wp1.x(), 6.0, 0.05);
  EXPECT_NEAR(p.wp1.y(), 0.0, 0.05);
  EXPECT_NEAR(p.wp2.x(), 6.0, 0.05);
  EXPECT_NEAR(p.wp2.y(), 2.0, 0.05);
}

TEST(WallDetection, WallAcrossTheZeroBearingStaysOneWall) {
  // The sweep starts and ends on the wall straight ahead: the points of one wall are at both ends of the
  // sweep (laser_line_extraction splits it in two).
  const std::vector<scenes::Wall> walls = {{{10.0, -15.0}, {10.0, 15.0}}};
  WallConfig cfg;
  const auto pts = sweepPoints(walls, {0, 0}, 0.0);
  ASSERT_GT(pts.size(), 50u);
  EXPECT_GT(pts.front().y(), -0.2);  // the sweep begins on the wall at y ~ 0 ...
  EXPECT_LT(pts.back().y(), 0.0);    // ... and ends there
  const auto segs = extractWalls(pts, cfg);
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_GT(segs[0].length(), 25.0);
  EXPECT_LT(lineDist(segs[0], {10.0, 0.0}), 0.05);
}

TEST(WallDetection, CornersSplitAndScatterIsNotAWall) {
  // An L-shaped corner: two walls, not one; isolated points (fish, speckle) give nothing.
  const std::vector<scenes::Wall> walls = {{{10.0, -10.0}, {10.0, 5.0}}, {{10.0, 5.0}, {-5.0, 5.0}}};
  WallConfig cfg;
  const auto segs = extractWalls(sweepPoints(walls, {0, 0}, 2.0), cfg);
  ASSERT_EQ(segs.size(), 2u);
  const double dot = std::abs((segs[0].b - segs[0].a).normalized().dot((segs[1].b - segs[1].a).normalized()));
  EXPECT_LT(dot, 0.05);  // perpendicular
  std::vector<Eigen::Vector2d> scatter;
  for (int i = 0; i < 40; ++i) scatter.emplace_back(5.0 * std::cos(i * 2.4), 7.0 * std::sin(i * 1.7));
  EXPECT_TRUE(extractWalls(scatter, cfg).empty());
  EXPECT_FALSE(planWallPath({}, {0, 0}, 0, cfg).ok);
}
