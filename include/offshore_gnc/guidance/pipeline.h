#pragma once
// The guidance of one vehicle as it runs on board: the mission's path, the LiDAR obstacles and the navigation
// state in; the SBB planner (USV), the replanning policy and LOS guidance; the reference for control, the path
// actually followed and the safety boxes out. The Guidance nodelet and the ROS-free loops both run exactly
// this: they feed it plain structs and the time and publish what it returns. ROS-free; NED, seconds.
#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/common/reconfigure_form.h"
#include "offshore_gnc/guidance/colregs.h"
#include "offshore_gnc/guidance/los.h"
#include "offshore_gnc/guidance/obstacle_memory.h"
#include "offshore_gnc/guidance/sbb.h"
#include "offshore_gnc/models/reference.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace guidance {

struct GuidanceParams {
  std::string vehicle = "usv";   // usv | girona500 | acolor: selects the preset the other values start from
  LosParams los;
  SbbParams sbb;
  bool sbb_enabled = true;       // plan around obstacles (the USV's LiDAR targets)
  ObstacleMemoryParams obstacles; // what is kept of the LiDAR's targets (sbb/obstacle_timeout, sbb/obstacle_memory...)
  ColregsParams colregs;         // moving tracks: give way and stand on (rules 13-17)
  double replan_distance = 0.5;  // re-set the LOS path only when a planned waypoint moved more than this [m]
  double odom_timeout = 1.0;     // older navigation -> hold the last good position [s]
  double rate = 10.0;            // guidance steps per second [Hz]
  std::string frame_id = "map_ned";  // the Guidance nodelet's: the frame of its path and status (NED)

  // The vehicle's defaults (thesis Tables 4.1-4.3 and what the simulations showed; docs/parameters.md).
  static GuidanceParams preset(const std::string& vehicle);
  static const ParamTable<GuidanceParams>& table();
  // What the Guidance nodelet's dynamic_reconfigure form shows (cfg/Guidance.cfg is generated from this and
  // table(); the defaults it shows are this struct's).
  static const std::vector<ReconfigureGroup>& reconfigurable();
  void validate() const;
};

struct GuidanceOutput {
  LosOutput los;
  MotionReference reference;     // what control follows (referenceOf(los))
  bool planned_changed = false;  // plannedPath() differs from the last output's: publish it
  bool boxes_changed = false;    // a replan happened: publish the boxes (also when empty)
  ColregsOutput colregs;         // the encounter with traffic, and the course it steers (los and reference carry it)
};

class GuidancePipeline {
 public:
  explicit GuidancePipeline(const GuidanceParams& p);
  void setParams(const GuidanceParams& p);  // validates; replans at the next update
  const GuidanceParams& params() const { return p_; }

  // The mission's path (NED). Empty: no path (idle). A new path chooses its detour sides afresh.
  void setPath(const std::vector<Eigen::Vector3d>& path);
  // A path that cannot be used (e.g. in a frame guidance does not work in): hold, and say why.
  void rejectPath(const std::string& why);
  // One obstacle frame's targets at time t (NED), placed with the last navigation state: kept with the ones seen
  // before that the sensor cannot see from there (ObstacleMemory). Non-finite geometry is dropped and counted.
  void setObstacles(const std::vector<SbbObstacle>& obstacles, double t);
  // The LiDAR's tracks at time t (NED): the confirmed moving ones are met by the rules (ColregsAvoidance) and their
  // targets are not boxed as standing obstacles; tentative and still ones are left to the SBB. Give them before
  // the same frame's setObstacles (a later frame's obstacles are matched to them predicted to that time).
  void setTracks(const std::vector<Contact>& tracks, double t) { colregs_.setTracks(tracks, t); }
  // Obstacles the mission knows of that the LiDAR may not see (the surfaced AUV the USV recovers: the simulated
  // LiDAR has no AUV, and a real one sees a low hull poorly), planned round and kept clear of like the seen ones
  // but kept until the next call (no obstacle_timeout). Empty: none. Non-finite geometry is dropped and counted.
  void setKnownObstacles(const std::vector<SbbObstacle>& obstacles);
  // The hull's reach about the reference point: a hold point keeps the hull, not the point, clear (none: the point).
  void setHullReach(const HullReach& hull) { hull_ = hull; }
  // Navigation state at time t.
  void setState(const VehicleState& s, double t);

  // One guidance step at time t, dt after the previous one. False before the first state (nothing to say).
  bool update(double t, double dt, GuidanceOutput& out);

  const std::vector<Eigen::Vector3d>& plannedPath() const { return planned_; }
  const SbbPlan& plan() const { return plan_; }
  // What is planned round at time t: the seen obstacles (fresh, or kept out of view), and the known ones.
  std::vector<SbbObstacle> obstacles(double t) const;
  // What the last plan went round (obstacles(t) at the last replan: what guidance/obstacles publishes).
  const std::vector<SbbObstacle>& plannedRound() const { return planned_round_; }
  // Of the seen obstacles at the last LiDAR frame, those kept from memory (out of the sensor's view).
  int remembered() const { return seen_.remembered(); }
  const Counters& counters() const { return counters_; }            // stale_odom, bad_obstacles, ...
  const Counters& losCounters() const { return los_.counters(); }   // nan_pose, bad_path, ...
  const Counters& colregsCounters() const { return colregs_.counters(); }  // bad_tracks, give_way, ...

 private:
  void replan(const VehicleState& s, double t);
  // The encounters with the moving tracks (ColregsAvoidance): an alteration replaces the LOS heading.
  void avoidTraffic(const VehicleState& s, double t, GuidanceOutput& out);
  // A hold point too close to an obstacle (sbb/hold_clearance) is refused: the nearest clear point is held instead,
  // and the status says so (counter hold_point_in_box).
  void keepHoldClear(double t, GuidanceOutput& out);
  // Dynamic positioning runs straight to its point and plans round nothing: the path's last point is taken on
  // final_radius only when that run keeps the hull's reach (at least the corridor) clear of every boxed obstacle.
  bool finalRunBlocked(const Eigen::Vector2d& from, double t) const;
  // The hull swinging round on station at `at` keeps sbb/hold_clearance from every obstacle (MotionReference's
  // room_to_turn).
  bool roomToTurn(const Eigen::Vector2d& at, double t) const;

  GuidanceParams p_;
  LosGuidance los_;
  std::vector<Eigen::Vector3d> base_path_, planned_;
  std::vector<bool> planned_detour_;
  ObstacleMemory seen_;
  ColregsAvoidance colregs_;
  bool steering_ = false;  // the last step steered for traffic (the LOS integral is held)
  std::vector<SbbObstacle> known_;
  SbbPlan plan_;  // the last plan: its boxes' sides are kept while safe
  std::vector<SbbObstacle> planned_round_;
  VehicleState state_;
  double state_time_ = 0.0;
  bool have_state_ = false, new_path_ = false, replan_ = false, planned_changed_ = false, boxes_changed_ = false;
  std::string reject_reason_;
  Eigen::Vector2d refused_hold_ = Eigen::Vector2d::Constant(1e300);  // the last hold point refused
  HullReach hull_;
  bool final_run_blocked_ = false;
  std::optional<Eigen::Vector2d> moved_hold_;                        // ... and where it was moved
  Counters counters_;
};

}  // namespace guidance
}  // namespace offshore_gnc
