// Split-and-merge wall detection (Publication II) on synthetic sonar sweeps of a tank and of single walls.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

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

// A sweep as SonarTargets publishes it on sonar/sweep: x, y, z, intensity FLOAT32 (point_step 16), one row, one
// point per detection in acquisition order.
struct SweepCloud {
  std::vector<std::uint8_t> data;
  std::uint32_t width = 0;
  CloudView view() const {
    CloudView v;
    v.data = data.data();
    v.size = data.size();
    v.width = width;
    v.height = 1;
    v.point_step = 16;
    v.row_step = 16 * width;
    auto f = [](std::uint32_t off) {
      CloudField c;
      c.present = true; c.offset = off; c.datatype = std::uint8_t(FieldType::Float32);
      return c;
    };
    v.x = f(0); v.y = f(4); v.z = f(8);
    return v;
  }
};

SweepCloud packSweep(const std::vector<Eigen::Vector2d>& pts) {
  SweepCloud c;
  c.width = static_cast<std::uint32_t>(pts.size());
  for (const auto& p : pts) {
    for (const float v : {float(p.x()), float(p.y()), 5.0f, 200.0f}) {
      const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
      c.data.insert(c.data.end(), b, b + sizeof v);
    }
  }
  return c;
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

TEST(WallDetection, DetectorReadsTheSweepCloudInAcquisitionOrder) {
  const Eigen::Vector2d c[4] = {{0, 0}, {20, 0}, {20, 10}, {0, 10}};
  std::vector<scenes::Wall> walls;
  for (int i = 0; i < 4; ++i) walls.push_back({c[i], c[(i + 1) % 4]});
  const auto pts = sweepPoints(walls, {6.0, 3.0}, 0.3, 0.05);
  WallConfig cfg;
  WallDetector det(cfg);
  const SweepWalls r = det.detect(packSweep(pts).view());
  ASSERT_EQ(r.error, CloudError::None) << r.message;
  ASSERT_EQ(r.points.size(), pts.size());
  // the same walls as from the points themselves (float32 in the cloud: within a millimetre)
  const auto want = extractWalls(pts, cfg);
  ASSERT_EQ(r.walls.size(), 4u);
  ASSERT_EQ(r.walls.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_LT((r.walls[i].a - want[i].a).norm(), 1e-3);
    EXPECT_LT((r.walls[i].b - want[i].b).norm(), 1e-3);
  }
  const WallPath p = det.plan(r.walls, {6.0, 3.0}, 0.0);
  ASSERT_TRUE(p.ok);
  EXPECT_NEAR((p.wp2 - p.wp1).norm(), cfg.spacing, 1e-9);
  EXPECT_EQ(det.counters().total(), 0u);
}

TEST(WallDetection, DetectorCountsEmptyMalformedAndNonFiniteSweeps) {
  const std::vector<scenes::Wall> walls = {{{8.0, -12.0}, {8.0, 12.0}}};
  const auto pts = sweepPoints(walls, {0, 0}, 1.0);
  WallDetector det{WallConfig{}};

  // nothing detected: SonarTargets publishes a cloud of no points; no walls, no error
  const SweepWalls empty = det.detect(packSweep({}).view());
  EXPECT_EQ(empty.error, CloudError::None);
  EXPECT_TRUE(empty.walls.empty());
  EXPECT_EQ(det.counters().get("empty_sweep"), 1u);

  const SweepCloud cloud = packSweep(pts);
  CloudView v = cloud.view();
  v.y.present = false;
  SweepWalls r = det.detect(v);
  EXPECT_EQ(r.error, CloudError::MissingXyz);
  EXPECT_TRUE(r.walls.empty());
  EXPECT_FALSE(r.message.empty());
  v = cloud.view();
  v.size -= 3;
  EXPECT_EQ(det.detect(v).error, CloudError::SizeMismatch);
  v = cloud.view();
  v.x.datatype = std::uint8_t(FieldType::UInt8);
  EXPECT_EQ(det.detect(v).error, CloudError::BadFieldType);
  v = cloud.view();
  v.width = 0;  // no points over a full buffer
  EXPECT_EQ(det.detect(v).error, CloudError::Empty);
  EXPECT_EQ(det.counters().get("missing_xyz"), 1u);
  EXPECT_EQ(det.counters().get("size_mismatch"), 1u);
  EXPECT_EQ(det.counters().get("bad_field"), 1u);
  EXPECT_EQ(det.counters().get("empty_cloud"), 1u);

  // NaN and infinite points are dropped and counted; the wall is still found from the rest
  auto holed = pts;
  holed[pts.size() / 3].x() = std::numeric_limits<double>::quiet_NaN();
  holed[pts.size() / 2].y() = std::numeric_limits<double>::infinity();
  r = det.detect(packSweep(holed).view());
  EXPECT_EQ(r.error, CloudError::None);
  EXPECT_EQ(r.non_finite, 2u);
  EXPECT_EQ(r.points.size(), pts.size() - 2);
  EXPECT_EQ(det.counters().get("non_finite_point"), 2u);
  ASSERT_EQ(r.walls.size(), 1u);
  EXPECT_LT(lineDist(r.walls[0], {8.0, 0.0}), 0.05);
}
