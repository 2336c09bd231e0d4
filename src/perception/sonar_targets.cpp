#include "offshore_gnc/perception/sonar_targets.h"

#include <cmath>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

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
      .integer("min_beams", &P::min_beams, 1, 10000, "targets seen in fewer beams are dropped (speckle)");
  return t;
}

void SonarConfig::validate() const { table().validate(*this); }

SonarTargetExtractor::SonarTargetExtractor(const SonarConfig& cfg) : cfg_(cfg) { cfg_.validate(); }

bool SonarTargetExtractor::detect(const SonarBeamView& b, double& range, std::uint8_t& intensity) const {
  int best = -1;
  std::size_t best_i = 0;
  for (std::size_t i = 0; i < b.num_bins; ++i) {
    const double r = b.range_offset + b.range_resolution * static_cast<double>(i);
    if (r < cfg_.min_range) continue;
    if (cfg_.max_range > 0.0 && r > cfg_.max_range) break;
    if (b.bins[i] > best) {
      best = b.bins[i];
      best_i = i;
    }
  }
  if (best < cfg_.threshold) return false;
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

SonarTargetExtractor::BeamStatus SonarTargetExtractor::addBeam(const SonarBeamView& b, const Eigen::Isometry3d& pose) {
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
  if (!detect(b, d.range, d.intensity)) {
    closeRun(false);
    return BeamStatus::NoDetection;
  }
  d.stamp = b.stamp;
  d.bearing = b.bearing;
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
  for (const auto& r : runs_)
    if (static_cast<int>(r.d.size()) >= cfg_.min_beams) current_.targets.push_back(makeTarget(r.d));
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
