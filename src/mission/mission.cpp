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
const ParamTable<CoverageArea>& CoverageArea::table() {
  using P = CoverageArea;
  static const ParamTable<P> t = ParamTable<P>()
      .number("north_min", &P::north_min, -1e5, 1e5, "m", "southern edge of the search area (local NED)")
      .number("north_max", &P::north_max, -1e5, 1e5, "m", "northern edge")
      .number("east_min", &P::east_min, -1e5, 1e5, "m", "western edge")
      .number("east_max", &P::east_max, -1e5, 1e5, "m", "eastern edge")
      .number("depth", &P::depth, 0.0, 1000.0, "m", "depth of the coverage")
      .number("spacing", &P::spacing, 0.5, 1000.0, "m", "distance between the lawnmower's tracks");
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
      .number("start_delay", &P::start_delay, 0.0, 3600.0, "s", "the search starts this long after start-up");
  return t;
}

void AuvMissionParams::validate() const {
  table().validate(*this, "mission/");
  coverage.validate();
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

void AuvMission::tick(double t) {
  if (!ticked_) {
    ticked_ = true;
    first_tick_ = t;
  }
  if (phase_ == AuvPhase::Idle && t - first_tick_ >= p_.start_delay) start(t);
}

void AuvMission::start(double t) {
  if (phase_ != AuvPhase::Idle) return;
  phase_ = AuvPhase::Coverage;
  start_time_ = t;
  path_due_ = coveragePath(p_.coverage);
}

void AuvMission::stop() { path_due_ = std::vector<Eigen::Vector3d>(); }  // guidance idle: thrusters off

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
  target_ = target_due_ = best->mean();
  detection_time_ = t - start_time_;
  phase_ = AuvPhase::TargetFound;
  stop();
  return true;
}

void AuvMission::onCoverageFinished(double /*t*/) {
  if (phase_ != AuvPhase::Coverage) return;
  phase_ = AuvPhase::NoTarget;
  stop();
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
              "arrived, the USV is on station once this close to its station point (the hold counts from there)");
  return t;
}

void UsvMissionParams::validate() const { table().validate(*this, "mission/"); }

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

UsvMission::UsvMission(const UsvMissionParams& p) : p_(p), distance_to_go_(kNaN), on_station_since_(kNaN) {
  p_.validate();
}

void UsvMission::onPose(const Eigen::Vector2d& ned, double heading, double t) {
  if (!ned.allFinite() || !std::isfinite(heading)) {
    counters_.increment("pose_not_finite");
    return;
  }
  pose_ = ned;
  heading_ = heading;
  const auto& held = hold_point_ ? hold_point_ : station_;
  if (phase_ == UsvPhase::Arrived && held && std::isnan(on_station_since_) && (ned - *held).norm() <= p_.station_radius)
    on_station_since_ = t;
  if (!station_) {  // station keeping (dynamic positioning) where the mission starts, until a target arrives
    station_ = ned;
    path_due_ = holdPath(ned, heading);
  }
  tick(t);
}

void UsvMission::onGuidance(guidance::Mode mode, double distance_to_go, double t, const Eigen::Vector2d& hold_point) {
  distance_to_go_ = distance_to_go;
  if (mode == guidance::Mode::kStationKeeping && hold_point.allFinite()) hold_point_ = hold_point;
  if (phase_ != UsvPhase::Transit) return;
  if (mode == guidance::Mode::kFollowPath) following_ = true;
  if (following_ && mode == guidance::Mode::kStationKeeping) onPathFinished(t);
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

double UsvMission::distanceToGo() const { return phase() == UsvPhase::Transit ? distance_to_go_ : kNaN; }

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
  if (manual_ && t - last_manual_ > p_.manual_timeout && last_manual_ > -1e300) onManual(false, t);
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
  if (!refusal_.empty()) os << "; refused a target: " << refusal_;
  return os.str();
}

}  // namespace mission
}  // namespace offshore_gnc
