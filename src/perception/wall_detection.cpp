#include "offshore_gnc/perception/wall_detection.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace perception {

const ParamTable<WallConfig>& WallConfig::table() {
  using W = WallConfig;
  static const ParamTable<W> t = ParamTable<W>()
      .number("split_distance", &W::split_distance, 1e-3, 100, "m", "eq. 7: a point farther from the line splits the set")
      .number("break_distance", &W::break_distance, 1e-3, 1e3, "m", "consecutive points farther apart start a new set")
      .degrees("merge_angle_deg", &W::merge_angle, 0.0, 45.0, "segments whose directions differ less are collinear...")
      .number("merge_distance", &W::merge_distance, 0.0, 100, "m", "...when each one's ends lie this close to the other's line...")
      .number("merge_gap", &W::merge_gap, 0.0, 1e3, "m", "...and the gap between them is at most this")
      .integer("min_points", &W::min_points, 2, 1000000, "a segment of fewer points is no wall")
      .number("min_length", &W::min_length, 0.0, 1e4, "m", "the shortest wall a path is planned along")
      .number("wall_distance", &W::offset, 0.0, 1e3, "m", "the waypoints' distance from the wall")
      .number("waypoint_spacing", &W::spacing, 1e-3, 1e3, "m", "the two waypoints are this far apart (Publication II)")
      .string("base_frame", &W::base_frame, "the vehicle frame whose pose at the sweep's end places the waypoints");
  return t;
}

void WallConfig::validate() const { table().validate(*this); }

namespace {

// A segment being built: the indices of its points (several runs after merging).
struct Work {
  std::vector<Eigen::Vector2d> pts;
  Eigen::Vector2d c{0, 0}, u{1, 0};  // centroid and unit direction of the total-least-squares line
  double tmin = 0, tmax = 0, rms = 0;
};

void fit(Work& w) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : w.pts) c += p;
  c /= static_cast<double>(w.pts.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : w.pts) cov += (p - c) * (p - c).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  w.c = c;
  w.u = es.eigenvectors().col(1).normalized();  // largest eigenvalue: the line direction
  // Keep the direction of acquisition so that "a" is the first end.
  if (w.u.dot(w.pts.back() - w.pts.front()) < 0) w.u = -w.u;
  w.tmin = w.tmax = 0;
  bool first = true;
  double ss = 0;
  const Eigen::Vector2d n(-w.u.y(), w.u.x());
  for (const auto& p : w.pts) {
    const double t = w.u.dot(p - c);
    if (first || t < w.tmin) w.tmin = t;
    if (first || t > w.tmax) w.tmax = t;
    first = false;
    const double e = n.dot(p - c);
    ss += e * e;
  }
  w.rms = std::sqrt(ss / static_cast<double>(w.pts.size()));
}

double lineDistance(const Work& w, const Eigen::Vector2d& p) {
  return std::abs(Eigen::Vector2d(-w.u.y(), w.u.x()).dot(p - w.c));
}

// Steps 2-5 of Algorithm 1 on points[i..j] (inclusive): line through the end points (eq. 6), farthest
// point (eq. 7), split there while it is farther than the threshold.
void split(const std::vector<Eigen::Vector2d>& pts, std::size_t i, std::size_t j, double thr,
           std::vector<std::pair<std::size_t, std::size_t>>& out) {
  std::vector<std::pair<std::size_t, std::size_t>> stack{{i, j}};
  while (!stack.empty()) {
    auto [s, e] = stack.back();
    stack.pop_back();
    const Eigen::Vector2d& p1 = pts[s];
    const Eigen::Vector2d& p2 = pts[e];
    const double a = p1.y() - p2.y(), b = p2.x() - p1.x(), c = p1.x() * p2.y() - p2.x() * p1.y();
    const double norm = std::hypot(a, b);
    double dmax = -1;
    std::size_t k = s;
    for (std::size_t m = s + 1; m < e; ++m) {
      const double d = norm > 0 ? std::abs(a * pts[m].x() + b * pts[m].y() + c) / norm : (pts[m] - p1).norm();
      if (d > dmax) {
        dmax = d;
        k = m;
      }
    }
    if (dmax > thr && k > s && k < e) {
      stack.push_back({k, e});  // processed after [s, k]: output stays in acquisition order
      stack.push_back({s, k});
    } else {
      out.push_back({s, e});
    }
  }
}

bool collinear(const Work& x, const Work& y, const WallConfig& cfg) {
  if (std::abs(x.u.dot(y.u)) < std::cos(cfg.merge_angle)) return false;
  const Eigen::Vector2d xa = x.c + x.tmin * x.u, xb = x.c + x.tmax * x.u;
  const Eigen::Vector2d ya = y.c + y.tmin * y.u, yb = y.c + y.tmax * y.u;
  if (lineDistance(x, ya) > cfg.merge_distance || lineDistance(x, yb) > cfg.merge_distance ||
      lineDistance(y, xa) > cfg.merge_distance || lineDistance(y, xb) > cfg.merge_distance)
    return false;
  // Gap along the common direction between the two intervals (negative when they overlap).
  const double ty0 = x.u.dot(ya - x.c), ty1 = x.u.dot(yb - x.c);
  const double gap = std::max(std::min(ty0, ty1) - x.tmax, x.tmin - std::max(ty0, ty1));
  return gap <= cfg.merge_gap;
}

}  // namespace

std::vector<WallSegment> extractWalls(const std::vector<Eigen::Vector2d>& points, const WallConfig& cfg) {
  cfg.validate();
  std::vector<Work> work;
  // Sets of consecutive points without gaps, then split (Algorithm 1 steps 1-5).
  std::size_t start = 0;
  std::vector<std::pair<std::size_t, std::size_t>> parts;
  for (std::size_t i = 1; i <= points.size(); ++i) {
    if (i == points.size() || (points[i] - points[i - 1]).norm() > cfg.break_distance) {
      if (i - start >= 2) split(points, start, i - 1, cfg.split_distance, parts);
      start = i;
    }
  }
  for (const auto& [s, e] : parts) {
    Work w;
    w.pts.assign(points.begin() + static_cast<long>(s), points.begin() + static_cast<long>(e) + 1);
    fit(w);
    work.push_back(std::move(w));
  }
  // Step 6: merge collinear segments, any pair (the first and last of a sweep included), until stable.
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < work.size() && !merged; ++i) {
      for (std::size_t j = i + 1; j < work.size() && !merged; ++j) {
        if (!collinear(work[i], work[j], cfg)) continue;
        Work m;
        m.pts = work[i].pts;
        m.pts.insert(m.pts.end(), work[j].pts.begin(), work[j].pts.end());
        fit(m);
        if (m.rms > cfg.split_distance) continue;  // would not pass the split test: not one line
        work[i] = std::move(m);
        work.erase(work.begin() + static_cast<long>(j));
        merged = true;
      }
    }
  }
  std::vector<WallSegment> out;
  for (const auto& w : work) {
    if (static_cast<int>(w.pts.size()) < cfg.min_points) continue;
    WallSegment s;
    s.a = w.c + w.tmin * w.u;
    s.b = w.c + w.tmax * w.u;
    s.num_points = static_cast<int>(w.pts.size());
    s.rms = w.rms;
    if (s.length() >= cfg.min_length) out.push_back(s);
  }
  std::sort(out.begin(), out.end(), [](const WallSegment& x, const WallSegment& y) { return x.length() > y.length(); });
  return out;
}

WallPath planWallPath(const std::vector<WallSegment>& walls, const Eigen::Vector2d& vehicle, double yaw,
                      const WallConfig& cfg) {
  WallPath p;
  const WallSegment* best = nullptr;
  for (const auto& w : walls)
    if (w.length() >= cfg.min_length && (!best || w.length() > best->length())) best = &w;
  if (!best) return p;
  Eigen::Vector2d u = (best->b - best->a).normalized();
  const Eigen::Vector2d heading(std::cos(yaw), std::sin(yaw));
  if (u.dot(heading) < 0) u = -u;
  Eigen::Vector2d n(-u.y(), u.x());
  const Eigen::Vector2d foot = best->a + u * u.dot(vehicle - best->a);
  if (n.dot(vehicle - foot) < 0) n = -n;  // waypoints on the vehicle's side
  p.ok = true;
  p.wall = *best;
  p.wp1 = foot + n * cfg.offset;
  p.wp2 = p.wp1 + u * cfg.spacing;
  return p;
}

WallDetector::WallDetector(const WallConfig& cfg) : cfg_(cfg) { cfg_.validate(); }

SweepWalls WallDetector::detect(const CloudView& c) {
  SweepWalls r;
  // an empty sweep is published as a cloud of no points with its fields: nothing to check
  if (std::uint64_t(c.width) * c.height == 0 && c.size == 0) {
    counters_.increment("empty_sweep");
    return r;
  }
  r.error = checkCloudLayout(c, r.message);
  if (r.error != CloudError::None) {
    counters_.increment(toString(r.error));
    return r;
  }
  r.points.reserve(std::size_t(c.width) * c.height);
  for (std::uint32_t row = 0; row < c.height; ++row) {
    for (std::uint32_t col = 0; col < c.width; ++col) {
      const std::uint8_t* p = c.data + std::size_t(row) * c.row_step + std::size_t(col) * c.point_step;
      const double x = readField(p + c.x.offset, c.x.datatype), y = readField(p + c.y.offset, c.y.datatype);
      if (!std::isfinite(x) || !std::isfinite(y)) {
        ++r.non_finite;
        continue;
      }
      r.points.emplace_back(x, y);
    }
  }
  if (r.non_finite) counters_.increment("non_finite_point", r.non_finite);
  r.walls = extractWalls(r.points, cfg_);
  return r;
}

}  // namespace perception
}  // namespace offshore_gnc
