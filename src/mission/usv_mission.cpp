// The USV's mission (UsvMission) but its recovery (usv_recovery.cpp): transit, arrival, manual control, the peer.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "mission_internal.h"
#include "offshore_gnc/guidance/paths.h"

namespace offshore_gnc {
namespace mission {

namespace {
constexpr double kVaneTf = 30.0;  // [s] the weathervaned bow's averaging time (UsvMission::onPose)
}  // namespace

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
      .number("run_in_clearance", &P::run_in_clearance, 0.0, 100.0, "m",
              "recovering, the run-in point lies this far beyond an obstacle's extent and the hull's longest reach "
              "(out of guidance's safety box about it)")
      .number("settle_time", &P::settle_time, 0.0, 3600.0, "s", "both vehicles stationary this long: RECOVERED")
      .number("station_time", &P::station_time, 0.0, 3600.0, "s",
              "arrived, on station at the target at least this long before leaving to recover the surfaced AUV")
      .number("station_timeout", &P::station_timeout, 0.0, 1e5, "s",
              "arrived but never on station this long: it goes to recover the AUV all the same (counted)");
  return t;
}

void UsvMissionParams::validate() const { table().validate(*this, "mission/"); }

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
