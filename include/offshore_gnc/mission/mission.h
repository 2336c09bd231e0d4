#pragma once
// Co-operative mission logic (paper section 3.2.3, thesis chapter 5), ROS-free. The nodelets feed events
// (detections, poses, guidance progress, manual control, peer liveness) and publish what these machines ask
// for (paths, the target, status). All positions in map_ned (x north, y east, z down) [m], times in seconds.
#include <Eigen/Core>

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/guidance/los.h"
#include "offshore_gnc/safety/region.h"

namespace offshore_gnc {
namespace mission {

// The AUV's search area as a north/east rectangle; coveragePath() lays guidance::lawnmower over it (legs along
// north, `spacing` apart to the east, from the south-west corner). Empty for a degenerate rectangle.
struct CoverageArea {
  double north_min = 0, north_max = 0, east_min = 0, east_max = 0, depth = 0, spacing = 5.0;
  static const ParamTable<CoverageArea>& table();
  void validate() const;  // also refuses an empty rectangle, naming it
};
std::vector<Eigen::Vector3d> coveragePath(const CoverageArea& a);

// ------------------------------------------------------------------------------------------------- AUV
struct AuvMissionParams {
  int confirm_detections = 2;        // detections of the same object needed before it counts (sonar sweeps)
  double confirm_radius = 2.0;       // detections closer than this are the same object [m]
  double detection_max_age = 120.0;  // unconfirmed detections older than this are forgotten [s]
  double start_delay = 2.0;          // the search starts this long after the first tick [s]
  CoverageArea coverage;             // from the mission config or, in simulation, the scenario
  static const ParamTable<AuvMissionParams>& table();  // without `coverage` (read under its own prefix)
  void validate() const;
};

enum class AuvPhase { Idle, Coverage, TargetFound, NoTarget };
const char* toString(AuvPhase p);

// Coverage -> first confirmed detection -> stop (thrusters off: the aColor AUV had no DP, paper 3.2.3) ->
// report the target; coverage finished without a detection -> stop and say so. What guidance and the USV
// must be told comes out of takePath() / takeTarget() (each once, when it changes).
class AuvMission {
 public:
  explicit AuvMission(const AuvMissionParams& p = {});

  void tick(double t);                                    // starts the coverage start_delay after the first tick
  void start(double t);                                   // Idle -> Coverage (the coverage path is due)
  // Guidance's mode: the end of the coverage path is station keeping after path following.
  void onGuidance(guidance::Mode mode, double t);
  // A sonar target in map_ned. Returns true when this detection confirms the target (phase -> TargetFound).
  bool onDetection(const Eigen::Vector3d& p, double t);
  void onCoverageFinished(double t);                      // guidance reached the last coverage waypoint

  // The path guidance must follow now (the coverage; empty = stop), once per change.
  std::optional<std::vector<Eigen::Vector3d>> takePath();
  // The confirmed target for the USV, once.
  std::optional<Eigen::Vector3d> takeTarget();

  AuvPhase phase() const { return phase_; }
  bool finished() const { return phase_ == AuvPhase::TargetFound || phase_ == AuvPhase::NoTarget; }
  bool thrustersOff() const { return finished(); }       // the vehicle stops once the search is over
  // Confirmed target: mean of the detections that confirmed it.
  const std::optional<Eigen::Vector3d>& target() const { return target_; }
  double detectionTime() const { return detection_time_; }  // NaN until found
  std::string detail() const;
  const Counters& counters() const { return counters_; }

 private:
  struct Cluster {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int n = 0;
    double last_t = 0.0;
    Eigen::Vector3d mean() const { return sum / n; }
  };
  void stop();

  AuvMissionParams p_;
  AuvPhase phase_ = AuvPhase::Idle;
  std::vector<Cluster> clusters_;
  std::optional<Eigen::Vector3d> target_, target_due_;
  std::optional<std::vector<Eigen::Vector3d>> path_due_;
  double start_time_ = 0.0, detection_time_, first_tick_ = 0.0;
  bool ticked_ = false, following_ = false;
  Counters counters_;
};

// ------------------------------------------------------------------------------------------------- USV
struct UsvMissionParams {
  double waypoint_spacing = 10.0;   // straight path to the target with a waypoint every 10 m (paper 3.2.3) [m]
  double standoff = 3.0;            // stop this far short of the target, then station keeping [m]
  double min_distance = 1.0;        // a target closer than this (after the stand-off) needs no transit [m]
  double peer_timeout = 60.0;       // AUV side silent this long before a target arrived -> report, keep DP [s]
  double manual_timeout = 1.0;      // manual control is released this long after its last command [s]
  double station_radius = 1.0;      // arrived, the USV is on station once this close to its hold point [m]
  static const ParamTable<UsvMissionParams>& table();
  void validate() const;
};

inline const Eigen::Vector2d kNoPoint = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());

enum class UsvPhase { StationKeeping, Transit, Arrived, Manual, PeerLost };
const char* toString(UsvPhase p);

// Station keeping -> /target received -> straight path (SBB avoidance is the guidance's) -> stand-off reached
// -> station keeping. Manual control always wins; autonomy resumes where it was when manual ends. The path for
// guidance comes out of takePath() once per change (the hold path where the mission starts, the transit).
class UsvMission {
 public:
  explicit UsvMission(const UsvMissionParams& p = {});

  // Navigation pose (NED) and heading; the first one fixes where station keeping starts.
  void onPose(const Eigen::Vector2d& ned, double heading, double t);
  // A target from the AUV; returns true when it starts (or restarts) a transit. A target whose position is not
  // finite is rejected and counted. A repeat of the same target (within 0.5 m) does not replan.
  bool onTarget(const Eigen::Vector2d& target, double t);
  // The operating region (the safety supervisor's `region`, docs/safety.md): a target outside it, or whose
  // transit from the vehicle would leave it, is refused with a sentence (refusal()) and counted
  // ("target_outside_region"); the mission goes on as it was. Without one, no check.
  void setRegion(std::optional<safety::Region> region) { region_ = std::move(region); }
  const std::string& refusal() const { return refusal_; }  // why the last refused target was refused
  void onPathFinished(double t);           // guidance reports the end of the path reached
  // Guidance's mode and distance to go: the end of the transit is station keeping after path following. The point
  // guidance holds (NaN: none) is what being on station is measured against: guidance moves it off an obstacle's
  // safety box when the stand-off point lies inside one.
  void onGuidance(guidance::Mode mode, double distance_to_go, double t,
                  const Eigen::Vector2d& hold_point = kNoPoint);
  void onManual(bool active, double t);
  void onManualCommand(double t);          // a manual command seen: manual until manual_timeout after the last
  void onPeerAlive(double t);              // any sign of life from the AUV side (link status, relayed topic)
  void tick(double t);                     // time-based checks (peer timeout, manual released)
  std::optional<std::vector<Eigen::Vector2d>> takePath();
  double distanceToGo() const;             // along the transit path; NaN outside the transit
  // Arrived, when the USV first came within station_radius of the point guidance holds (NaN before): the hold at the
  // target counts from here (the main job's hold_time, the report's usv_hold_p95_m).
  double onStationSince() const { return on_station_since_; }

  UsvPhase phase() const { return manual_ ? UsvPhase::Manual : phase_; }
  bool finished() const { return phase_ == UsvPhase::Arrived; }
  // The path to follow (from the pose at the time the target came, to the stand-off point), waypoints every
  // `waypoint_spacing`; empty while station keeping. `path_version` increments on every new path.
  const std::vector<Eigen::Vector2d>& path() const { return path_; }
  int pathVersion() const { return path_version_; }
  const std::optional<Eigen::Vector2d>& target() const { return target_; }
  const std::optional<Eigen::Vector2d>& stationPoint() const { return station_; }  // where DP holds
  std::string detail() const;
  const Counters& counters() const { return counters_; }

 private:
  UsvMissionParams p_;
  UsvPhase phase_ = UsvPhase::StationKeeping;
  bool manual_ = false, following_ = false;
  std::optional<Eigen::Vector2d> pose_, target_, station_, refused_, hold_point_;
  std::optional<safety::Region> region_;
  std::string refusal_;
  std::optional<std::vector<Eigen::Vector2d>> path_due_;
  std::vector<Eigen::Vector2d> path_;
  int path_version_ = 0;
  double last_peer_ = 0.0, heading_ = 0.0, last_manual_ = -1e300, distance_to_go_, on_station_since_;
  bool peer_seen_ = false;
  Counters counters_;
};

// Station keeping at `p` expressed as a path guidance understands: guidance holds the end of a path, so a short
// lead-in leg along the current heading ends at p (no turn is needed to "follow" it).
std::vector<Eigen::Vector2d> holdPath(const Eigen::Vector2d& p, double heading, double lead_in = 2.0);

}  // namespace mission
}  // namespace offshore_gnc
