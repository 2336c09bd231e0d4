// The AUV's mission (AuvMission): the search over its coverage path, the hold at depth, the ascent, the surface.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "mission_internal.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/guidance/paths.h"

namespace offshore_gnc {
namespace mission {

namespace {
const Eigen::Vector3d kNoPoint3 = Eigen::Vector3d::Constant(kNaN);

// holdPath at p's depth: guidance holds the end of a path, its depth too.
std::vector<Eigen::Vector3d> holdPath3(const Eigen::Vector3d& p, double heading) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& w : holdPath(p.head<2>(), heading)) out.emplace_back(w.x(), w.y(), p.z());
  return out;
}
}  // namespace

const ParamTable<CoverageArea>& CoverageArea::table() {
  using P = CoverageArea;
  static const ParamTable<P> t = ParamTable<P>()
      .number("north_min", &P::north_min, -1e5, 1e5, "m", "southern edge of the search area (local NED)")
      .number("north_max", &P::north_max, -1e5, 1e5, "m", "northern edge")
      .number("east_min", &P::east_min, -1e5, 1e5, "m", "western edge")
      .number("east_max", &P::east_max, -1e5, 1e5, "m", "eastern edge")
      .number("depth", &P::depth, 0.0, 1000.0, "m", "depth of the coverage")
      .number("spacing", &P::spacing, 0.5, 1000.0, "m", "distance between the lawnmower's tracks")
      .number("second_depth", &P::second_depth, 0.0, 1000.0, "m",
              "when > 0, the lawnmower is flown back at this depth if the first pass found nothing (0: one pass)");
  return t;
}

void CoverageArea::validate() const {
  table().validate(*this, "coverage/");
  if (!(north_max > north_min) || !(east_max >= east_min))
    throw ConfigError("parameter 'coverage' is an empty rectangle (north " + std::to_string(north_min) + ".." +
                      std::to_string(north_max) + ", east " + std::to_string(east_min) + ".." +
                      std::to_string(east_max) + ")");
}

const ParamTable<AuvMissionParams>& AuvMissionParams::table() {
  using P = AuvMissionParams;
  static const ParamTable<P> t = ParamTable<P>()
      .integer("confirm_detections", &P::confirm_detections, 1, 100, "sonar sweeps that must see the same object")
      .number("confirm_radius", &P::confirm_radius, 0.1, 50.0, "m", "detections closer than this are one object")
      .number("detection_max_age", &P::detection_max_age, 1.0, 1e5, "s", "unconfirmed detections older are forgotten")
      .number("search_margin", &P::search_margin, 0.0, 1000.0, "m",
              "detections farther than this outside the coverage area are not its target (moorings, hulls met on the way)")
      .number("start_delay", &P::start_delay, 0.0, 3600.0, "s", "the search starts this long after start-up")
      .number("hold_standoff", &P::hold_standoff, 0.0, 50.0, "m",
              "after the find, hold at depth this far from the target on the line from the find, facing it")
      .number("refine_distance", &P::refine_distance, 0.05, 50.0, "m",
              "while holding, the refined target is resent once it moved this far from the one sent")
      .number("hold_timeout", &P::hold_timeout, 1.0, 1e5, "s", "holding this long without the USV's arrival: ascend")
      .number("usv_timeout", &P::usv_timeout, 1.0, 1e5, "s",
              "holding without the USV's mission status this long (link lost, its stack dead): ascend")
      .number("ascent_rate", &P::ascent_rate, 0.01, 2.0, "m/s", "the depth reference rises at most this fast")
      .number("surface_depth", &P::surface_depth, 0.05, 5.0, "m", "shallower than this the AUV is at the surface")
      .number("surface_clearance", &P::surface_clearance, 0.0, 500.0, "m",
              "surface at least this far from where the USV holds or is bound by its last status (moving at depth first)")
      .number("overhead_clearance", &P::overhead_clearance, 0.0, 500.0, "m",
              "ascending, hold the depth while the USV (its reported position) is closer than this")
      .number("station_radius", &P::station_radius, 0.1, 50.0, "m",
              "on station at its hold point, and stationary at the surface, within this")
      .number("still_window", &P::still_window, 1.0, 600.0, "s",
              "at the surface also stationary when its position stayed within station_radius of their mean this long, "
              "and moved less than that over it, on GPS fixes (the latest within it)");
  return t;
}

void AuvMissionParams::validate() const {
  table().validate(*this, "mission/");
  coverage.validate();
}

std::vector<Eigen::Vector3d> coveragePath(const CoverageArea& a) {
  if (!(a.north_max > a.north_min)) return {};
  std::vector<Eigen::Vector3d> path = guidance::lawnmower(
      {a.north_min, a.east_min}, 0.0, a.north_max - a.north_min, a.east_max - a.east_min, a.spacing, a.depth);
  if (a.second_depth > 0.0 && path.size() >= 2) {
    // back along the same tracks, from the last track's start: that track is flown again while changing depth
    const std::size_t n = path.size();
    path.reserve(2 * n - 1);
    for (std::size_t i = n - 1; i-- > 0;) path.emplace_back(path[i].x(), path[i].y(), a.second_depth);
  }
  return path;
}


AuvMission::AuvMission(const AuvMissionParams& p)
    : p_(p), hold_(kNoPoint3), detection_time_(kNaN), on_station_since_(kNaN), ascent_t_(kNaN), surfaced_t_(kNaN) {
  p_.validate();
}

void AuvMission::tick(double t) {
  if (!ticked_) {
    ticked_ = true;
    first_tick_ = t;
  }
  if (phase_ == AuvPhase::Idle && t - first_tick_ >= p_.start_delay) start(t);
  if (phase_ == AuvPhase::NoTarget) ascend(t, "the search ended without a target");
  if (phase_ == AuvPhase::TargetFound) {
    std::ostringstream why;
    if (t - found_t_ >= p_.hold_timeout) {
      why << "held " << p_.hold_timeout << " s without the USV's arrival";
      ascend(t, why.str());
    } else if (t - std::max(found_t_, usv_t_) >= p_.usv_timeout) {
      why << "no status from the USV for " << p_.usv_timeout << " s";
      ascend(t, why.str());
    }
  }
  if (phase_ != AuvPhase::Ascent) return;
  if (clearing_) {  // first clear of the USV at depth: at its point, or as far from the USV (a loose hold gets there)
    if (!pose_ || ((pose_->head<2>() - hold_.head<2>()).norm() > p_.station_radius &&
                   (pose_->head<2>() - *usv_).norm() < p_.surface_clearance - p_.station_radius))
      return;
    clearing_ = false;
    ramp_t_ = t;
  }
  // the USV over the AUV (a fresh report): the depth held until it has gone (not the supervisor's surface, with no
  // USV status to judge by, nor a vehicle already at the surface)
  if (mind_usv_ && usv_pos_ && pose_ && t - usv_t_ <= p_.usv_timeout && pose_->z() >= p_.surface_depth &&
      (pose_->head<2>() - *usv_pos_).norm() < p_.overhead_clearance) {
    counters_.increment("ascent_paused_usv_overhead");
    ramp_t_ = t;
    return;
  }
  double d = std::max(0.0, depth_ref_ - p_.ascent_rate * (t - ramp_t_));
  ramp_t_ = t;
  // a vehicle the safety supervisor already brought up is not sent down again (1 m: far beyond the depth
  // controller's lag behind the ramp, which must not pull the ramp up after the vehicle)
  if (pose_ && pose_->z() < d - 1.0) d = std::max(0.0, pose_->z());
  if (d != depth_ref_) {
    depth_ref_ = hold_.z() = d;
    hold(hold_, t);
  }
  if (depth_ref_ <= 0.0 && pose_ && pose_->z() < p_.surface_depth) {
    phase_ = AuvPhase::Surfaced;
    surfaced_t_ = t;
  }
}

void AuvMission::hold(const Eigen::Vector3d& point, double /*t*/) { path_due_ = holdPath3(point, hold_heading_); }

void AuvMission::ascend(double t, const std::string& why, bool clear_of_usv) {
  phase_ = AuvPhase::Ascent;
  ascent_t_ = ramp_t_ = t;
  why_ascent_ = why;
  const Eigen::Vector3d at = pose_ ? *pose_ : hold_;
  if (!at.allFinite()) {  // nowhere known to hold: up where it is, on the supervisor's surface hold
    depth_ref_ = 0.0;
    path_due_ = std::vector<Eigen::Vector3d>();
    return;
  }
  depth_ref_ = std::max(0.0, at.z());
  // up where it holds (the spot), or where it is when it was not holding one
  Eigen::Vector2d up = hold_.allFinite() ? Eigen::Vector2d(hold_.head<2>()) : Eigen::Vector2d(at.head<2>());
  const Eigen::Vector2d away = up - (usv_ ? *usv_ : up);
  mind_usv_ = clear_of_usv;
  clearing_ = clear_of_usv && usv_ && away.norm() < p_.surface_clearance;
  if (clearing_) {  // surface clear of the USV's hull: move away from it at depth first, facing the way
    const Eigen::Vector2d dir = away.norm() > 1e-3 ? Eigen::Vector2d(away.normalized())
                                                   : Eigen::Vector2d(std::cos(yaw_), std::sin(yaw_));
    up = *usv_ + p_.surface_clearance * dir;
    hold_heading_ = std::atan2(dir.y(), dir.x());
  }
  hold_ = Eigen::Vector3d(up.x(), up.y(), depth_ref_);
  auto path = clearing_ ? guidance::straightLine({at.x(), at.y(), depth_ref_}, hold_) : std::vector<Eigen::Vector3d>();
  if (path.size() >= 2) path_due_ = std::move(path);
  else hold(hold_, t);
}

void AuvMission::onPose(const Eigen::Vector3d& ned, double yaw, double t) {
  if (!ned.allFinite() || !std::isfinite(yaw)) {
    counters_.increment("pose_not_finite");
    return;
  }
  pose_ = ned;
  yaw_ = yaw;
  if (phase_ == AuvPhase::TargetFound && std::isnan(on_station_since_) &&
      (ned.head<2>() - hold_.head<2>()).norm() <= p_.station_radius)
    on_station_since_ = t;
  steady_ = false;
  if (phase_ != AuvPhase::Surfaced && phase_ != AuvPhase::Recovered) {
    surface_track_.clear();
    return;
  }
  surface_track_.emplace_back(t, ned.head<2>());
  while (surface_track_.size() > 1 && surface_track_[1].first <= t - p_.still_window) surface_track_.pop_front();
  if (t - surface_track_.front().first < p_.still_window) return;  // not watched that long yet
  if (t - surface_fix_t_ > p_.still_window) return;                 // on the USBL alone: steady says nothing
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& s : surface_track_) mean += s.second;
  mean /= static_cast<double>(surface_track_.size());
  // and not creeping: a Girona500 facing a push it could not quite hold drifted 1.4 m in the window, all within 1 m
  // of the mean; called stationary, it came down onto the USV closing in (tuning seed 32 run 262)
  steady_ = std::all_of(surface_track_.begin(), surface_track_.end(),
                        [&](const auto& s) { return (s.second - mean).norm() <= p_.station_radius; }) &&
            (surface_track_.back().second - surface_track_.front().second).norm() <= p_.station_radius;
}

void AuvMission::onUsvStatus(UsvPhase phase, const Eigen::Vector2d& usv_ned, const Eigen::Vector2d& usv_station,
                             double t) {
  usv_t_ = t;
  usv_phase_ = phase;
  if (usv_station.allFinite()) usv_ = usv_station;
  else if (usv_ned.allFinite()) usv_ = usv_ned;
  if (usv_ned.allFinite()) usv_pos_ = usv_ned;
  const bool arrived = phase == UsvPhase::Arrived || phase == UsvPhase::Recovery || phase == UsvPhase::Recovered;
  if (phase_ == AuvPhase::TargetFound && arrived) ascend(t, "the USV has arrived");
  if (phase_ == AuvPhase::Surfaced && phase == UsvPhase::Recovered) phase_ = AuvPhase::Recovered;
}

void AuvMission::onSafetySurface(double t) {
  if (phase_ == AuvPhase::TargetFound || phase_ == AuvPhase::NoTarget)
    ascend(t, "the safety supervisor surfaced it", false);
}

bool AuvMission::stationary() const {
  // Not without a fix: an aColor at the surface lost its USBL fixes with the USV 12 m off, reckoned itself on its
  // point while its hold drifted at 0.7 m/s before a 7.7 m/s wind, and the USV closed in onto it (evaluation seed
  // 17000 run 463, 2026-12-06).
  return (phase_ == AuvPhase::Surfaced || phase_ == AuvPhase::Recovered) && pose_ && !fix_lost_ &&
         ((pose_->head<2>() - hold_.head<2>()).norm() <= p_.station_radius || steady_);
}

void AuvMission::start(double t) {
  if (phase_ != AuvPhase::Idle) return;
  phase_ = AuvPhase::Coverage;
  start_time_ = t;
  path_due_ = coveragePath(p_.coverage);
}

void AuvMission::onGuidance(guidance::Mode mode, double t) {
  if (phase_ != AuvPhase::Coverage) return;
  if (mode == guidance::Mode::kFollowPath) following_ = true;
  if (following_ && mode == guidance::Mode::kStationKeeping) onCoverageFinished(t);
}

std::optional<std::vector<Eigen::Vector3d>> AuvMission::takePath() {
  auto p = std::move(path_due_);
  path_due_.reset();
  return p;
}

std::optional<Eigen::Vector3d> AuvMission::takeTarget() {
  auto p = target_due_;
  target_due_.reset();
  return p;
}

bool AuvMission::onDetection(const Eigen::Vector3d& p, double t) {
  if (!p.allFinite() || !std::isfinite(t)) {
    counters_.increment("detection_not_finite");
    return false;
  }
  if (phase_ == AuvPhase::TargetFound) {
    refine(p, t);
    return false;
  }
  if (phase_ != AuvPhase::Coverage) {
    counters_.increment("detection_outside_search");
    return false;
  }
  // The target is in the area searched: a mooring or a hull the sonar met on the way there is not it (a buoy's
  // mooring 5 m from the start, seen twice as the AUV dived, was "found" 38 m from the target).
  const CoverageArea& a = p_.coverage;
  const double out_n = std::max({a.north_min - p.x(), p.x() - a.north_max, 0.0});
  const double out_e = std::max({a.east_min - p.y(), p.y() - a.east_max, 0.0});
  if (std::hypot(out_n, out_e) > p_.search_margin) {
    counters_.increment("detection_outside_area");
    return false;
  }
  counters_.increment("detections");
  // forget stale candidates, so that clutter seen once long ago cannot confirm a new one
  for (auto it = clusters_.begin(); it != clusters_.end();)
    it = (t - it->last_t > p_.detection_max_age) ? clusters_.erase(it) : it + 1;
  Cluster* best = nullptr;
  double best_d = p_.confirm_radius;
  for (auto& c : clusters_) {
    const double d = (c.mean() - p).norm();
    if (d <= best_d) best_d = d, best = &c;
  }
  if (!best) {
    clusters_.emplace_back();
    best = &clusters_.back();
  }
  best->sum += p;
  best->n += 1;
  best->last_t = t;
  if (best->n < p_.confirm_detections) return false;
  confirmed_ = *best;
  target_ = target_due_ = target_sent_ = best->mean();
  detection_time_ = t - start_time_;
  found_t_ = t;
  phase_ = AuvPhase::TargetFound;
  // Keep the spot: hold_standoff from the target on the line from where the vehicle is, facing it (the sonar's
  // sector looks ahead: it goes on seeing the target), at the depth it searched at.
  const Eigen::Vector3d& tg = *target_;
  const Eigen::Vector2d from = pose_ ? Eigen::Vector2d(pose_->head<2>() - tg.head<2>()) : Eigen::Vector2d::Zero();
  const Eigen::Vector2d dir = from.norm() > 1e-3 ? Eigen::Vector2d(from.normalized()) : Eigen::Vector2d::Zero();
  hold_heading_ = from.norm() > 1e-3 ? std::atan2(-dir.y(), -dir.x()) : yaw_;
  const Eigen::Vector2d h = tg.head<2>() + p_.hold_standoff * dir;
  hold_ = Eigen::Vector3d(h.x(), h.y(), pose_ ? pose_->z() : p_.coverage.depth);
  hold(hold_, t);
  return true;
}

void AuvMission::refine(const Eigen::Vector3d& p, double /*t*/) {
  if ((p - *target_).norm() > p_.confirm_radius) {  // another object, or clutter: the target stays as it is
    counters_.increment("detection_other_object");
    return;
  }
  confirmed_.sum += p;
  confirmed_.n += 1;
  target_ = confirmed_.mean();
  counters_.increment("target_refinements");
  if ((*target_ - *target_sent_).norm() >= p_.refine_distance) {
    target_due_ = target_sent_ = target_;
    counters_.increment("target_resent");
  }
}

void AuvMission::onCoverageFinished(double t) {
  if (phase_ != AuvPhase::Coverage) return;
  phase_ = AuvPhase::NoTarget;
  found_t_ = t;
  hold_heading_ = yaw_;
  if (pose_) {  // keep where it is until the next tick sends it up
    hold_ = *pose_;
    hold(hold_, t);
  } else {
    path_due_ = std::vector<Eigen::Vector3d>();
  }
}

std::string AuvMission::detail() const {
  std::ostringstream os;
  switch (phase_) {
    case AuvPhase::Idle: os << "waiting to start"; break;
    case AuvPhase::Coverage: os << "searching, " << clusters_.size() << " unconfirmed candidate(s)"; break;
    case AuvPhase::TargetFound:
      os << "target confirmed at N " << (*target_)(0) << " E " << (*target_)(1) << " D " << (*target_)(2)
         << " after " << detection_time_ << " s (" << confirmed_.n << " detections); holding at N " << hold_.x()
         << " E " << hold_.y() << " D " << hold_.z() << ", " << p_.hold_standoff << " m from it";
      break;
    case AuvPhase::NoTarget: os << "coverage finished without a confirmed detection"; break;
    case AuvPhase::Ascent:
      os << "ascending (" << why_ascent_ << "): ";
      if (clearing_) os << "first clear of the USV at depth, to N " << hold_.x() << " E " << hold_.y();
      else os << "depth reference " << depth_ref_ << " m, rising at " << p_.ascent_rate << " m/s";
      break;
    case AuvPhase::Surfaced:
      os << "at the surface, holding at N " << hold_.x() << " E " << hold_.y();
      if (pose_) os << " (" << (pose_->head<2>() - hold_.head<2>()).norm() << " m off it)";
      os << (stationary() ? ", on it" : "") << "; waiting to be recovered";
      break;
    case AuvPhase::Recovered: os << "recovered: the USV holds beside it"; break;
  }
  if (noTarget() && phase_ != AuvPhase::NoTarget) os << "; the search ended without a confirmed detection";
  return os.str();
}

}  // namespace mission
}  // namespace offshore_gnc
