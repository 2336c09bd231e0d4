#pragma once
// The co-operative mission (paper 3.2.3, thesis chapter 5) ROS-free in one process: both vehicles' stacks
// (closed_loop/stacks.h) on one simulated clock, the AUV's confirmed target and both missions' statuses handed
// across as the relay would, until the USV reports the AUV recovered (docs/mission.md: it holds beside the surfaced
// AUV, both stationary), the time limit, or `after_kill` seconds after a stack was killed. The same scenario,
// configuration and seeds as ./scripts/mission, with the figures its report gives (metrics over the same samples:
// guidance's cross-track error in path following; the AUV's from the first waypoint reached and on the truth, as the
// report's auv_xte_true_rmse_m). The AUV navigates as in the ROS mission: on USBL fixes placed by the USV's GPS and
// heading relayed over the radio (closed_loop/usbl_navigation.h); the radio (sim/radio.h, the main job's model and
// parameters) delays what crosses it and loses best-effort messages.
#include <Eigen/Core>

#include <array>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "offshore_gnc/closed_loop/outcome.h"
#include "offshore_gnc/closed_loop/stacks.h"
#include "offshore_gnc/guidance/metrics.h"
#include "offshore_gnc/sim/radio.h"
#include "offshore_gnc/sim/scenario.h"

namespace offshore_gnc {
namespace closed_loop {

struct MissionConfig {
  std::string scenario_file;
  sim::Scenario scenario;
  UsvStackConfig usv;
  AuvStackConfig auv;
  sim::RadioParams radio;                 // the radio between the masters (config/relay/radio.yaml, as the main job's)
  std::uint64_t radio_seed = 1;
  // The main job's own faults, between the vehicles (offshore_gnc::faultKinds() "both"): `link` takes the radio
  // down, `geofence` hands the USV a target 5 km north of the origin as if the AUV had sent it.
  FaultPlan link_faults;
  // A stack killed at a simulated time (./scripts/mission --kill V@T): it stops, nothing crosses the radio from or
  // to it any more, and the run goes on for after_kill seconds with the other vehicle.
  std::string kill;  // "", "usv" or "auv"
  double kill_at = 0.0, after_kill = 60.0;
};
// The scenario (its mission section says how a run is judged), the vehicles' configuration files under config_dir
// and the radio between them (config_dir/relay/radio.yaml).
MissionConfig loadMission(const std::string& config_dir, const std::string& scenario_file,
                          const std::string& auv_model = "girona500");

struct VehicleRecord {
  std::vector<Eigen::Vector4d> truth;                 // (t, north, east, down) at 20 Hz, as the bags record it
  std::vector<Eigen::Vector2d> xte;                   // (t, e) of guidance's samples in path following while tracking
                                                      // (the USV's transit, the AUV's search)
  std::vector<Eigen::Vector2d> xte_truth;             // the same samples on the truth (distance from the active leg)
  // The same samples split as the report splits an AUV's (thesis Table 4.4 leaves the approach out): from the
  // first waypoint reached (active leg 2 on) on guidance's estimate and on the truth (the true position's
  // distance from the active leg), and the approach before it on the truth.
  std::vector<Eigen::Vector2d> xte_tracking, xte_tracking_truth, xte_approach_truth;
  std::vector<Eigen::Vector3d> planned;               // the longest path guidance planned
  std::vector<guidance::SbbBox> boxes;                // the last safety boxes
  guidance::TrackingMetrics metrics, metrics_truth;   // over xte, xte_truth
  guidance::TrackingMetrics tracking, tracking_truth, approach_truth;  // over the split samples
  std::string final_phase;
  std::vector<std::pair<double, std::string>> phases;  // (t, phase) at each change of the mission's phase
};

// The USBL fixes as the report scores them (python/offshore_gnc/report.py usbl_verdicts, the same names in
// metrics.json): each against the AUV's truth at its stamp; rejected by a quality gate of the positioning or by the
// navigation filter's gate; an outlier is a fix farther than kUsblOutlierM from the truth.
constexpr double kUsblOutlierM = 3.0;  // three times the 1 m sigma the navigation gives a fix (fix_min_sigma)
struct UsblFixScores {
  std::size_t received = 0, rejected = 0;
  std::map<std::string, std::size_t> rejected_by;  // fit_error, depth, stale, filter_error, no_position, gated
  std::size_t outliers = 0, rejected_outliers = 0, outliers_accepted = 0;
  // The rejections meant to catch outliers (filter_error, fit_error, depth, gated: a fix's own quality, as against
  // stale, no USV pose in time), how many of them were outliers and how many had no position to score.
  std::size_t by_gates = 0, by_gates_outliers = 0, by_gates_unplaced = 0;
  std::size_t multipath_replies = 0;  // replies the simulated pair sent by a reflected path
};

struct MissionResult {
  bool success = false;    // outcome == kSuccess
  Outcome outcome = Outcome::kTimeout;
  std::string reason;      // the sentence
  VehicleRecord usv, auv;
  std::optional<Eigen::Vector3d> target;  // what the AUV reported
  double target_error_m = 0.0;            // horizontal, against the nearest true target (NaN without one)
  double detection_time_s = 0.0;          // from the start of the coverage (NaN without a detection)
  double min_clearance_m = 0.0;           // the USV hull's closest approach to an obstacle (sim/contact.h; <= 0:
                                          // contact; NaN without obstacles)
  // the same against the vessels under way alone (issue 33: the traffic's closest point of approach, hull to hull;
  // NaN without traffic, and then left out of mission_rosfree's JSON)
  double traffic_min_clearance_m = std::numeric_limits<double>::quiet_NaN();
  // the USV's true distance from the nearest true target where it held there (its last moment in ARRIVED, before it
  // left for the recovery), else where it ended (NaN without a target)
  double usv_final_distance_to_target_m = 0.0;
  // Station keeping (docs/mission.md): the largest distance from where the USV started waiting until the target
  // came, and the 95th percentile distance from its hold point over the hold at the target (NaN without one); the
  // same over its holds in the recovery (the run-in, beside the AUV).
  double usv_wait_drift_m = 0.0, usv_hold_p95_m = 0.0, usv_recovery_hold_p95_m = 0.0;
  // The USV's true cross-track on the recovery's legs (usv.metrics* count its transit only).
  guidance::TrackingMetrics usv_recovery_xte_truth;
  // The AUV's navigation during its mission (until it reports finished): its estimate against its truth,
  // horizontal, at the estimate's rate (the report's auv_nav_rmse_m); the USBL fixes (none with navigation ins).
  double auv_nav_rmse_m = 0.0, auv_nav_max_m = 0.0;
  UsblFixScores usbl;
  std::size_t relay_lost = 0;
  double sim_time_s = 0.0, wall_time_s = 0.0;
  std::vector<safety::Transition> usv_safety, auv_safety;  // each supervisor's activations and releases
  std::vector<std::string> target_refusals;  // the USV mission's reasons for refusing a target it was handed
  // After the find (docs/mission.md, "Recovery"; the main job's report computes the same):
  bool recovered = false;                  // the USV reported RECOVERED
  std::string stack_died;                  // the killed stack ("" none)
  double auv_hold_excursion_m = 0.0;       // the AUV's true position from its hold point (3-D), on station until the ascent
  double auv_ascent_drift_m = 0.0;         // horizontal, from the surfacing point, once it rose 0.3 m until at the surface
  double auv_surface_excursion_m = 0.0;    // horizontal, from the point it holds at the surface, while there (NaN never)
  double recovery_distance_m = 0.0;        // the USV hull to the AUV (a disc of its length) at the end
  double usv_auv_min_clearance_m = 0.0;    // the least of that while the AUV was within kAuvContactDepth of the surface
  double find_to_recovery_s = 0.0;         // from the find (or the search's end) to RECOVERED
  // the absolute simulated times [s] (NaN: not reached): the search's end, the ascent, at the surface, RECOVERED
  double found_at_s = 0.0, ascent_at_s = 0.0, surfaced_at_s = 0.0, recovered_at_s = 0.0;
  Eigen::Vector3d auv_hold_point = Eigen::Vector3d::Zero();     // where it held at depth (NaN none)
  Eigen::Vector2d auv_surface_point = Eigen::Vector2d::Zero();  // where it held at the surface (NaN none)
  Eigen::Vector2d recovery_point = Eigen::Vector2d::Zero();     // where the USV held beside it (NaN none)
  // The USV at 20 Hz, what a tuner looks at (mission_rosfree --out writes it as usv_trace.csv, kUsvTraceHeader):
  // truth, guidance's reference and cross-track, the joystick command, dynamic positioning's last step.
  std::vector<std::array<double, 19>> usv_trace;
  // The AUV at 20 Hz (auv_trace.csv, kAuvTraceHeader): truth, its navigation estimate, the reference control
  // follows, the Girona500's requested wrench (NaN on the aColor).
  std::vector<std::array<double, 17>> auv_trace;
  // Each path the USV's guidance planned (usv_plans.csv): when, its status (a detour, blocked, ...), its waypoints
  // and what it was planned round (each obstacle's position and extent), to see why the boat went where it went.
  struct Plan {
    double t = 0.0;
    std::string status;
    std::vector<Eigen::Vector2d> path;
    std::vector<guidance::SbbObstacle> round;
  };
  std::vector<Plan> usv_plans;
  // Each USBL fix and its verdict (usbl_fixes.csv), beside the AUV's true position at its time.
  std::vector<UsblFixRecord> usbl_fixes;
};
inline constexpr const char* kUsvTraceHeader =
    "t,north,east,yaw,u,v,r,ref_mode,ref_north,ref_east,ref_heading,xte,surge,sway,yaw_cmd,"
    "dp_heading,dp_steady_north,dp_steady_east,dp_distance";

inline constexpr const char* kAuvTraceHeader =
    "t,north,east,down,yaw,est_north,est_east,est_down,ref_mode,ref_north,ref_east,ref_depth,ref_heading,"
    "tau_x,tau_y,tau_z,tau_n";

MissionResult runMission(const MissionConfig& cfg);

}  // namespace closed_loop
}  // namespace offshore_gnc
