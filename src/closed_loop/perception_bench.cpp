// Perception benchmark: LiDAR target extraction on an MRS1000-size frame (4 x 1100), a dense 128 x 1024 frame and
// a cluttered harbour frame (the simulator's MRS1000 ray caster in a basin with quays, a breakwater, moored
// vessels and mooring buoys) against PCL's EuclideanClusterExtraction on the same frames (same filters, 2-D
// projection, cluster tolerance = gap), plus one sonar sweep. Prints one JSON object as the last line.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/perception/lidar_targets.h"
#include "offshore_gnc/perception/sonar_image.h"
#include "offshore_gnc/perception/sonar_targets.h"
#include "offshore_gnc/perception/synthetic_scenes.h"
#include "offshore_gnc/sim/sensors.h"

using namespace offshore_gnc;
using namespace offshore_gnc::perception;
using Clock = std::chrono::steady_clock;

namespace {

scenes::Scene scene() {
  scenes::Scene s;
  for (int i = 0; i < 6; ++i) s.circles.push_back({15.0 + 8.0 * i, -20.0 + 7.0 * i, 0.5 + 0.1 * i});
  s.boxes = {{30.0, 25.0, 0.3, 12.0, 4.0}, {-25.0, 10.0, 1.2, 8.0, 3.0}, {-10.0, -30.0, 0.0, 20.0, 6.0}};
  return s;
}

// A harbour basin as a USV sees it leaving its berth (NED, metres; the USV at the origin heading north): land
// behind quays 30 m to the west and 35 m to the east, a breakwater 55 m ahead with the entrance on the east side,
// vessels moored 2 m off both quays, mooring buoys in the basin.
sim::World harbour() {
  sim::World w;
  auto land = [&w](double n0, double n1, double e0, double e1) {
    w.shorelines.push_back({{n0, e0}, {n1, e0}, {n1, e1}, {n0, e1}});
  };
  land(-80.0, 90.0, 35.0, 90.0);    // east quay
  land(-80.0, 90.0, -90.0, -30.0);  // west quay
  land(55.0, 62.0, -30.0, 12.0);    // breakwater; the entrance is between it and the east quay
  const double east_berths[] = {-40.0, -24.0, -9.0, 5.0, 19.0, 34.0};
  for (std::size_t i = 0; i < 6; ++i) {
    sim::Vessel v;
    v.centre = {east_berths[i], 35.0 - 2.0 - 1.75};
    v.length = 11.0 + 1.5 * double(i % 3);
    v.width = 3.5;
    v.height = 2.5;
    w.vessels.push_back(v);
  }
  for (double n : {-30.0, -12.0, 8.0, 30.0}) {
    sim::Vessel v;
    v.centre = {n, -30.0 + 2.0 + 2.0};
    v.length = 14.0;
    v.width = 4.0;
    v.height = 3.0;
    w.vessels.push_back(v);
  }
  for (const Eigen::Vector2d& c : {Eigen::Vector2d(18.0, -8.0), Eigen::Vector2d(26.0, 6.0), Eigen::Vector2d(38.0, -15.0),
                                  Eigen::Vector2d(44.0, 2.0), Eigen::Vector2d(12.0, 14.0)})
    w.buoys.push_back({c, 0.6, 1.0});
  return w;
}

// The simulator's MRS1000 frame as the USV simulator publishes it (organised, FLU), in the benchmark's layout.
scenes::Cloud harbourFrame(double& returns) {
  sim::LidarConfig lc;  // the simulator's MRS1000 defaults: 4 layers, 275 deg in 0.25 deg steps, 64 m
  sim::Lidar lidar(lc, harbour(), 7);
  VehicleState s;
  s.position = {-25.0, 2.0, 0.0};  // in the south half of the basin, looking up it
  sim::LidarScan scan;
  lidar.scan(s, scan);
  scenes::Cloud c;
  c.width = static_cast<std::uint32_t>(scan.beams);
  c.height = static_cast<std::uint32_t>(scan.layers);
  c.data.resize(std::size_t(c.width) * c.height * c.point_step);
  std::size_t hit = 0;
  for (int l = 0; l < scan.layers; ++l)
    for (int b = 0; b < scan.beams; ++b) {
      const Eigen::Vector3d p = scan.pointFrd(l, b);
      hit += p.allFinite();
      const float xyz[4] = {float(p.x()), float(-p.y()), float(-p.z()), 100.f};
      std::uint8_t* dst = c.data.data() + (std::size_t(l) * c.width + b) * c.point_step;
      std::memcpy(dst, xyz, 16);
      const std::uint16_t ring = std::uint16_t(l);
      std::memcpy(dst + 16, &ring, 2);
    }
  returns = double(hit) / (double(c.width) * c.height);
  return c;
}

// PCL baseline: the same filtering as the extractor, then Euclidean clustering in 2-D.
std::vector<Eigen::Vector3d> pclClusters(const scenes::Cloud& c, const LidarConfig& cfg) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  const std::size_t n = std::size_t(c.width) * c.height;
  cloud->reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    float p[3];
    std::memcpy(p, c.data.data() + i * c.point_step, 12);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
    const double r2 = double(p[0]) * p[0] + double(p[1]) * p[1];
    if (r2 < cfg.min_range * cfg.min_range || r2 > cfg.max_range * cfg.max_range || p[2] < cfg.min_z || p[2] > cfg.max_z)
      continue;
    cloud->push_back(pcl::PointXYZ(p[0], p[1], 0.f));
  }
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  tree->setInputCloud(cloud);
  std::vector<pcl::PointIndices> clusters;
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
  ec.setClusterTolerance(cfg.gap);
  ec.setMinClusterSize(cfg.min_points);
  ec.setMaxClusterSize(static_cast<int>(n));
  ec.setSearchMethod(tree);
  ec.setInputCloud(cloud);
  ec.extract(clusters);
  std::vector<Eigen::Vector3d> centroids;
  for (const auto& cl : clusters) {
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    for (int i : cl.indices) s += Eigen::Vector3d((*cloud)[i].x, (*cloud)[i].y, 0.0);
    centroids.push_back(s / double(cl.indices.size()));
  }
  return centroids;
}

template <typename F>
double msPerRun(int reps, F&& f) {
  f();  // warm-up (allocations)
  const auto t0 = Clock::now();
  for (int i = 0; i < reps; ++i) f();
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count() / reps;
}

// Same objects: equal counts and each of ours has a PCL centroid within 0.1 m (2-D).
bool sameTargets(const LidarResult& r, const std::vector<Eigen::Vector3d>& pcl_c) {
  if (r.targets.size() != pcl_c.size()) return false;
  for (const auto& t : r.targets) {
    bool found = false;
    for (const auto& c : pcl_c) found |= (t.centroid.head<2>() - c.head<2>()).norm() < 0.1;
    if (!found) return false;
  }
  return true;
}

}  // namespace

int main() {
  LidarConfig cfg;
  const auto s = scene();
  const auto small = scenes::lidarFrame(s, 4, 1100, deg2rad(275.0), deg2rad(3.75), true, 120.0, 0.02);
  const auto dense = scenes::lidarFrame(s, 128, 1024, 2 * kPi, deg2rad(10.0), true, 120.0, 0.02);
  LidarTargetExtractor ex(cfg);
  LidarResult rs, rd;
  std::vector<Eigen::Vector3d> ps, pd;
  const double lidar_small = msPerRun(500, [&] { rs = ex.extract(small.view()); });
  const double lidar_dense = msPerRun(30, [&] { rd = ex.extract(dense.view()); });
  const double pcl_small = msPerRun(50, [&] { ps = pclClusters(small, cfg); });
  const double pcl_dense = msPerRun(3, [&] { pd = pclClusters(dense, cfg); });
  double returns = 0.0;
  const auto harbour_frame = harbourFrame(returns);
  LidarResult rh;
  std::vector<Eigen::Vector3d> ph;
  const double lidar_harbour = msPerRun(500, [&] { rh = ex.extract(harbour_frame.view()); });
  const double pcl_harbour = msPerRun(50, [&] { ph = pclClusters(harbour_frame, cfg); });
  std::printf("lidar small: %zu targets %.3f ms | PCL %zu clusters %.3f ms | ratio %.1fx\n", rs.targets.size(),
              lidar_small, ps.size(), pcl_small, pcl_small / lidar_small);
  std::printf("lidar dense: %zu targets %.3f ms | PCL %zu clusters %.3f ms | ratio %.1fx\n", rd.targets.size(),
              lidar_dense, pd.size(), pcl_dense, pcl_dense / lidar_dense);
  std::printf("lidar harbour (%.0f %% returns): %zu targets %.3f ms | PCL %zu clusters %.3f ms | ratio %.1fx\n",
              100 * returns, rh.targets.size(), lidar_harbour, ph.size(), pcl_harbour, pcl_harbour / lidar_harbour);

  // Sonar: one full 400-beam turn of 300 bins, moving vehicle; extraction and the Cartesian image.
  std::vector<scenes::Circle> circles = {{10.0, 5.0, 0.6}, {-8.0, -12.0, 1.0}, {3.0, -9.0, 0.5}};
  std::vector<scenes::Wall> walls = {{{25.0, -30.0}, {25.0, 30.0}}};
  std::vector<std::vector<std::uint8_t>> beams;
  for (int k = 0; k < 400; ++k) beams.push_back(scenes::sonarBins(circles, walls, {0.0, 0.0}, 2 * kPi * k / 400, 0.1, 300));
  std::size_t sonar_targets = 0;
  auto sweep = [&](bool image) {
    SonarTargetExtractor sx(SonarConfig{});
    SonarImage img(30.0, 200);
    for (int k = 0; k <= 400; ++k) {
      SonarBeamView b;
      b.stamp = 0.05 * k;
      b.bearing = 2 * kPi * (k % 400) / 400;
      b.beam_width = deg2rad(3.0);
      b.range_resolution = 0.1;
      b.bins = beams[k % 400].data();
      b.num_bins = 300;
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation().x() = 0.0;
      sx.addBeam(b, pose);
      if (image) img.addBeam(b.bearing, b.beam_width, b.range_resolution, 0.0, b.bins, b.num_bins);
    }
    if (sx.sweepReady()) sonar_targets = sx.takeSweep().targets.size();
    if (image) {
      volatile int sink = img.render().rows;
      (void)sink;
    }
  };
  const double sonar_sweep = msPerRun(50, [&] { sweep(false); });
  const double sonar_image = msPerRun(20, [&] { sweep(true); }) - sonar_sweep;
  std::printf("sonar sweep (400 beams x 300 bins): %zu targets %.3f ms; + Cartesian image %.3f ms\n", sonar_targets,
              sonar_sweep, sonar_image);
  std::printf("{\"lidar_ms_small\": %.4f, \"lidar_ms_dense\": %.3f, \"pcl_ms_small\": %.3f, \"pcl_ms_dense\": %.2f, "
              "\"ratio_small\": %.1f, \"ratio_dense\": %.1f, \"targets_small\": %zu, \"targets_dense\": %zu, "
              "\"same_targets_small\": %s, \"same_targets_dense\": %s, \"sonar_ms_sweep\": %.3f, "
              "\"sonar_image_ms\": %.3f, \"sonar_targets\": %zu, \"lidar_ms_harbour\": %.4f, \"pcl_ms_harbour\": %.3f, "
              "\"ratio_harbour\": %.1f, \"targets_harbour\": %zu, \"pcl_clusters_harbour\": %zu, "
              "\"same_targets_harbour\": %s, \"returns_harbour\": %.3f}\n",
              lidar_small, lidar_dense, pcl_small, pcl_dense, pcl_small / lidar_small, pcl_dense / lidar_dense,
              rs.targets.size(), rd.targets.size(), sameTargets(rs, ps) ? "true" : "false",
              sameTargets(rd, pd) ? "true" : "false", sonar_sweep, sonar_image, sonar_targets, lidar_harbour,
              pcl_harbour, pcl_harbour / lidar_harbour, rh.targets.size(), ph.size(),
              sameTargets(rh, ph) ? "true" : "false", returns);
  return 0;
}
