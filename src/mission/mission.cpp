#include "offshore_gnc/mission/mission.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/geometry.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/guidance/paths.h"

namespace offshore_gnc {
namespace mission {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const Eigen::Vector3d kNoPoint3 = Eigen::Vector3d::Constant(kNaN);
constexpr double kVaneTf = 30.0;  // [s] the weathervaned bow's averaging time (UsvMission::onPose)

// holdPath at p's depth: guidance holds the end of a path, its depth too.
std::vector<Eigen::Vector3d> holdPath3(const Eigen::Vector3d& p, double heading) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& w : holdPath(p.head<2>(), heading)) out.emplace_back(w.x(), w.y(), p.z());
  return out;
}

template <class Phase, std::size_t N>
std::optional<Phase> phaseFromString(const std::string& s, const Phase (&all)[N]) {
  for (Phase p : all)
    if (s == toString(p)) return p;
  return std::nullopt;
}
}  // namespace

const char* toString(AuvPhase p) {
  switch (p) {
    case AuvPhase::Idle: return "IDLE";
    case AuvPhase::Coverage: return "COVERAGE";
    case AuvPhase::TargetFound: return "TARGET_FOUND";
    case AuvPhase::NoTarget: return "NO_TARGET";
    case AuvPhase::Ascent: return "ASCENT";
    case AuvPhase::Surfaced: return "SURFACED";
    case AuvPhase::Recovered: return "RECOVERED";
  }
  return "?";
}

const char* toString(UsvPhase p) {
  switch (p) {
    case UsvPhase::StationKeeping: return "STATION_KEEPING";
    case UsvPhase::Transit: return "TRANSIT";
    case UsvPhase::Arrived: return "ARRIVED";
    case UsvPhase::Recovery: return "RECOVERY";
    case UsvPhase::Recovered: return "RECOVERED";
    case UsvPhase::Manual: return "MANUAL";
    case UsvPhase::PeerLost: return "PEER_LOST";
  }
  return "?";
}

std::optional<AuvPhase> auvPhaseFromString(const std::string& s) {
  static const AuvPhase all[] = {AuvPhase::Idle,    AuvPhase::Coverage, AuvPhase::TargetFound, AuvPhase::NoTarget,
                                 AuvPhase::Ascent, AuvPhase::Surfaced, AuvPhase::Recovered};
  return phaseFromString(s, all);
}

std::optional<UsvPhase> usvPhaseFromString(const std::string& s) {
  static const UsvPhase all[] = {UsvPhase::StationKeeping, UsvPhase::Transit, UsvPhase::Arrived, UsvPhase::Recovery,
                                 UsvPhase::Recovered,      UsvPhase::Manual,  UsvPhase::PeerLost};
  return phaseFromString(s, all);
}

// ------------------------------------------------------------------------------------------------- AUV
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
              "on GPS fixes (the latest within it)");
  return t;
}

void AuvMissionParams::validate() const {
  table().validate(*this, "mission/");
  coverage.validate();
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
  steady_ = std::all_of(surface_track_.begin(), surface_track_.end(),
                        [&](const auto& s) { return (s.second - mean).norm() <= p_.station_radius; });
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
  return (phase_ == AuvPhase::Surfaced || phase_ == AuvPhase::Recovered) && pose_ &&
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

// ------------------------------------------------------------------------------------------------- USV
const ParamTable<UsvMissionParams>& UsvMissionParams::table() {
  using P = UsvMissionParams;
  static const ParamTable<P> t = ParamTable<P>()
      .number("waypoint_spacing", &P::waypoint_spacing, 0.5, 1000.0, "m",
              "straight path to the target with a waypoint every this many metres (paper 3.2.3)")
      .number("standoff", &P::standoff, 0.0, 500.0, "m", "stop this far short of the target")
      .number("min_distance", &P::min_distance, 0.0, 100.0, "m", "closer than this after the stand-off: no transit")
      .number("peer_timeout", &P::peer_timeout, 1.0, 1e5, "s",
              "AUV side silent this long before a target came: PEER_LOST, keep holding")
      .number("manual_timeout", &P::manual_timeout, 0.05, 60.0, "s",
              "manual control is released this long after its last command")
      .number("station_radius", &P::station_radius, 0.1, 100.0, "m",
              "arrived, the USV is on station once this close to its station point (the hold counts from there)")
      .number("recovery_distance", &P::recovery_distance, 0.5, 100.0, "m",
              "recovering, the bow holds this far from the surfaced AUV, downstream of it")
      .number("recovery_replan", &P::recovery_replan, 0.1, 100.0, "m",
              "the recovery is planned again when the AUV's reported position moved this far")
      .number("auv_extent", &P::auv_extent, 0.1, 50.0, "m",
              "the surfaced AUV's size as guidance's safety box about its reported position takes it on the way to "
              "the run-in (the Girona500's length; the aColor's 1.0 m fits in it)")
      .number("recovery_clearance", &P::recovery_clearance, 0.0, 100.0, "m",
              "recovering, the hull closing in and holding keeps this clear of an obstacle's extent (the side chosen)")
      .number("settle_time", &P::settle_time, 0.0, 3600.0, "s", "both vehicles stationary this long: RECOVERED")
      .number("station_time", &P::station_time, 0.0, 3600.0, "s",
              "arrived, on station at the target at least this long before leaving to recover the surfaced AUV")
      .number("station_timeout", &P::station_timeout, 0.0, 1e5, "s",
              "arrived but never on station this long: it goes to recover the AUV all the same (counted)");
  return t;
}

void UsvMissionParams::validate() const { table().validate(*this, "mission/"); }

std::vector<Eigen::Vector2d> holdPath(const Eigen::Vector2d& p, double heading, double lead_in) {
  if (!p.allFinite() || !std::isfinite(heading) || !(lead_in > 0.0)) return {};
  return {p - lead_in * Eigen::Vector2d(std::cos(heading), std::sin(heading)), p};
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

UsvMission::UsvMission(const UsvMissionParams& p)
    : p_(p), distance_to_go_(kNaN), on_station_since_(kNaN), settled_since_(kNaN), recovered_t_(kNaN),
      auv_still_since_(kNaN) {
  p_.validate();
}

void UsvMission::onPose(const Eigen::Vector2d& ned, double heading, double t) {
  if (!ned.allFinite() || !std::isfinite(heading)) {
    counters_.increment("pose_not_finite");
    return;
  }
  pose_ = ned;
  heading_ = heading;
  // Dynamic positioning weathervanes the bow into the current (docs/guidance-control.md), swinging about it for a
  // minute after an arrival (+-40 degrees seen): the mean over kVaneTf is the recovery's "into the current".
  const Eigen::Vector2d bow(std::cos(heading), std::sin(heading));
  if (phase_ != UsvPhase::StationKeeping && phase_ != UsvPhase::Arrived && phase_ != UsvPhase::PeerLost)
    vane_ = kNoPoint;
  else if (!vane_.allFinite())
    vane_ = bow;
  else
    vane_ += std::clamp((t - pose_t_) / kVaneTf, 0.0, 1.0) * (bow - vane_);
  pose_t_ = t;
  const auto& held = hold_point_ ? hold_point_ : station_;
  if ((phase_ == UsvPhase::Arrived || phase_ == UsvPhase::Recovery) && held && std::isnan(on_station_since_) &&
      (ned - *held).norm() <= p_.station_radius)
    on_station_since_ = t;
  if (!station_) {  // station keeping (dynamic positioning) where the mission starts, until a target arrives
    station_ = ned;
    path_due_ = holdPath(ned, heading);
  }
  tick(t);
}

void UsvMission::onGuidance(guidance::Mode mode, double distance_to_go, double t, const Eigen::Vector2d& hold_point) {
  distance_to_go_ = distance_to_go;
  // Guidance's hold point stands for the station (moved off an obstacle's box by a few metres at most): one farther
  // is the last path's, held for a step before a new one takes (a hold path ends in station keeping at once), and it
  // put the USV "on station" at its old point.
  if (mode == guidance::Mode::kStationKeeping && hold_point.allFinite() &&
      (!station_ || (hold_point - *station_).norm() < 0.5 * p_.waypoint_spacing))
    hold_point_ = hold_point;
  if (phase_ != UsvPhase::Transit) return;
  if (mode == guidance::Mode::kFollowPath) following_ = true;
  // Station keeping ends the transit once guidance has followed it, or when the boat already holds within
  // station_radius of the station: a refined target that moved the station a little while the USV waited there
  // gave a path guidance never followed (its end inside the final circle of acceptance), and the mission stayed
  // in TRANSIT to the end (evaluation run 54, 2026-12-05).
  const bool there = pose_ && station_ && (*pose_ - *station_).norm() <= p_.station_radius;
  if ((following_ || there) && mode == guidance::Mode::kStationKeeping) onPathFinished(t);
}

void UsvMission::onManualCommand(double t) {
  last_manual_ = t;
  onManual(true, t);
}

std::optional<std::vector<Eigen::Vector2d>> UsvMission::takePath() {
  auto p = std::move(path_due_);
  path_due_.reset();
  return p;
}

std::vector<guidance::SbbObstacle> UsvMission::keepClear() const {
  if (phase_ != UsvPhase::Recovery || alongside_ || !auv_planned_.allFinite()) return {};
  guidance::SbbObstacle o;
  o.id = kAuvObstacleId;
  o.origin = auv_planned_;
  o.length = o.width = p_.auv_extent;
  o.boxed = round_auv_;  // otherwise only a detour round something else keeps off it
  return {o};
}

double UsvMission::distanceToGo() const {
  return phase() == UsvPhase::Transit || phase() == UsvPhase::Recovery ? distance_to_go_ : kNaN;
}

bool UsvMission::onTarget(const Eigen::Vector2d& target, double t) {
  onPeerAlive(t);
  if (!target.allFinite()) {
    counters_.increment("target_not_finite");
    return false;
  }
  if (!pose_) {
    counters_.increment("target_before_pose");
    return false;
  }
  if (target_ && (*target_ - target).norm() < 0.5) return false;  // repeated (relay resend, latched)
  if (region_) {
    std::string why = region_->checkTarget(target.x(), target.y());
    if (why.empty() && region_->checkPath(std::vector<Eigen::Vector2d>{*pose_, target})) {
      std::ostringstream os;
      os << "the transit to the target at N " << target.x() << " E " << target.y()
         << " would leave the operating region";
      why = os.str();
    }
    if (!why.empty()) {
      if (!refused_ || (*refused_ - target).norm() >= 0.5) counters_.increment("target_outside_region");
      refused_ = target;
      refusal_ = why;
      return false;
    }
  }
  target_ = target;
  const Eigen::Vector2d d = target - *pose_;
  const double dist = d.norm();
  // stop `standoff` short of the target on the line from the vehicle
  const Eigen::Vector2d goal = dist > p_.standoff ? Eigen::Vector2d(target - d / dist * p_.standoff) : *pose_;
  if ((goal - *pose_).norm() < p_.min_distance) {
    counters_.increment("target_within_standoff");
    station_ = *pose_;
    path_.clear();
    phase_ = UsvPhase::Arrived;
    arrived_ = true;
    arrived_t_ = t;
    ++path_version_;
    path_due_ = holdPath(*station_, heading_);
    return false;
  }
  path_.clear();
  for (const auto& w : guidance::straightLine({pose_->x(), pose_->y(), 0.0}, {goal.x(), goal.y(), 0.0},
                                              p_.waypoint_spacing))
    path_.push_back(w.head<2>());
  station_ = goal;
  on_station_since_ = kNaN;
  hold_point_.reset();
  phase_ = UsvPhase::Transit;
  following_ = false;
  ++path_version_;
  path_due_ = path_;
  return true;
}

void UsvMission::onPathFinished(double t) {
  if (phase_ != UsvPhase::Transit) return;
  phase_ = UsvPhase::Arrived;
  arrived_ = true;
  arrived_t_ = t;
}

void UsvMission::onAuvStatus(AuvPhase phase, const Eigen::Vector3d& auv_ned, bool stationary, double t) {
  onPeerAlive(t);
  auv_phase_ = phase;
  // stationary since when, in reports that kept coming (a gap of half the settle time says nothing of it)
  if (!stationary) auv_still_since_ = kNaN;
  else if (!auv_stationary_ || std::isnan(auv_still_since_) || t - auv_t_ > 0.5 * p_.settle_time) auv_still_since_ = t;
  auv_stationary_ = stationary;
  auv_t_ = t;
  if (auv_ned.head<2>().allFinite()) auv_pos_ = auv_ned.head<2>();
  else counters_.increment("auv_position_not_finite");
  recover(t);
}

void UsvMission::setPath(std::vector<Eigen::Vector2d> path) {
  path_ = path;
  ++path_version_;
  path_due_ = std::move(path);
  hold_point_.reset();
  following_ = false;
  on_station_since_ = kNaN;
}

void UsvMission::recover(double t) {
  if (!pose_) return;
  const bool surfaced = auv_phase_ && (*auv_phase_ == AuvPhase::Surfaced || *auv_phase_ == AuvPhase::Recovered) &&
                        auv_pos_.allFinite();
  if (phase_ == UsvPhase::Arrived && surfaced) {  // the hold at the target first
    const bool held = !std::isnan(on_station_since_) && t - on_station_since_ >= p_.station_time;
    if (!held && t - arrived_t_ < p_.station_timeout) return;
    if (!held) counters_.increment("left_station_unsettled");
  }
  if ((phase_ == UsvPhase::Arrived || phase_ == UsvPhase::StationKeeping) && surfaced) {
    phase_ = UsvPhase::Recovery;
    // the side away from the current: the dynamic positioning has turned the bow into it, so downstream is astern;
    // without a current any side is as good
    downstream_ = vane_.norm() > 1e-3 ? Eigen::Vector2d(vane_.normalized())
                                      : Eigen::Vector2d(std::cos(heading_), std::sin(heading_));
    recovery_axis_ = kNoPoint;
    planRecovery(t);
    return;
  }
  if (phase_ != UsvPhase::Recovery) return;
  // a surfaced AUV moves: planned again once it moved recovery_replan, or at once when it stops holding its point
  // while the USV is close to it (back to the run-in)
  if (surfaced && ((auv_pos_ - auv_planned_).norm() > p_.recovery_replan || (alongside_ && !auv_stationary_)))
    planRecovery(t);
  if (!alongside_ && auvHeld(t) && (*pose_ - run_in_).norm() <= p_.recovery_distance) {  // at the run-in: close in
    alongside_ = true;
    planRecovery(t);
  }
  if (!alongside_) return;
  const Eigen::Vector2d& held = hold_point_ ? *hold_point_ : recovery_point_;
  const bool here = (*pose_ - held).norm() <= p_.station_radius;
  const bool auv_still = auv_stationary_ && t - auv_t_ <= p_.settle_time;  // a stale report says nothing
  if (!here || !auv_still) {
    settled_since_ = kNaN;
    return;
  }
  if (std::isnan(settled_since_)) settled_since_ = t;
  if (t - settled_since_ >= p_.settle_time) {
    phase_ = UsvPhase::Recovered;
    recovered_t_ = t;
  }
}

bool UsvMission::auvHeld(double t) const {
  return auv_stationary_ && t - auv_still_since_ >= p_.settle_time && t - auv_t_ <= p_.settle_time;
}

void UsvMission::setObstacles(const std::vector<guidance::SbbObstacle>& obstacles) {
  obstacles_.clear();
  for (const auto& o : obstacles)
    if (o.id != kAuvObstacleId && o.origin.allFinite() && std::isfinite(o.length) && std::isfinite(o.width))
      obstacles_.push_back(o);
}

bool UsvMission::sweepClear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double reach) const {
  for (const auto& o : obstacles_)
    if (segmentDistance(a, b, o.origin) < 0.5 * std::max(o.length, o.width) + reach + p_.recovery_clearance) return false;
  return true;
}

Eigen::Vector2d UsvMission::recoveryAxis(const Eigen::Vector2d& auv) {
  // the hull from its stern at the run-in to its bow holding recovery_distance off the AUV
  const double run = hull_.astern + hull_.ahead + p_.waypoint_spacing;
  auto clear = [&](const Eigen::Vector2d& up) {
    const Eigen::Vector2d bow = auv - p_.recovery_distance * up;
    return sweepClear(bow - run * up, bow, hull_.abeam);
  };
  if (recovery_axis_.allFinite() && clear(recovery_axis_)) return recovery_axis_;
  // from the current's, by 30 degrees either way: of each pair first the side whose hold is nearer the USV
  const double off = p_.recovery_distance + hull_.ahead;
  for (double deg : {0.0, 30.0, 60.0, 90.0}) {
    Eigen::Vector2d sides[2];
    for (int k = 0; k < 2; ++k) sides[k] = Eigen::Rotation2Dd(deg2rad(k ? -deg : deg)) * downstream_;
    if (pose_ && ((auv - off * sides[1]) - *pose_).norm() < ((auv - off * sides[0]) - *pose_).norm())
      std::swap(sides[0], sides[1]);
    for (const auto& up : sides)
      if (clear(up)) return up;
  }
  counters_.increment("recovery_side_blocked");
  return downstream_;
}

void UsvMission::planRecovery(double t) {
  const Eigen::Vector2d last_axis = recovery_axis_;
  recovery_axis_ = recoveryAxis(auv_pos_);
  // Another side (an obstacle seen since blocks the last): from its run-in again, not straight across (evaluation
  // seed 7000 run 962: at the first side's run-in, the second side's point 16 m off across a buoy, held for at once).
  if (last_axis.allFinite() && last_axis.dot(recovery_axis_) < std::cos(deg2rad(10.0))) alongside_ = false;
  const Eigen::Vector2d auv = auv_pos_, up = recovery_axis_, u = *pose_;
  const double off = p_.recovery_distance + hull_.ahead;  // the reference point's distance: the bow at recovery_distance
  const double heading = std::atan2(up.y(), up.x());     // bow on to the AUV
  recovery_point_ = auv - off * up;                       // downstream of it
  run_in_ = recovery_point_ - p_.waypoint_spacing * up;
  auv_planned_ = auv;
  settled_since_ = kNaN;
  // Already downstream and close (a replan, or it arrived there): close in along the axis at once. Otherwise the
  // run-in first: guidance cuts every waypoint but the last (the USV's 16 m circle of acceptance), and dynamic
  // positioning's straight line to a point 10 m away passed the AUV with the bow 1.9 m off it.
  // Closing in only to an AUV that holds its point (auvHeld): one that moves is kept at the run-in's distance, the
  // run-in moved with it (a Girona500 that could not hold against 0.5 m/s drifted onto the USV holding downstream of
  // it and touched the hull; an aColor swinging +-3 m about its point came within 0.3 m of it).
  // The straight close-in from where it is swings the whole hull round on dynamic positioning: only when that
  // sweep (the hull's longest reach either side of the line) is clear of what guidance plans round. A guard, not a
  // fix seen to act: seed 7000's recovery collisions replayed the same with it and without it.
  const Eigen::Vector2d from_point = u - recovery_point_;
  const double sweep = std::max({hull_.ahead, hull_.astern, hull_.abeam});
  alongside_ = auvHeld(t) && (alongside_ || (from_point.dot(up) <= 0.0 && from_point.norm() <= p_.waypoint_spacing &&
                                             sweepClear(u, recovery_point_, sweep)));
  if (alongside_) {
    station_ = recovery_point_;
    setPath(holdPath(recovery_point_, heading));
    return;
  }
  // The way to the run-in: straight, and when it passes the AUV closer than the recovery point, round it by
  // guidance's safety box about it (keepClear()): its corners are reached within the detour radius, and its side is
  // kept while guidance replans the same path (each new path here chooses afresh, as any new path does in guidance).
  // (The mission's own legs beside the AUV, 9.3 m off, were ordinary waypoints:
  // guidance's 16 m circle of acceptance cut them, and in the evaluation campaign the hull touched the AUV in 6 of
  // 100 runs, 2026-12-05.) Only then: a box behind the USV merged with a shore's boxes and blocked the way.
  round_auv_ = segmentDistance(u, run_in_, auv) < off;
  std::vector<Eigen::Vector2d> path;
  for (const auto& w : guidance::straightLine({u.x(), u.y(), 0.0}, {run_in_.x(), run_in_.y(), 0.0}, p_.waypoint_spacing))
    path.push_back(w.head<2>());
  station_ = run_in_;
  if (path.size() < 2) path = holdPath(run_in_, heading);
  setPath(std::move(path));
}

void UsvMission::onManual(bool active, double /*t*/) {
  if (active && !manual_) counters_.increment("manual_takeovers");
  manual_ = active;
}

void UsvMission::onPeerAlive(double t) {
  last_peer_ = t;
  peer_seen_ = true;
  if (phase_ == UsvPhase::PeerLost) phase_ = UsvPhase::StationKeeping;
}

void UsvMission::tick(double t) {
  if (!peer_seen_) {  // the clock starts at the first tick
    peer_seen_ = true;
    last_peer_ = t;
  }
  if (manual_ && t - last_manual_ > p_.manual_timeout && last_manual_ > -1e300) onManual(false, t);
  // Before a target came, a silent AUV side means the mission cannot go on: hold position and say so.
  if (phase_ == UsvPhase::StationKeeping && !target_ && t - last_peer_ > p_.peer_timeout) phase_ = UsvPhase::PeerLost;
  recover(t);
}

std::string UsvMission::detail() const {
  std::ostringstream os;
  if (manual_) os << "manual control active (autonomy suspended); ";
  switch (phase_) {
    case UsvPhase::StationKeeping: os << "station keeping, waiting for the AUV's target"; break;
    case UsvPhase::Transit:
      os << "transit to stand-off point N " << (*station_)(0) << " E " << (*station_)(1) << " (" << path_.size()
         << " waypoints)";
      break;
    case UsvPhase::Arrived:
      os << "arrived; station keeping " << p_.standoff << " m from the target, waiting for the AUV at the surface";
      break;
    case UsvPhase::Recovery:
      os << "recovering the AUV at N " << auv_planned_.x() << " E " << auv_planned_.y() << ": "
         << (alongside_ ? "closing in to" : "run-in to") << " N " << station_->x() << " E " << station_->y()
         << ", then the bow " << p_.recovery_distance << " m off it" << (std::isnan(settled_since_) ? "" : "; both stationary");
      break;
    case UsvPhase::Recovered:
      os << "recovered: holding " << p_.recovery_distance << " m off the AUV's bow-on at N " << recovery_point_.x()
         << " E " << recovery_point_.y();
      break;
    case UsvPhase::Manual: break;  // phase_ never holds Manual: manual_ overlays it
    case UsvPhase::PeerLost:
      os << "no sign of the AUV side for more than " << p_.peer_timeout << " s; holding position";
      break;
  }
  if (!refusal_.empty()) os << "; refused a target: " << refusal_;
  return os.str();
}

}  // namespace mission
}  // namespace offshore_gnc
