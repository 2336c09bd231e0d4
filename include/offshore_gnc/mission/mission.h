#pragma once
// Co-operative mission logic (paper section 3.2.3, thesis chapter 5), ROS-free. The nodelets feed events
// (detections, poses, guidance progress, manual control, the other vehicle's mission status) and publish what
// these machines ask for (paths, the target, status). After the find (issue 36) the AUV keeps the spot at depth,
// comes up at a bounded rate and holds at the surface; the USV, once it has arrived, goes to the surfaced AUV and
// holds beside it until both are stationary (RECOVERED). All positions in map_ned (x north, y east, z down) [m],
// times in seconds.
#include <Eigen/Core>

#include <algorithm>
#include <deque>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/models/state.h"
#include "offshore_gnc/guidance/los.h"
#include "offshore_gnc/guidance/sbb.h"
#include "offshore_gnc/safety/region.h"

namespace offshore_gnc {
namespace mission {

// The AUV's search area as a north/east rectangle; coveragePath() lays guidance::lawnmower over it (legs along
// north, `spacing` apart to the east, from the south-west corner) at `depth`, then, when `second_depth` > 0, flies it
// back at that depth: one tilted sonar fan cannot see a whole deep target band (docs/mission.md, AUV). The
// search ends at the first confirmed find, so the second pass is flown only when the first found nothing. Empty for
// a degenerate rectangle.
struct CoverageArea {
  double north_min = 0, north_max = 0, east_min = 0, east_max = 0, depth = 0, spacing = 5.0;
  double second_depth = 0.0;  // 0: one pass
  static const ParamTable<CoverageArea>& table();
  void validate() const;  // also refuses an empty rectangle, naming it
};
std::vector<Eigen::Vector3d> coveragePath(const CoverageArea& a);

inline const Eigen::Vector2d kNoPoint = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
// The surfaced AUV's id among guidance's obstacles (UsvMission::keepClear; no LiDAR target's tracker id).
constexpr std::uint32_t kAuvObstacleId = 0xFFFFFFFEu;

enum class AuvPhase { Idle, Coverage, TargetFound, NoTarget, Ascent, Surfaced, Recovered };
enum class UsvPhase { StationKeeping, Transit, Arrived, Recovery, Recovered, Manual, PeerLost };
const char* toString(AuvPhase p);
const char* toString(UsvPhase p);
// The phase a status message names (the other vehicle's, across the relay); nullopt for an unknown name.
std::optional<AuvPhase> auvPhaseFromString(const std::string& s);
std::optional<UsvPhase> usvPhaseFromString(const std::string& s);

// ------------------------------------------------------------------------------------------------- AUV
struct AuvMissionParams {
  int confirm_detections = 2;        // detections of the same object needed before it counts (sonar sweeps)
  double confirm_radius = 2.0;       // detections closer than this are the same object [m]
  double detection_max_age = 120.0;  // unconfirmed detections older than this are forgotten [s]
  double search_margin = 5.0;        // detections farther than this outside the coverage area are not its target [m]
  double start_delay = 2.0;          // the search starts this long after the first tick [s]
  // After the search (issue 36): keep the spot at depth, come up under control, wait at the surface.
  double hold_standoff = 5.0;        // hold this far from the target on the line from the find, facing it [m]
  double refine_distance = 0.5;      // the refined target is resent once it moved this far from the one sent [m]
  double hold_timeout = 600.0;       // holding this long without the USV's arrival: ascend anyway [s]
  double usv_timeout = 30.0;         // holding without the USV's status this long (link lost, stack dead): ascend [s]
  double ascent_rate = 0.1;          // the depth reference rises at most this fast [m/s]
  double surface_depth = kAuvSurfaceDepth;  // shallower than this the AUV is at the surface [m]
  double surface_clearance = 10.0;   // surface at least this far from where the USV holds or is bound [m]
  // Ascending, the depth is held while the USV itself (its reported position, not its station) is closer than
  // this: a USV carried off its station by a strong set came over the rising Girona500 (evaluation seed 5000 run 13,
  // 0.32 m/s and 7 m/s of wind: the hull touched it at 323 s). [m]
  double overhead_clearance = 6.0;
  double station_radius = 1.0;       // on station (and, at the surface, stationary) this close to its point [m]
  // At the surface also stationary when its position stayed within station_radius of their mean this long, and moved
  // less than that from the window's first to its last, on GPS
  // fixes (the latest within it), wherever it holds: a Girona500 pushed 1-6 m off its point by wind and current and
  // steady there left the USV waiting at the run-in to the time limit (evaluation seed 7000, 2026-12-05: 31 of its
  // 40 auv_adrift). Not on the USBL alone: an aColor's USBL estimate can be steady but off (2026-12-04). [s]
  double still_window = 20.0;
  CoverageArea coverage;             // from the mission config or, in simulation, the scenario
  static const ParamTable<AuvMissionParams>& table();  // without `coverage` (read under its own prefix)
  void validate() const;
};

// Coverage -> first confirmed detection -> TARGET_FOUND: hold at depth hold_standoff from the target facing it
// (dynamic positioning on the navigation it searched on), the sonar refining the target, resent when it moved
// refine_distance -> ASCENT when the USV reports it has arrived (or hold_timeout, usv_timeout, or the safety
// supervisor surfaces it): first clear of the USV at depth if it is within surface_clearance, then up at
// ascent_rate -> SURFACED: holding at the surface, its position in the status for the USV -> RECOVERED once the
// USV says so (it keeps holding). Coverage finished without a detection -> NO_TARGET -> ASCENT at once. What
// guidance and the USV must be told comes out of takePath() / takeTarget() (each once, when it changes).
class AuvMission {
 public:
  explicit AuvMission(const AuvMissionParams& p = {});

  void tick(double t);                                    // starts the coverage start_delay after the first tick
  void start(double t);                                   // Idle -> Coverage (the coverage path is due)
  // Guidance's mode: the end of the coverage path is station keeping after path following.
  void onGuidance(guidance::Mode mode, double t);
  // A sonar target in map_ned. Returns true when this detection confirms the target (phase -> TargetFound);
  // while holding, a detection of the same object refines it.
  bool onDetection(const Eigen::Vector3d& p, double t);
  void onCoverageFinished(double t);                      // guidance reached the last coverage waypoint
  // The navigation estimate (NED, yaw): where the hold is placed and the ascent is measured.
  void onPose(const Eigen::Vector3d& ned, double yaw, double t);
  // The USV mission's status across the relay: its phase, navigation position and the point it holds or is bound
  // for (NaN: none). The AUV surfaces clear of where the USV will be: it says ARRIVED up to 10 m short of its point
  // (guidance's final radius), and an aColor surfaced under the hull that came on.
  void onUsvStatus(UsvPhase phase, const Eigen::Vector2d& usv_ned, const Eigen::Vector2d& usv_station, double t);
  // The safety supervisor surfaces the vehicle (surface or abort): after the search, the mission ascends too, so
  // that it does not dive back to its hold when the override is released.
  void onSafetySurface(double t);
  // A GPS fix at the surface came (the Girona500's /auv/gps/fix): its surface position is the GPS's, not the USBL's.
  void onSurfaceFix(double t) { surface_fix_t_ = t; }
  // The navigation's fix lost (/auv/navigation/status fix_lost): its position is dead reckoning, and an aColor's
  // hold drifts without a fix (drift_without_fix), so on its point or steady says nothing: not stationary.
  void onFixLost(bool lost) { fix_lost_ = lost; }

  // The path guidance must follow now (the coverage, the hold, the ascent), once per change.
  std::optional<std::vector<Eigen::Vector3d>> takePath();
  // The target for the USV: the confirmed one, then each refinement that moved it refine_distance; once each.
  std::optional<Eigen::Vector3d> takeTarget();

  AuvPhase phase() const { return phase_; }
  bool searchOver() const { return phase_ != AuvPhase::Idle && phase_ != AuvPhase::Coverage; }
  bool noTarget() const { return searchOver() && !target_; }  // the search ended without a target
  bool finished() const { return phase_ == AuvPhase::Recovered; }
  // Confirmed target: mean of the detections that confirmed (and since refined) it.
  const std::optional<Eigen::Vector3d>& target() const { return target_; }
  double detectionTime() const { return detection_time_; }  // NaN until found
  // The point held now (the hold at depth, the surfacing point during the ascent and at the surface); NaN none.
  const Eigen::Vector3d& holdPoint() const { return hold_; }
  const std::optional<Eigen::Vector3d>& pose() const { return pose_; }  // the last navigation estimate
  // TargetFound: when the vehicle first came within station_radius of its hold point (NaN before).
  double onStationSince() const { return on_station_since_; }
  // At the surface, within station_radius of the point it holds or, on GPS, steady for still_window (what the USV
  // waits for before closing in and before RECOVERED). Judged on steadiness alone (over 10 s, before the Girona500
  // had GPS at the surface), the ROS job's USV closed in on one whose USBL navigation there was steady but off, and
  // touched it (2026-12-04); a steady AUV off its point on GPS is one that cannot stem the wind and current.
  bool stationary() const;
  double searchEndedAt() const { return searchOver() ? found_t_ : std::numeric_limits<double>::quiet_NaN(); }
  double ascentStart() const { return ascent_t_; }          // NaN before the ascent
  double surfacedAt() const { return surfaced_t_; }         // NaN before
  std::string detail() const;
  const Counters& counters() const { return counters_; }

 private:
  struct Cluster {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int n = 0;
    double last_t = 0.0;
    Eigen::Vector3d mean() const { return sum / n; }
  };
  void hold(const Eigen::Vector3d& point, double t);  // hold path at point, heading hold_heading_
  void ascend(double t, const std::string& why, bool clear_of_usv = true);
  void refine(const Eigen::Vector3d& p, double t);

  AuvMissionParams p_;
  AuvPhase phase_ = AuvPhase::Idle;
  std::vector<Cluster> clusters_;
  Cluster confirmed_;
  std::optional<Eigen::Vector3d> target_, target_due_, target_sent_, pose_;
  std::optional<std::vector<Eigen::Vector3d>> path_due_;
  std::optional<Eigen::Vector2d> usv_;  // where the USV is, or will hold
  std::optional<Eigen::Vector2d> usv_pos_;  // where the USV is (its last status)
  std::optional<UsvPhase> usv_phase_;
  Eigen::Vector3d hold_;
  std::string why_ascent_;
  double start_time_ = 0.0, detection_time_, first_tick_ = 0.0, found_t_ = 0.0, usv_t_ = -1e300, yaw_ = 0.0;
  double hold_heading_ = 0.0, on_station_since_, ascent_t_, surfaced_t_, ramp_t_ = 0.0, depth_ref_ = 0.0;
  double surface_fix_t_ = -1e300;
  bool ticked_ = false, following_ = false, clearing_ = false, mind_usv_ = true, steady_ = false, fix_lost_ = false;
  std::deque<std::pair<double, Eigen::Vector2d>> surface_track_;  // at the surface, the last still_window of poses
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
  double recovery_distance = 4.0;   // recovering, the bow holds this far from the surfaced AUV [m]
  double recovery_replan = 2.0;     // the recovery is planned again when the AUV's position moved this far [m]
  double auv_extent = 1.5;          // the surfaced AUV's size for guidance's safety box about it (keepClear) [m]
  double recovery_clearance = 3.0;  // the hull, holding and closing in, keeps this clear of an obstacle's extent [m]
  // The run-in, where the USV waits for the AUV to settle, lies at least this far beyond an obstacle's extent and the
  // hull's longest reach: out of guidance's safety box about it (6 m across), else neither its detour nor dynamic
  // positioning's straight run gets there (tuning seed 33 runs 11, 350: a run-in 4.7 m off a moored vessel's corner,
  // the supervisor's all-stop every few seconds for 600-2900 s, the wind setting the boat onto a buoy or the vessel;
  // 8 m without the reach fixed run 11, not 350).
  double run_in_clearance = 6.0;    // [m]
  double settle_time = 10.0;        // both vehicles stationary this long: RECOVERED [s]
  // Arrived, the USV holds on station at the target at least station_time (from first coming within station_radius)
  // before it leaves to recover a surfaced AUV; one that could not get on station goes after station_timeout.
  // (It had left as soon as the AUV surfaced: an aColor found and surfaced within 40 s of the USV's arrival, and the
  // USV, still swinging onto its point in 7-8 m/s of wind, left 5-6 m off it: off_station, evaluation seed 5000.)
  double station_time = 30.0;       // [s]
  double station_timeout = 180.0;   // [s]
  static const ParamTable<UsvMissionParams>& table();
  void validate() const;
};

// Station keeping -> /target received -> straight path (SBB avoidance is the guidance's) -> stand-off reached
// -> ARRIVED, station keeping -> the AUV reports itself at the surface -> RECOVERY: to recovery_distance off
// the AUV, bow on, on the side away from the current (downstream of it: a USV that loses its jets drifts away
// from the AUV, not onto it); first to a run-in point waypoint_spacing farther downstream (round the AUV when the
// way passes close to it), then, once the AUV has held its point for settle_time, dynamic positioning closes in
// along the axis toward it (back to the run-in whenever the AUV stops holding) -> both vehicles stationary for
// settle_time -> RECOVERED. Without a target (the AUV surfaced after its search) station keeping
// goes straight to RECOVERY. Manual control always wins; autonomy resumes where it was when manual ends. The
// path for guidance comes out of takePath() once per change (the hold path where the mission starts, the
// transit, the recovery).
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
  // The AUV mission's status across the relay: its phase, navigation position, whether it is stationary.
  void onAuvStatus(AuvPhase phase, const Eigen::Vector3d& auv_ned, bool stationary, double t);
  // How far the hull reaches about the reference point (models::HullFootprint): the recovery distance is the bow's,
  // so the reference point holds that much farther off, and the hull keeps clear of the obstacles.
  void setHullReach(const guidance::HullReach& hull) { hull_ = hull; }
  // What guidance plans round (its LiDAR's targets, with those it keeps out of the sensor's view); the mission's
  // own (kAuvObstacleId) are left out. The recovery's side is chosen so that the hull, closing in from the run-in
  // and holding bow-on to the AUV, keeps recovery_clearance from them: dynamic positioning's straight run to a point
  // plans round nothing (the default scenario's buoy under the close-in: 3 seeds in 30 touched it, 2026-12-05).
  void setObstacles(const std::vector<guidance::SbbObstacle>& obstacles);
  void tick(double t);                     // time-based checks (peer timeout, manual released)
  std::optional<std::vector<Eigen::Vector2d>> takePath();
  // What guidance must plan round besides what its LiDAR sees (GuidancePipeline::setKnownObstacles), current with
  // each path takePath() gives: on the way to the recovery's run-in, the surfaced AUV (kAuvObstacleId, auv_extent
  // about its reported position; the simulated LiDAR has no AUV, a real one sees a low hull poorly), boxed when the
  // way passes it closer than the recovery point, else only a side a detour must not take; nothing once closing in
  // along the axis (the bow's recovery_distance is the approach's own) or in any other phase.
  std::vector<guidance::SbbObstacle> keepClear() const;
  double distanceToGo() const;             // along the transit path; NaN outside the transit
  // Arrived, when the USV first came within station_radius of the point guidance holds (NaN before): the hold at the
  // target counts from here (the main job's hold_time, the report's usv_hold_p95_m).
  double onStationSince() const { return on_station_since_; }

  UsvPhase phase() const { return manual_ ? UsvPhase::Manual : phase_; }
  bool finished() const { return phase_ == UsvPhase::Recovered; }
  bool arrived() const { return arrived_; }  // came to ARRIVED (on station at the target) at some time
  // RECOVERY: where the USV holds, and the AUV's surface position it was planned against (NaN before).
  const Eigen::Vector2d& recoveryPoint() const { return recovery_point_; }
  const Eigen::Vector2d& auvSurface() const { return auv_planned_; }
  double recoveredAt() const { return recovered_t_; }  // NaN before
  // The path to follow (from the pose at the time the target came, to the stand-off point), waypoints every
  // `waypoint_spacing`; empty while station keeping. `path_version` increments on every new path.
  const std::vector<Eigen::Vector2d>& path() const { return path_; }
  int pathVersion() const { return path_version_; }
  const std::optional<Eigen::Vector2d>& target() const { return target_; }
  const std::optional<Eigen::Vector2d>& stationPoint() const { return station_; }  // where DP holds
  const std::optional<Eigen::Vector2d>& pose() const { return pose_; }  // the last navigation estimate
  std::string detail() const;
  const Counters& counters() const { return counters_; }

 private:
  void setPath(std::vector<Eigen::Vector2d> path);  // a new path for guidance (hold point measured afresh)
  void planRecovery(double t);
  // The recovery's axis (from the run-in to the AUV): the last one while still clear of the obstacles, else the
  // clear one nearest to the current's (within 90 degrees: never upstream of the AUV); none clear: the current's.
  Eigen::Vector2d recoveryAxis(const Eigen::Vector2d& auv);
  // Where the reference point holds on the axis `up` (toward the AUV), downstream of it: the bow recovery_distance off.
  Eigen::Vector2d recoveryPointOf(const Eigen::Vector2d& auv, const Eigen::Vector2d& up) const;
  // No obstacle guidance plans round within its extent / 2 + `reach` + `clearance` of the segment a-b (a point: a == b).
  bool sweepClear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double reach, double clearance) const;
  bool auvHeld(double t) const;  // the AUV has reported itself stationary for settle_time, the last report fresh
  void recover(double t);                           // RECOVERY's checks, each tick

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
  bool peer_seen_ = false, arrived_ = false;
  double arrived_t_ = -1e300;  // when the phase became ARRIVED
  // the AUV's last status, and the recovery planned against it
  std::optional<AuvPhase> auv_phase_;
  Eigen::Vector2d auv_pos_ = kNoPoint, auv_planned_ = kNoPoint, recovery_point_ = kNoPoint, recovery_axis_ = kNoPoint;
  Eigen::Vector2d downstream_ = kNoPoint;  // the recovery's preferred axis: into the current (the bow's mean)
  std::vector<guidance::SbbObstacle> obstacles_;
  guidance::HullReach hull_;
  bool auv_stationary_ = false, alongside_ = false;  // alongside: closing in from the run-in point
  Eigen::Vector2d run_in_ = kNoPoint;
  bool round_auv_ = false;  // the way to the run-in passes the AUV: guidance boxes it (keepClear)
  Eigen::Vector2d vane_ = kNoPoint;  // the bow's mean direction while holding: where the current comes from
  double pose_t_ = 0.0;
  double auv_t_ = -1e300, settled_since_, recovered_t_, auv_still_since_;
  Counters counters_;
};

// Station keeping at `p` expressed as a path guidance understands: guidance holds the end of a path, so a short
// lead-in leg along the current heading ends at p (no turn is needed to "follow" it).
std::vector<Eigen::Vector2d> holdPath(const Eigen::Vector2d& p, double heading, double lead_in = 2.0);

}  // namespace mission
}  // namespace offshore_gnc
