#include "offshore_gnc/guidance/obstacle_memory.h"

#include <algorithm>
#include <cmath>

namespace offshore_gnc {
namespace guidance {

const ParamTable<ObstacleMemoryParams>& ObstacleMemoryParams::table() {
  using P = ObstacleMemoryParams;
  static const ParamTable<P> t = ParamTable<P>()
      .number("obstacle_timeout", &P::timeout, 0.1, 3600.0, "s",
              "no obstacle frame for this long: the obstacles are dropped at the next replan")
      .number("obstacle_memory", &P::memory, 0.0, 86400.0, "s",
              "an obstacle out of the sensor's view (astern, beside the hull) is kept this long after last seen")
      .integer("confirm_frames", &P::confirm_frames, 1, 1000,
               "an obstacle is kept out of view only when seen in this many frames")
      .number("match_gap", &P::match_gap, 0.0, 100.0, "m",
              "a target this close to a kept obstacle's extent is that obstacle seen again")
      .number("extent_hold", &P::extent_hold, 0.0, 3600.0, "s",
              "an obstacle seen again keeps the largest extent it had over this long (0: each frame's own)")
      .number("clear_time", &P::clear_time, 0.0, 3600.0, "s",
              "an obstacle in the sensor's view but not in its frames, or one not yet seen in confirm_frames frames, is "
              "dropped after missing this long (0: at once)")
      .number("sensor_ahead", &P::sensor_ahead, -100.0, 100.0, "m",
              "the obstacle sensor (LiDAR) ahead of the reference point")
      .degrees("sensor_aperture_deg", &P::sensor_aperture, 0.0, 360.0,
               "the obstacle sensor's horizontal field of view, centred on the bow")
      .number("sensor_near", &P::sensor_near, 0.0, 1000.0, "m",
              "nearer than this to the sensor an obstacle may be missed even in its field of view");
  return t;
}

void ObstacleMemoryParams::validate() const { table().validate(*this, "sbb/"); }

ObstacleMemory::ObstacleMemory(const ObstacleMemoryParams& p) : p_(p) { p_.validate(); }

void ObstacleMemory::setParams(const ObstacleMemoryParams& p) {
  p.validate();
  p_ = p;
}

bool ObstacleMemory::inView(const Eigen::Vector2d& q, const Eigen::Vector2d& position, double yaw) const {
  if (!position.allFinite() || !std::isfinite(yaw)) return false;  // nowhere to look from: nothing is cleared
  const Eigen::Vector2d bow(std::cos(yaw), std::sin(yaw));
  const Eigen::Vector2d d = q - (position + p_.sensor_ahead * bow);
  if (d.norm() < p_.sensor_near) return false;
  const double bearing = std::atan2(bow.x() * d.y() - bow.y() * d.x(), bow.dot(d));
  return std::abs(bearing) <= 0.5 * p_.sensor_aperture;
}

void ObstacleMemory::update(const std::vector<SbbObstacle>& seen, const Eigen::Vector2d& position, double yaw,
                            double t) {
  auto reach = [](const SbbObstacle& o) { return 0.5 * std::max(o.length, o.width); };
  std::vector<Kept> next;
  next.reserve(seen.size() + kept_.size());
  for (const auto& s : seen) next.push_back({s, t, 1, 2.0 * reach(s), t, -1.0});
  remembered_ = 0;
  for (auto& k : kept_) {
    // seen again: the frame's targets stand for it, and inherit its count (a cluster that splits or merges
    // keeps its history) and the largest extent it had within extent_hold (matched on the frame's own extent)
    bool again = false;
    for (std::size_t i = 0; i < seen.size(); ++i)
      if ((seen[i].origin - k.o.origin).norm() <= reach(seen[i]) + reach(k.o) + p_.match_gap) {
        next[i].frames = std::max(next[i].frames, k.frames + 1);
        if (k.extent > next[i].extent && t - k.extent_t <= p_.extent_hold) {
          next[i].extent = k.extent;
          next[i].extent_t = k.extent_t;
        }
        again = true;
      }
    if (again) continue;
    // not in this frame: kept out of view if it was there for certain, and where the sensor looks, or while it is
    // not yet certain, only until it has been missed for clear_time (a low buoy flickers in and out of the lowest
    // layer as the boat pitches; 25 m off, it came in one frame of three, was dropped at each miss before its count
    // reached confirm_frames, and the detour round it came and went 32 times in 14 s: the default scenario, seed 1)
    if (t - k.seen_t > p_.memory) continue;
    if (k.frames < p_.confirm_frames || inView(k.o.origin, position, yaw)) {
      if (k.missed_t < 0.0) k.missed_t = t;
      if (t - k.missed_t >= p_.clear_time) continue;
    }
    ++remembered_;
    next.push_back(k);
  }
  kept_ = std::move(next);
  frame_t_ = t;
}

std::vector<SbbObstacle> ObstacleMemory::active(double t) const {
  std::vector<SbbObstacle> out;
  if (t - frame_t_ > p_.timeout) return out;
  for (const auto& k : kept_) {
    SbbObstacle o = k.o;
    if (k.extent > std::max(o.length, o.width)) o.length = o.width = k.extent;
    out.push_back(o);
  }
  return out;
}

}  // namespace guidance
}  // namespace offshore_gnc
