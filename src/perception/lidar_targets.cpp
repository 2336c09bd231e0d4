#include "offshore_gnc/perception/lidar_targets.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace perception {

namespace {

constexpr std::uint32_t kMaxRings = 1024;

}  // namespace

const ParamTable<LidarConfig>& LidarConfig::table() {
  using P = LidarConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("min_range", &P::min_range, 0.0, 1e4, "m", "closer returns are dropped (spray, the mount)")
      .number("max_range", &P::max_range, 0.0, 1e4, "m", "farther returns are dropped")
      .number("min_z", &P::min_z, -1e4, 1e4, "m", "lower returns (cloud frame) are water-surface returns")
      .number("max_z", &P::max_z, -1e4, 1e4, "m", "higher returns are dropped")
      .number("gap", &P::gap, 1e-3, 1e3, "m", "a jump between consecutive returns larger than this starts a target")
      .number("layer_merge", &P::layer_merge, 0.0, 1e3, "m", "segments of different layers closer than this are one")
      .integer("min_points", &P::min_points, 1, 1000000, "smaller clusters are dropped (spray, birds)")
      .integer("max_beam_gap", &P::max_beam_gap, 1, 1000000,
               "consecutive returns of a layer more beams apart start a new target (1 = adjacent beams only)")
      .integer("min_run", &P::min_run, 1, 1000000, "a layer's run of fewer returns is dropped (isolated spray)")
      .integer("confirm_frames", &P::confirm_frames, 1, 1000, "a target is reported once seen in this many frames in a row")
      .number("confirm_distance", &P::confirm_distance, 0.0, 100.0, "m",
              "a target continues one of the last frame within this distance")
      .list("hull_box", 4, -1e3, 1e3, "m", "own hull [min_x, max_x, min_y, max_y] in the cloud frame; empty = off",
            [](const P& p) { return std::vector<double>{p.hull_min_x, p.hull_max_x, p.hull_min_y, p.hull_max_y}; },
            [](P& p, const std::vector<double>& v) {
              p.hull_min_x = v[0], p.hull_max_x = v[1], p.hull_min_y = v[2], p.hull_max_y = v[3];
            });
  return t;
}

void LidarConfig::validate() const {
  table().validate(*this);
  requireRange("max_range", max_range, min_range, 1e4);
  requireRange("max_z", max_z, min_z, 1e4);
}

Eigen::Matrix3d levelling(double roll, double pitch) {
  return (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

LidarTargetExtractor::LidarTargetExtractor(const LidarConfig& cfg) : cfg_(cfg) { cfg_.validate(); }

bool LidarTargetExtractor::checkLayout(const CloudView& c, LidarResult& r) {
  r.error = checkCloudLayout(c, r.message);
  if (r.error == CloudError::None) return true;
  counters_.increment(toString(r.error));
  return false;
}

std::size_t LidarTargetExtractor::find(std::size_t i) {
  while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
  return i;
}

bool LidarTargetExtractor::closeEnough(const Segment& a, const Segment& b) const {
  const float d = static_cast<float>(cfg_.layer_merge);
  if (a.minx > b.maxx + d || b.minx > a.maxx + d || a.miny > b.maxy + d || b.miny > a.maxy + d) return false;
  // Bounding boxes touch; confirm with points: up to 16 samples of the shorter segment against all of the
  // longer one (adjacent layers of one object are close everywhere, so a few samples suffice).
  const Segment& s = (a.end - a.begin) <= (b.end - b.begin) ? a : b;
  const Segment& l = (&s == &a) ? b : a;
  const auto& sp = layers_[s.layer];
  const auto& lp = layers_[l.layer];
  const std::uint32_t n = s.end - s.begin;
  const std::uint32_t samples = std::min<std::uint32_t>(n, 16);
  const float d2 = d * d;
  for (std::uint32_t k = 0; k < samples; ++k) {
    const P& p = sp[s.begin + (samples == 1 ? 0 : k * (n - 1) / (samples - 1))];
    for (std::uint32_t j = l.begin; j < l.end; ++j) {
      const float dx = p.x - lp[j].x, dy = p.y - lp[j].y;
      if (dx * dx + dy * dy <= d2) return true;
    }
  }
  return false;
}

LidarResult LidarTargetExtractor::extract(const CloudView& c, const Eigen::Matrix3d& level) {
  LidarResult r;
  if (!checkLayout(c, r)) return r;
  const bool organised = c.height > 1;
  const bool use_ring = !organised && c.ring.present && typeSize(c.ring.datatype) > 0 &&
                        c.ring.offset + typeSize(c.ring.datatype) <= c.point_step;
  const bool fast = c.x.datatype == std::uint8_t(FieldType::Float32) &&
                    c.y.datatype == std::uint8_t(FieldType::Float32) && c.z.datatype == std::uint8_t(FieldType::Float32);
  const std::size_t nlayers = organised ? c.height : (use_ring ? kMaxRings : 1);
  if (layers_.size() < nlayers) layers_.resize(nlayers);
  for (auto& l : layers_) l.clear();

  const bool hull = cfg_.hull_min_x < cfg_.hull_max_x && cfg_.hull_min_y < cfg_.hull_max_y;
  const double rmin2 = cfg_.min_range * cfg_.min_range, rmax2 = cfg_.max_range * cfg_.max_range;
  const bool tilted = !level.isIdentity(1e-12);
  std::size_t bad_ring = 0, non_finite = 0, used = 0;
  // each layer's scan position (the column of an organised cloud; the count so far in a layer of the buffer)
  beam_.assign(nlayers, 0);
  for (std::uint32_t row = 0; row < c.height; ++row) {
    const std::uint8_t* rp = c.data + std::size_t(row) * c.row_step;
    for (std::uint32_t col = 0; col < c.width; ++col) {
      const std::uint8_t* pp = rp + std::size_t(col) * c.point_step;
      double x, y, z;
      if (fast) {
        x = loadUnaligned<float>(pp + c.x.offset), y = loadUnaligned<float>(pp + c.y.offset);
        z = loadUnaligned<float>(pp + c.z.offset);
      } else {
        x = readField(pp + c.x.offset, c.x.datatype), y = readField(pp + c.y.offset, c.y.datatype);
        z = readField(pp + c.z.offset, c.z.datatype);
      }
      std::size_t layer = row;
      if (use_ring) {
        const double ring = readField(pp + c.ring.offset, c.ring.datatype);
        if (!(ring >= 0 && ring < kMaxRings)) {
          ++bad_ring;
          continue;
        }
        layer = static_cast<std::size_t>(ring);
      } else if (!organised) {
        layer = 0;
      }
      const std::uint32_t beam = beam_[layer]++;
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
        ++non_finite;  // no echo: normal for LiDARs, counted only in the result
        continue;
      }
      // the own hull moves with the sensor: tested before levelling
      if (hull && x >= cfg_.hull_min_x && x <= cfg_.hull_max_x && y >= cfg_.hull_min_y && y <= cfg_.hull_max_y)
        continue;
      if (tilted) {
        const Eigen::Vector3d l = level * Eigen::Vector3d(x, y, z);
        x = l.x(), y = l.y(), z = l.z();
      }
      const double r2 = x * x + y * y;
      if (r2 < rmin2 || r2 > rmax2 || z < cfg_.min_z || z > cfg_.max_z) continue;
      layers_[layer].push_back(P{float(x), float(y), float(z), beam});
      ++used;
    }
  }
  if (bad_ring) counters_.increment("bad_ring", bad_ring);
  r.points_in = std::size_t(c.width) * c.height;
  r.points_used = used;
  r.non_finite = non_finite;

  // Split each layer in scan order.
  segments_.clear();
  const float gap2 = float(cfg_.gap * cfg_.gap);
  for (std::uint32_t li = 0; li < nlayers; ++li) {
    const auto& pts = layers_[li];
    if (pts.empty()) continue;
    Segment s{li, 0, 0, pts[0].x, pts[0].x, pts[0].y, pts[0].y};
    for (std::uint32_t i = 0; i < pts.size(); ++i) {
      if (i > 0) {
        const float dx = pts[i].x - pts[i - 1].x, dy = pts[i].y - pts[i - 1].y;
        // an object returns on neighbouring beams: a run also ends where beams are skipped (a return among misses
        // is spray or foam, not the next part of the same object)
        if (dx * dx + dy * dy > gap2 || pts[i].beam - pts[i - 1].beam > std::uint32_t(cfg_.max_beam_gap)) {
          s.end = i;
          if (s.end - s.begin >= std::uint32_t(cfg_.min_run)) segments_.push_back(s);
          s = Segment{li, i, i, pts[i].x, pts[i].x, pts[i].y, pts[i].y};
        }
      }
      s.minx = std::min(s.minx, pts[i].x); s.maxx = std::max(s.maxx, pts[i].x);
      s.miny = std::min(s.miny, pts[i].y); s.maxy = std::max(s.maxy, pts[i].y);
    }
    s.end = static_cast<std::uint32_t>(pts.size());
    if (s.end - s.begin >= std::uint32_t(cfg_.min_run)) segments_.push_back(s);
  }
  parent_.resize(segments_.size());
  std::iota(parent_.begin(), parent_.end(), 0);

  // Wrap at the end of a 360-degree aperture: the last segment of a layer continues its first.
  for (std::size_t i = 0; i < segments_.size();) {
    std::size_t j = i;
    while (j + 1 < segments_.size() && segments_[j + 1].layer == segments_[i].layer) ++j;
    const auto& pts = layers_[segments_[i].layer];
    if (j > i && segments_[i].begin == 0 && segments_[j].end == pts.size()) {
      const float dx = pts.front().x - pts.back().x, dy = pts.front().y - pts.back().y;
      if (dx * dx + dy * dy <= gap2) parent_[find(j)] = find(i);
    }
    i = j + 1;
  }

  // Merge segments of different layers that touch: sweep over segments sorted by min x.
  order_.resize(segments_.size());
  std::iota(order_.begin(), order_.end(), 0);
  std::sort(order_.begin(), order_.end(), [this](std::size_t a, std::size_t b) { return segments_[a].minx < segments_[b].minx; });
  const float lm = float(cfg_.layer_merge);
  for (std::size_t oi = 0; oi < order_.size(); ++oi) {
    const Segment& a = segments_[order_[oi]];
    for (std::size_t oj = oi + 1; oj < order_.size(); ++oj) {
      const Segment& b = segments_[order_[oj]];
      if (b.minx > a.maxx + lm) break;
      if (a.layer == b.layer || find(order_[oi]) == find(order_[oj])) continue;
      if (closeEnough(a, b)) parent_[find(order_[oj])] = find(order_[oi]);
    }
  }

  // Gather clusters, describe them.
  std::vector<std::size_t> slot(segments_.size(), SIZE_MAX);
  std::size_t nclusters = 0;
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const std::size_t root = find(i);
    if (slot[root] == SIZE_MAX) slot[root] = nclusters++;
  }
  if (cluster_points_.size() < nclusters) cluster_points_.resize(nclusters);
  for (std::size_t k = 0; k < nclusters; ++k) cluster_points_[k].clear();
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    auto& out = cluster_points_[slot[find(i)]];
    const auto& pts = layers_[segments_[i].layer];
    for (std::uint32_t k = segments_[i].begin; k < segments_[i].end; ++k) out.emplace_back(pts[k].x, pts[k].y, pts[k].z);
  }
  std::vector<TargetGeometry> raw;
  now_.clear();
  for (std::size_t k = 0; k < nclusters; ++k) {
    const auto& pts = cluster_points_[k];
    if (pts.size() < static_cast<std::size_t>(cfg_.min_points)) continue;
    raw.push_back(describeTarget(pts, Eigen::Vector3d::Zero()));
    Seen box{float(pts[0].x()), float(pts[0].x()), float(pts[0].y()), float(pts[0].y()), 1};
    for (const auto& p : pts) {
      box.minx = std::min(box.minx, float(p.x())), box.maxx = std::max(box.maxx, float(p.x()));
      box.miny = std::min(box.miny, float(p.y())), box.maxy = std::max(box.maxy, float(p.y()));
    }
    now_.push_back(box);
  }
  confirm(raw, seen_, r);
  seen_.swap(now_);
  return r;
}

// Continues each target's streak from the last frame's target whose box lies within confirm_distance of its own
// (the sensor moves little in 80 ms: a metre covers 1.5 m/s and a turn at 30 m), and keeps those seen long enough.
void LidarTargetExtractor::confirm(std::vector<TargetGeometry>& raw, const std::vector<Seen>& last, LidarResult& r) {
  const float d = static_cast<float>(cfg_.confirm_distance);
  for (std::size_t i = 0; i < raw.size(); ++i) {
    Seen& b = now_[i];
    for (const Seen& p : last)
      if (b.minx <= p.maxx + d && p.minx <= b.maxx + d && b.miny <= p.maxy + d && p.miny <= b.maxy + d)
        b.streak = std::max(b.streak, std::min(p.streak + 1, cfg_.confirm_frames));
    if (b.streak >= cfg_.confirm_frames) r.targets.push_back(std::move(raw[i]));
    else ++r.unconfirmed;
  }
}

}  // namespace perception
}  // namespace offshore_gnc
