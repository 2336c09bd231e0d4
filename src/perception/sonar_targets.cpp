#include "offshore_gnc/perception/sonar_targets.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/perception/wall_detection.h"

namespace offshore_gnc {
namespace perception {

const ParamTable<SonarConfig>& SonarConfig::table() {
  using P = SonarConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("min_range", &P::min_range, 0.0, 1e3, "m", "Algorithm 1: bins closer than this are ignored")
      .number("max_range", &P::max_range, 0.0, 1e3, "m", "bins farther are ignored (0 = every bin)")
      .integer("threshold", &P::threshold, 0, 255, "intensity the strongest bin must reach")
      .degrees("max_beam_gap_deg", &P::max_beam_gap, 0.01, 180.0,
               "a larger bearing step between detections starts a new target")
      .number("max_range_jump", &P::max_range_jump, 1e-3, 1e3, "m",
              "a larger range step between consecutive beams starts a new target")
      .integer("min_beams", &P::min_beams, 1, 10000, "targets seen in fewer beams are dropped (speckle)")
      .number("min_width", &P::min_width, 0.0, 100.0, "m",
              "narrower targets, the beam's width taken off, are point scatterers (mooring lines, fish): dropped")
      .number("cfar_factor", &P::cfar_factor, 0.0, 100.0, "",
              "a bin must reach this times the louder side's training mean (greatest-of CFAR; 0 = off)")
      .number("cfar_window", &P::cfar_window, 0.01, 100.0, "m", "CFAR training cells on each side")
      .number("cfar_guard", &P::cfar_guard, 0.0, 100.0, "m", "CFAR guard cells between a bin and its training cells")
      .degrees("vertical_beam_deg", &P::vertical_beam, 0.0, 90.0,
               "the sonar's vertical beam width (0 = no surface gate)")
      .number("surface_clearance", &P::surface_clearance, 0.0, 100.0, "m",
              "surface gate: the deepest hull draft (and wave trough) under the surface")
      .number("wall_margin", &P::wall_margin, 0.0, 100.0, "m",
              "a target mostly within this of a wall found in the sweep (2 m or longer) is part of it (0 = off)");
  return t;
}

void SonarConfig::validate() const { table().validate(*this); }

SonarTargetExtractor::SonarTargetExtractor(const SonarConfig& cfg) : cfg_(cfg) { cfg_.validate(); }

double SonarTargetExtractor::surfaceGate(double depth, double elevation) const {
  const double upper = elevation + 0.5 * cfg_.vertical_beam;
  if (cfg_.vertical_beam <= 0.0 || !std::isfinite(depth) || !(upper > 0.0)) return std::numeric_limits<double>::infinity();
  return std::max(0.0, depth - cfg_.surface_clearance) / std::sin(std::min(upper, kPi / 2));
}

bool SonarTargetExtractor::detect(const SonarBeamView& b, double& range, std::uint8_t& intensity,
                                  double gate) const {
  // CFAR training means from running sums: bins [i - guard - window, i - guard) and (i + guard, i + guard + window]
  const auto n = static_cast<long>(b.num_bins);
  const long guard = std::lround(cfg_.cfar_guard / b.range_resolution);
  const long window = std::max(1L, std::lround(cfg_.cfar_window / b.range_resolution));
  cumulative_.assign(b.num_bins + 1, 0.0);
  for (long i = 0; i < n; ++i) cumulative_[i + 1] = cumulative_[i] + b.bins[i];
  auto mean = [&](long lo, long hi) {  // of bins [lo, hi), clipped; NaN when empty
    lo = std::max(0L, lo), hi = std::min(n, hi);
    return hi > lo ? (cumulative_[hi] - cumulative_[lo]) / double(hi - lo) : std::numeric_limits<double>::quiet_NaN();
  };
  int best = -1;
  long best_i = 0;
  for (long i = 0; i < n; ++i) {
    const double r = b.range_offset + b.range_resolution * static_cast<double>(i);
    if (r < cfg_.min_range) continue;
    if ((cfg_.max_range > 0.0 && r > cfg_.max_range) || r > gate) break;
    if (b.bins[i] <= best || b.bins[i] < cfg_.threshold) continue;
    if (cfg_.cfar_factor > 0.0) {
      const double lead = mean(i - guard - window, i - guard), trail = mean(i + guard + 1, i + guard + window + 1);
      // the louder side: reverberation rises with range where the surface or the bottom enters the beam, and a
      // bin on that rise must stand out of what follows it too (greatest-of CFAR)
      const double background = std::isnan(lead) ? trail : (std::isnan(trail) ? lead : std::max(lead, trail));
      if (!std::isnan(background) && b.bins[i] < cfg_.cfar_factor * background) continue;
    }
    best = b.bins[i];
    best_i = i;
  }
  if (best < 0) return false;
  range = b.range_offset + b.range_resolution * static_cast<double>(best_i);
  intensity = static_cast<std::uint8_t>(best);
  return true;
}

bool SonarTargetExtractor::adjacent(const SonarDetection& a, const SonarDetection& b) const {
  return std::abs(angleDiff(a.bearing, b.bearing)) <= cfg_.max_beam_gap &&
         std::abs(a.range - b.range) <= cfg_.max_range_jump;
}

bool SonarTargetExtractor::check(const SonarBeamView& b) {
  if (b.num_bins == 0 || b.bins == nullptr) {
    counters_.increment("empty_beam");
    return false;
  }
  if (!std::isfinite(b.bearing) || b.bearing < 0.0 || b.bearing >= 2.0 * kPi) {
    counters_.increment("bad_bearing");
    return false;
  }
  if (!std::isfinite(b.range_resolution) || b.range_resolution <= 0.0 || !std::isfinite(b.range_offset) ||
      !std::isfinite(b.stamp)) {
    counters_.increment("bad_beam_geometry");
    return false;
  }
  return true;
}

SonarTargetExtractor::BeamStatus SonarTargetExtractor::addBeam(const SonarBeamView& b, const Eigen::Isometry3d& pose,
                                                               double head_depth) {
  if (!check(b)) return BeamStatus::Rejected;
  if (!pose.matrix().allFinite()) {
    counters_.increment("bad_pose");
    return BeamStatus::Rejected;
  }
  if ((b.status & (kFault | kCentring)) || !(b.status & kHeadReady)) {
    counters_.increment("head_not_ready");
    closeRun(false);  // the run of consecutive beams is broken
    return BeamStatus::HeadNotReady;
  }

  if (have_prev_) {
    const double step = angleDiff(b.bearing, prev_bearing_);
    const int dir = step > 1e-9 ? 1 : (step < -1e-9 ? -1 : 0);
    const bool reversal = (b.status & kSectorReverse) || (direction_ != 0 && dir != 0 && dir != direction_);
    if (reversal) {
      finishSweep(false);
    } else if (current_.swept_angle + std::abs(step) >= 2.0 * kPi - 1e-9) {
      finishSweep(true);
    } else {
      current_.swept_angle += std::abs(step);
    }
    if (dir != 0) direction_ = dir;
  }
  have_prev_ = true;
  prev_bearing_ = b.bearing;
  if (current_.beams == 0) current_.start_stamp = b.stamp;
  current_.end_stamp = b.stamp;
  const bool first_beam = current_.beams == 0;
  ++current_.beams;

  SonarDetection d;
  const Eigen::Vector3d axis = pose.linear() * Eigen::Vector3d(std::cos(b.bearing), std::sin(b.bearing), 0.0);
  const double elevation = std::asin(std::clamp(z_up_ ? axis.z() : -axis.z(), -1.0, 1.0));
  if (!detect(b, d.range, d.intensity, surfaceGate(head_depth, elevation))) {
    closeRun(false);
    return BeamStatus::NoDetection;
  }
  d.stamp = b.stamp;
  d.bearing = b.bearing;
  d.beam_width = b.beam_width;
  // Sonar head frame: x forward, y starboard, z down; bearing clockwise from x.
  d.sensor = pose.translation();
  d.point = pose * Eigen::Vector3d(d.range * std::cos(b.bearing), d.range * std::sin(b.bearing), 0.0);
  current_.detections.push_back(d);
  if (!run_.d.empty() && !adjacent(run_.d.back(), d)) closeRun(false);
  if (run_.d.empty()) run_.at_start = first_beam;
  run_.d.push_back(d);
  return BeamStatus::Detection;
}

void SonarTargetExtractor::closeRun(bool at_end) {
  if (run_.d.empty()) return;
  run_.at_end = at_end;
  runs_.push_back(std::move(run_));
  run_ = Run{};
}

SonarTarget SonarTargetExtractor::makeTarget(const std::vector<SonarDetection>& d) const {
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(d.size());
  Eigen::Vector3d sensor = Eigen::Vector3d::Zero();
  for (const auto& x : d) {
    pts.push_back(x.point);
    sensor += x.sensor;
  }
  sensor /= static_cast<double>(d.size());
  SonarTarget t;
  t.geometry = describeTarget(pts, sensor);
  // The sonar measures range per beam: the nearest return is the shortest beam range, not a re-projection.
  const SonarDetection* nearest = &d.front();
  for (const auto& x : d)
    if (x.range < nearest->range) nearest = &x;
  t.geometry.nearest = nearest->point;
  t.geometry.range = nearest->range;
  t.first_bearing = d.front().bearing;
  t.last_bearing = d.back().bearing;
  t.geometry.bearing = wrapTwoPi(t.first_bearing + 0.5 * angleDiff(t.last_bearing, t.first_bearing));
  t.stamp = d[d.size() / 2].stamp;
  return t;
}

double SonarTargetExtractor::width(const std::vector<SonarDetection>& d) {
  // world bearings from the sensor, relative to the first (the sweep is under 2 pi): their span is what the beam
  // swept over the object, which for a point is the beam's width (plus up to one step either side)
  const auto bearing = [](const SonarDetection& x) { return std::atan2(x.point.y() - x.sensor.y(), x.point.x() - x.sensor.x()); };
  const double b0 = bearing(d.front());
  double lo = 0.0, hi = 0.0, range = d.front().range;
  for (const auto& x : d) {
    const double a = angleDiff(bearing(x), b0);
    lo = std::min(lo, a), hi = std::max(hi, a);
    range = std::min(range, x.range);
  }
  return range * std::max(0.0, hi - lo - d.front().beam_width);
}

void SonarTargetExtractor::finishSweep(bool full_turn) {
  closeRun(true);
  current_.full_turn = full_turn;
  // A full turn starts and ends at the same bearing: a target across that bearing is one target.
  if (full_turn && runs_.size() >= 2 && runs_.front().at_start && runs_.back().at_end &&
      adjacent(runs_.back().d.back(), runs_.front().d.front())) {
    auto& last = runs_.back().d;
    last.insert(last.end(), runs_.front().d.begin(), runs_.front().d.end());
    runs_.erase(runs_.begin());
  }
  std::vector<WallSegment> walls;
  if (cfg_.wall_margin > 0.0 && !runs_.empty()) {
    std::vector<Eigen::Vector2d> points;
    points.reserve(current_.detections.size());
    for (const auto& x : current_.detections) points.push_back(x.point.head<2>());
    walls = extractWalls(points, WallConfig{});
  }
  const auto on_wall = [&](const std::vector<SonarDetection>& d) {
    std::size_t near = 0;
    for (const auto& x : d)
      for (const auto& w : walls) {
        if (w.length() < WallConfig{}.min_length) continue;
        const Eigen::Vector2d ab = w.b - w.a, p = x.point.head<2>();
        const double f = std::clamp((p - w.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        if ((w.a + f * ab - p).norm() <= cfg_.wall_margin) {
          ++near;
          break;
        }
      }
    return 2 * near >= d.size();
  };
  for (const auto& r : runs_) {
    if (static_cast<int>(r.d.size()) < cfg_.min_beams) continue;
    if (width(r.d) < cfg_.min_width) {
      counters_.increment("point_scatterers");
      continue;
    }
    if (!walls.empty() && on_wall(r.d)) {
      counters_.increment("wall_pieces");
      continue;
    }
    current_.targets.push_back(makeTarget(r.d));
  }
  runs_.clear();
  done_ = std::move(current_);
  current_ = SonarSweep{};
  ready_ = true;
}

void SonarTargetExtractor::flush() {
  if (current_.beams > 0) finishSweep(false);
}

SonarSweep SonarTargetExtractor::takeSweep() {
  ready_ = false;
  SonarSweep s = std::move(done_);
  done_ = SonarSweep{};
  return s;
}

}  // namespace perception
}  // namespace offshore_gnc
