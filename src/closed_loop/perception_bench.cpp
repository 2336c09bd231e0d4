// Perception benchmark: LiDAR target extraction on three frames against two PCL baselines, plus one sonar sweep.
// Frames: `small` (MRS1000 size, 4 x 1100, synthetic scene), `dense` (128 x 1024, the same scene) and `harbour`
// (the simulator's MRS1000 ray caster in a basin with quays, a breakwater, moored vessels and mooring buoys).
// Baselines, run per frame as a PCL user would, on the returns the extractor keeps (its own filter, `kept`):
//  - pcl3d: pcl::EuclideanClusterExtraction in 3-D, tolerance = gap, min size = min_points, no max size;
//  - pcl_organized: pcl::OrganizedConnectedComponentSegmentation with a pcl::EuclideanClusterComparator
//    (threshold = gap) on the frame as an organised cloud (one row per layer, dropped returns NaN).
// Each needs the frame as a pcl::PointCloud first: that conversion is timed on its own. The baselines' clusters
// are checked against our targets (`matchTargets`); exit status 1 when they disagree. Last line: one JSON object.
// PCL's headers stay in this file: nothing else pays their compile time.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/euclidean_cluster_comparator.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/organized_connected_component_segmentation.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/perception/lidar_targets.h"
#include "offshore_gnc/perception/sonar_image.h"
#include "offshore_gnc/perception/sonar_targets.h"
#include "perception/synthetic_scenes.h"
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

using PclCloud = pcl::PointCloud<pcl::PointXYZ>;
using Clusters = std::vector<pcl::PointIndices>;

pcl::PointXYZ pointAt(const scenes::Cloud& c, std::size_t i) {
  float p[3];
  std::memcpy(p, c.data.data() + i * c.point_step, sizeof p);  // point_step 18: unaligned
  return {p[0], p[1], p[2]};
}

// The extractor's filter (LidarTargetExtractor::extract), compared in double as there: finite x/y/z, horizontal
// range within [min_range, max_range], z within [min_z, max_z], outside the hull box (when one is set).
bool kept(const pcl::PointXYZ& p, const LidarConfig& cfg) {
  const double x = p.x, y = p.y, z = p.z;
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return false;
  const double r2 = x * x + y * y;
  if (r2 < cfg.min_range * cfg.min_range || r2 > cfg.max_range * cfg.max_range || z < cfg.min_z || z > cfg.max_z)
    return false;
  const bool hull = cfg.hull_min_x < cfg.hull_max_x && cfg.hull_min_y < cfg.hull_max_y;
  return !(hull && x >= cfg.hull_min_x && x <= cfg.hull_max_x && y >= cfg.hull_min_y && y <= cfg.hull_max_y);
}

// Per frame, before PCL can cluster: the kept returns as an unorganised cloud (its memory reused between frames)...
void toPcl(const scenes::Cloud& c, const LidarConfig& cfg, PclCloud& out) {
  out.clear();
  for (std::size_t i = 0, n = std::size_t(c.width) * c.height; i < n; ++i) {
    const pcl::PointXYZ p = pointAt(c, i);
    if (kept(p, cfg)) out.push_back(p);
  }
}

// ... or the whole frame as an organised cloud (width = points per layer, height = layers), dropped returns NaN.
void toPclOrganised(const scenes::Cloud& c, const LidarConfig& cfg, PclCloud& out) {
  out.resize(c.width, c.height);
  out.is_dense = false;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < out.size(); ++i) {
    const pcl::PointXYZ p = pointAt(c, i);
    out[i] = kept(p, cfg) ? p : pcl::PointXYZ(nan, nan, nan);
  }
}

// 3-D Euclidean clustering, set up once; extract() builds the kd-tree of the frame it is given (a new frame needs
// a new tree), unsorted radius results as PCL's own default tree (clustering does not need them sorted).
class Pcl3d {
 public:
  explicit Pcl3d(const LidarConfig& cfg) {
    ec_.setClusterTolerance(cfg.gap);
    ec_.setMinClusterSize(static_cast<pcl::uindex_t>(cfg.min_points));
    ec_.setMaxClusterSize(std::numeric_limits<pcl::uindex_t>::max());  // the extractor has no upper bound
    ec_.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>(false)));
  }
  void operator()(const PclCloud::ConstPtr& cloud, Clusters& out) {
    ec_.setInputCloud(cloud);
    out.clear();  // extract() appends
    ec_.extract(out);
  }

 private:
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec_;
};

// Connected components of the organised cloud: a point joins its left and upper neighbours closer than gap.
class PclOrganised {
 public:
  explicit PclOrganised(const LidarConfig& cfg) : min_points_(std::size_t(cfg.min_points)) {
    cmp_->setDistanceThreshold(static_cast<float>(cfg.gap), false);
  }
  void operator()(const PclCloud::ConstPtr& cloud, Clusters& out) {
    cmp_->setInputCloud(cloud);
    seg_.setInputCloud(cloud);
    // segment() would keep the previous frame's labels and append to its indices: both must start empty.
    labels_.clear();
    all_.clear();
    seg_.segment(labels_, all_);
    out.clear();
    for (auto& c : all_)  // segment() has no size limits; min_points as the extractor's
      if (c.indices.size() >= min_points_) out.push_back(std::move(c));
  }

 private:
  std::size_t min_points_;
  pcl::EuclideanClusterComparator<pcl::PointXYZ, pcl::Label>::Ptr cmp_{
      new pcl::EuclideanClusterComparator<pcl::PointXYZ, pcl::Label>};
  pcl::OrganizedConnectedComponentSegmentation<pcl::PointXYZ, pcl::Label> seg_{cmp_};
  pcl::PointCloud<pcl::Label> labels_;
  Clusters all_;
};

// Median time of one call, robust to other processes on the shared core: a warm-up call (allocations), then calls
// until `budget_ms` has passed (at least 5).
template <typename F>
double msPerRun(F&& f, double budget_ms = 1500.0) {
  f();
  std::vector<double> ms;
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double, std::milli>(budget_ms));
  do {
    const auto t0 = Clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  } while (ms.size() < 5 || Clock::now() < end);
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

struct Group {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  std::size_t points = 0;
};

constexpr double kMatchTol = 0.05;  // [m] x-y distance between our target's centroid and the baseline's

// x-y footprints of two clusters within `d`: bounding boxes first, then points.
bool touch(const PclCloud& cloud, const pcl::PointIndices& a, const pcl::PointIndices& b, double d) {
  auto box = [&](const pcl::PointIndices& c) {
    Eigen::AlignedBox2f bb;
    for (int i : c.indices) bb.extend(Eigen::Vector2f(cloud[i].x, cloud[i].y));
    return bb;
  };
  Eigen::AlignedBox2f ba = box(a), bb = box(b);
  ba.min().array() -= float(d), ba.max().array() += float(d);
  if (!ba.intersects(bb)) return false;
  const float d2 = float(d * d);
  for (int i : a.indices)
    for (int j : b.indices) {
      const float dx = cloud[i].x - cloud[j].x, dy = cloud[i].y - cloud[j].y;
      if (dx * dx + dy * dy <= d2) return true;
    }
  return false;
}

// The baseline's clusters as targets. The extractor merges a target's layers in x-y (within layer_merge); PCL
// measures in 3-D, so the layers of a sparse scanner (2.5 deg apart: more than gap apart beyond about 23 m) are
// clusters of their own. Clusters whose x-y footprints come within layer_merge are one target here, the
// extractor's own rule; this grouping is not timed (a PCL user would need it too: the timing favours PCL).
std::vector<Group> groups(const PclCloud& cloud, const Clusters& clusters, double layer_merge) {
  std::vector<std::size_t> root(clusters.size());
  for (std::size_t i = 0; i < root.size(); ++i) root[i] = i;
  auto find = [&root](std::size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  for (std::size_t i = 0; i < clusters.size(); ++i)
    for (std::size_t j = i + 1; j < clusters.size(); ++j)
      if (find(i) != find(j) && touch(cloud, clusters[i], clusters[j], layer_merge)) root[find(j)] = find(i);
  std::vector<Group> g(clusters.size());
  for (std::size_t i = 0; i < clusters.size(); ++i)
    for (int k : clusters[i].indices) {
      g[find(i)].centroid += Eigen::Vector2d(cloud[k].x, cloud[k].y);
      ++g[find(i)].points;
    }
  std::vector<Group> out;
  for (auto& x : g)
    if (x.points) out.push_back({x.centroid / double(x.points), x.points});
  return out;
}

// Same targets: as many groups as targets, and each target's centroid within kMatchTol of a group's (x-y);
// `offset` is the largest such distance.
bool matchTargets(const LidarResult& r, const std::vector<Group>& g, double& offset, std::string& why) {
  char buf[200];
  offset = 0.0;
  for (const auto& t : r.targets) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& x : g) best = std::min(best, (t.centroid.head<2>() - x.centroid).norm());
    offset = std::max(offset, best);
    if (best > kMatchTol) {
      std::snprintf(buf, sizeof buf, "our target at (%.2f, %.2f): nearest baseline centroid %.3f m away (> %.2f m)",
                    t.centroid.x(), t.centroid.y(), best, kMatchTol);
      why = buf;
      return false;
    }
  }
  if (r.targets.size() != g.size()) {
    std::snprintf(buf, sizeof buf, "%zu targets, the baseline %zu", r.targets.size(), g.size());
    why = buf;
    return false;
  }
  std::snprintf(buf, sizeof buf, "same targets (centroids within %.4f m)", offset);
  why = buf;
  return true;
}

struct Baseline {
  double convert_ms = 0, ms = 0;       // frame -> pcl::PointCloud; clustering
  std::size_t clusters = 0, targets = 0;  // PCL's clusters; the targets they make (`groups`)
  bool same = false;
  double offset = 0;  // [m] largest x-y distance of our target's centroid to the baseline's
  std::string why;
};

struct Frame {
  const char* name = "";
  double lidar_ms = 0;
  std::size_t targets = 0;
  Baseline pcl3d, organised;
};

Frame run(const char* name, const scenes::Cloud& c, const LidarConfig& cfg) {
  Frame f;
  f.name = name;
  LidarTargetExtractor ex(cfg);
  LidarResult r;
  f.lidar_ms = msPerRun([&] { r = ex.extract(c.view()); });
  f.targets = r.targets.size();
  PclCloud::Ptr cloud(new PclCloud);
  auto baseline = [&](auto convert, auto&& cluster) {
    Baseline b;
    Clusters clusters;
    b.convert_ms = msPerRun([&] { convert(c, cfg, *cloud); });
    b.ms = msPerRun([&] { cluster(cloud, clusters); });
    b.clusters = clusters.size();
    const auto g = groups(*cloud, clusters, cfg.layer_merge);
    b.targets = g.size();
    b.same = matchTargets(r, g, b.offset, b.why);
    return b;
  };
  f.pcl3d = baseline(toPcl, Pcl3d(cfg));
  f.organised = baseline(toPclOrganised, PclOrganised(cfg));
  auto line = [&](const char* what, const Baseline& b) {
    std::printf("  %-13s %3zu clusters -> %2zu targets %9.3f ms (+ conversion %.3f ms) = %6.1fx ours: %s\n", what,
                b.clusters, b.targets, b.ms, b.convert_ms, b.ms / f.lidar_ms, b.why.c_str());
  };
  std::printf("lidar %s (%u x %u, %zu returns kept): ours %zu targets %.4f ms\n", name, c.height, c.width,
              r.points_used, f.targets, f.lidar_ms);
  line("PCL 3-D", f.pcl3d);
  line("PCL organised", f.organised);
  return f;
}

}  // namespace

int main() {
  LidarConfig cfg;
  const auto s = scene();
  std::printf("PCL baselines on the returns our extractor keeps. Their clusters whose x-y footprints come within "
              "layer_merge (%.1f m) are one target (our rule for joining layers; in 3-D a 4-layer scanner's layers are "
              "apart beyond ~23 m), then checked: same count, each of our centroids within %.2f m of one (x-y).\n",
              cfg.layer_merge, kMatchTol);
  double returns = 0.0;
  const Frame frames[] = {
      run("small", scenes::lidarFrame(s, 4, 1100, deg2rad(275.0), deg2rad(3.75), true, 120.0, 0.02), cfg),
      run("dense", scenes::lidarFrame(s, 128, 1024, 2 * kPi, deg2rad(10.0), true, 120.0, 0.02), cfg),
      run("harbour", harbourFrame(returns), cfg)};
  std::printf("(harbour: %.0f %% of the beams return)\n", 100 * returns);

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
  const double sonar_sweep = msPerRun([&] { sweep(false); });
  const double sonar_image = msPerRun([&] { sweep(true); }) - sonar_sweep;
  std::printf("sonar sweep (400 beams x 300 bins): %zu targets %.3f ms; + Cartesian image %.3f ms\n", sonar_targets,
              sonar_sweep, sonar_image);

  // One JSON object: per frame f, ours (lidar_ms_f, targets_f), each baseline b in {pcl3d, pcl_organized}: its
  // clustering (b_ms_f), its conversion (b_convert_ms_f), b_ms_f / lidar_ms_f (ratio_b_f), with the conversion
  // ((b_ms_f + b_convert_ms_f) / lidar_ms_f: ratio_b_total_f), its clusters, the targets they make, the check.
  std::string json = "{";
  char buf[200];
  bool all_same = true;
  for (const Frame& f : frames) {
    std::snprintf(buf, sizeof buf, "\"lidar_ms_%s\": %.4f, \"targets_%s\": %zu, ", f.name, f.lidar_ms, f.name,
                  f.targets);
    json += buf;
    using Named = std::pair<const char*, const Baseline&>;
    for (const auto& [key, b] : {Named{"pcl3d", f.pcl3d}, Named{"pcl_organized", f.organised}}) {
      std::snprintf(buf, sizeof buf, "\"%s_ms_%s\": %.4f, \"%s_convert_ms_%s\": %.4f, \"ratio_%s_%s\": %.1f, ",
                    key, f.name, b.ms, key, f.name, b.convert_ms, key, f.name, b.ms / f.lidar_ms);
      json += buf;
      std::snprintf(buf, sizeof buf, "\"ratio_%s_total_%s\": %.1f, \"%s_clusters_%s\": %zu, \"%s_targets_%s\": %zu, "
                    "\"same_targets_%s_%s\": %s, ", key, f.name, (b.ms + b.convert_ms) / f.lidar_ms, key, f.name,
                    b.clusters, key, f.name, b.targets, key, f.name, b.same ? "true" : "false");
      json += buf;
      if (!b.same) {
        std::fprintf(stderr, "perception_bench: %s on the %s frame disagrees with our targets (%s): its timing is not "
                     "a like-with-like comparison\n", key, f.name, b.why.c_str());
        all_same = false;
      }
    }
  }
  std::snprintf(buf, sizeof buf, "\"returns_harbour\": %.3f, \"sonar_ms_sweep\": %.3f, \"sonar_image_ms\": %.3f, "
                "\"sonar_targets\": %zu}", returns, sonar_sweep, sonar_image, sonar_targets);
  std::printf("%s%s\n", json.c_str(), buf);
  return all_same ? 0 : 1;
}
