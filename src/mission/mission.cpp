#include "offshore_gnc/mission/mission.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/guidance/paths.h"

namespace offshore_gnc {
namespace mission {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

// ------------------------------------------------------------------------------------------------- AUV
void AuvMissionParams::validate() const {
  requireRange("mission/confirm_detections", confirm_detections, 1, 100);
  requireRange("mission/confirm_radius", confirm_radius, 0.1, 50.0);
  requireRange("mission/detection_max_age", detection_max_age, 1.0, 1e5);
}

const char* toString(AuvPhase p) {
  switch (p) {
    case AuvPhase::Idle: return "IDLE";
    case AuvPhase::Coverage: return "COVERAGE";
    case AuvPhase::TargetFound: return "TARGET_FOUND";
    case AuvPhase::NoTarget: return "NO_TARGET";
  }
  return "?";
}

AuvMission::AuvMission(const AuvMissionParams& p) : p_(p), detection_time_(kNaN) { p_.validate(); }

void AuvMission::start(double t) {
  if (phase_ != AuvPhase::Idle) return;
  phase_ = AuvPhase::Coverage;
  start_time_ = t;
}

bool AuvMission::onDetection(const Eigen::Vector3d& p, double t) {
  if (!p.allFinite() || !std::isfinite(t)) {
    counters_.increment("detection_not_finite");
    return false;
  }
  if (phase_ != AuvPhase::Coverage) {
    counters_.increment("detection_outside_coverage");
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
  target_ = best->mean();
  detection_time_ = t - start_time_;
  phase_ = AuvPhase::TargetFound;
  return true;
}

void AuvMission::onCoverageFinished(double /*t*/) {
  if (phase_ == AuvPhase::Coverage) phase_ = AuvPhase::NoTarget;
}

std::string AuvMission::detail() const {
  std::ostringstream os;
  switch (phase_) {
    case AuvPhase::Idle: os << "waiting to start"; break;
    case AuvPhase::Coverage: os << "searching, " << clusters_.size() << " unconfirmed candidate(s)"; break;
    case AuvPhase::TargetFound:
      os << "target confirmed at N " << (*target_)(0) << " E " << (*target_)(1) << " D " << (*target_)(2)
         << " after " << detection_time_ << " s; thrusters stopped";
      break;
    case AuvPhase::NoTarget: os << "coverage finished without a confirmed detection; thrusters stopped"; break;
  }
  return os.str();
}

// ------------------------------------------------------------------------------------------------- USV
void UsvMissionParams::validate() const {
  requireRange("mission/waypoint_spacing", waypoint_spacing, 0.5, 1000.0);
  requireRange("mission/standoff", standoff, 0.0, 500.0);
  requireRange("mission/min_distance", min_distance, 0.0, 100.0);
  requireRange("mission/peer_timeout", peer_timeout, 1.0, 1e5);
}

const char* toString(UsvPhase p) {
  switch (p) {
    case UsvPhase::StationKeeping: return "STATION_KEEPING";
    case UsvPhase::Transit: return "TRANSIT";
    case UsvPhase::Arrived: return "ARRIVED";
    case UsvPhase::Manual: return "MANUAL";
    case UsvPhase::PeerLost: return "PEER_LOST";
  }
  return "?";
}

std::vector<Eigen::Vector2d> holdPath(const Eigen::Vector2d& p, double heading, double lead_in) {
  if (!p.allFinite() || !std::isfinite(heading) || !(lead_in > 0.0)) return {};
  return {p - lead_in * Eigen::Vector2d(std::cos(heading), std::sin(heading)), p};
}

std::vector<Eigen::Vector3d> coveragePath(const CoverageArea& a) {
  if (!(a.north_max > a.north_min)) return {};
  return guidance::lawnmower({a.north_min, a.east_min}, 0.0, a.north_max - a.north_min, a.east_max - a.east_min,
                             a.spacing, a.depth);
}

UsvMission::UsvMission(const UsvMissionParams& p) : p_(p) { p_.validate(); }

void UsvMission::onPose(const Eigen::Vector2d& ned, double t) {
  if (!ned.allFinite()) {
    counters_.increment("pose_not_finite");
    return;
  }
  pose_ = ned;
  if (!station_) station_ = ned;  // station keeping starts where the vehicle is
  tick(t);
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
    ++path_version_;
    return false;
  }
  path_.clear();
  for (const auto& w : guidance::straightLine({pose_->x(), pose_->y(), 0.0}, {goal.x(), goal.y(), 0.0},
                                              p_.waypoint_spacing))
    path_.push_back(w.head<2>());
  station_ = goal;
  phase_ = UsvPhase::Transit;
  ++path_version_;
  return true;
}

void UsvMission::onPathFinished(double /*t*/) {
  if (phase_ == UsvPhase::Transit) phase_ = UsvPhase::Arrived;
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
  // Before a target came, a silent AUV side means the mission cannot go on: hold position and say so.
  if (phase_ == UsvPhase::StationKeeping && !target_ && t - last_peer_ > p_.peer_timeout) phase_ = UsvPhase::PeerLost;
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
    case UsvPhase::Arrived: os << "arrived; station keeping " << p_.standoff << " m from the target"; break;
    case UsvPhase::Manual: break;  // phase_ never holds Manual: manual_ overlays it
    case UsvPhase::PeerLost:
      os << "no sign of the AUV side for more than " << p_.peer_timeout << " s; holding position";
      break;
  }
  return os.str();
}

}  // namespace mission
}  // namespace offshore_gnc
