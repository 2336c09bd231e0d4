#include "offshore_gnc/guidance/pipeline.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "offshore_gnc/common/geometry.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace guidance {

GuidanceParams GuidanceParams::preset(const std::string& vehicle) {
  GuidanceParams p;
  p.vehicle = vehicle;
  if (vehicle == "usv") {
    // Table 4.1 LOS row; R = 2 L_USV (L_USV = 8 m, Table 3.3). The waterjet boat brakes at only ~0.05 m/s^2:
    // slow down over the last 60 m; safety-box corners and the stand-off point are reached, not cut.
    p.los.kp = 0.1;
    p.los.ki = 0.001;
    p.los.crab_gain = 0.0027;  // 0.004 at the 1.5 m/s cruise before the update scaled with the speed
    p.los.measured_crab = true;  // the GPS-compass gives course and heading: the crab angle is measured
    p.los.crab_tf = 5.0;
    p.los.acceptance_radius = 16.0;
    p.los.detour_radius = 3.0;
    // The last 10 m are dynamic positioning's: it brakes with the buckets astern and closes in at most at its
    // max_speed, where the end of the path left the boat at 0.8 m/s and it overshot the point by 3-5 m.
    p.los.final_radius = 10.0;
    p.los.approach_distance = 60.0;
    p.los.approach_speed = 0.2;
    p.los.surge_speed = 1.5;
    p.sbb.safety_x = 10.0;
    p.sbb.safety_y = 6.0;
    p.sbb.corridor = 3.0;  // half beam 1.5 m + the tracking error at the corners
    p.sbb.approach = 25.0;
    p.sbb_enabled = true;
  } else if (vehicle == "girona500") {
    // Table 4.3 LOS row. The Girona500 turns on the spot: a 0.5 m sphere.
    p.los.kp = 0.0333;
    p.los.ki = 0.0;
    p.los.sphere = true;
    p.los.acceptance_radius = 0.5;
    p.los.surge_speed = 0.3;
    // The crab estimate learns on the legs only: on the 8 m approach to the first it wound up to 34 deg and the
    // position-following vehicle kept its bow (and its sonar's 90 deg sector) 27 deg off every leg.
    p.los.crab_band = 2.0;
    p.sbb_enabled = false;
  } else if (vehicle == "acolor") {
    // Table 4.2 LOS row; R = 3 L_AUV (Publication IV: its positions come from the USBL only), with L_AUV =
    // 0.46 m for the BlueROV2 Heavy-class frame the model assumes (config/models/acolor.yaml). The thesis gives
    // no speed (a constant PWM): 0.5 m/s, at which the sonar sees the target on 2-3 sweeps per pass (at 0.7 m/s
    // on 1-2, and the confirmation needs two). Unlike the holonomic Girona500 it steers against the current
    // with its heading: the crab estimate, kept in NED so the lawnmower's return legs start with their own.
    p.los.kp = 0.333;
    p.los.ki = 0.0;
    p.los.sphere = true;
    p.los.acceptance_radius = 1.4;
    p.los.surge_speed = 0.5;
    p.los.crab_ned = true;
    p.los.crab_gain = 0.1;  // per m/s: 0.05 at its 0.5 m/s
    p.sbb_enabled = false;
  } else {
    throw ConfigError("parameter 'vehicle' = '" + vehicle + "' is not one of: usv, girona500, acolor");
  }
  return p;
}

const ParamTable<GuidanceParams>& GuidanceParams::table() {
  using P = GuidanceParams;
  static const ParamTable<P> t = ParamTable<P>()
      .choice("vehicle", &P::vehicle, {"usv", "girona500", "acolor"}, "vehicle whose preset the other values start from")
      .nest("los/", &P::los, LosParams::table())
      .nest("sbb/", &P::sbb, SbbParams::table())
      .flag("sbb/enabled", &P::sbb_enabled, "plan safety boxes around obstacles")
      .nest("sbb/", &P::obstacles, ObstacleMemoryParams::table())
      .nest("colregs/", &P::colregs, ColregsParams::table())
      .number("sbb/replan_distance", &P::replan_distance, 0.0, 100.0, "m",
              "re-set the LOS path only when a planned waypoint moved more than this")
      .number("odom_timeout", &P::odom_timeout, 0.01, 60.0, "s", "older navigation: hold the last good position")
      .number("rate", &P::rate, 0.1, 100.0, "Hz", "guidance steps per second")
      .string("frame_id", &P::frame_id, "frame of the path and status the nodelet publishes (NED)");
  return t;
}

const std::vector<ReconfigureGroup>& GuidanceParams::reconfigurable() {
  static const std::vector<ReconfigureGroup> g = {
      {"los", {"los/kp", "los/ki", "los/integral_limit", "los/adaptive_crab", "los/crab_gain", "los/crab_limit",
               "los/acceptance_radius", "los/surge_speed", "los/final_radius", "los/detour_radius",
               "los/approach_distance", "los/approach_speed"}},
      {"sbb", {"sbb/safety_x", "sbb/safety_y", "sbb/corridor", "sbb/max_offset"}}};
  return g;
}

void GuidanceParams::validate() const {
  table().validate(*this);
  colregs.validate();
}

GuidancePipeline::GuidancePipeline(const GuidanceParams& p)
    : p_(p), los_(p.los), seen_(p.obstacles), colregs_(p.colregs) {
  p_.validate();
}

void GuidancePipeline::setParams(const GuidanceParams& p) {
  p.validate();
  los_.setParams(p.los);
  seen_.setParams(p.obstacles);
  colregs_.setParams(p.colregs);
  p_ = p;
  replan_ = true;
}

void GuidancePipeline::setPath(const std::vector<Eigen::Vector3d>& path) {
  base_path_ = path;
  reject_reason_.clear();
  new_path_ = true;
  plan_.boxes.clear();  // a new route chooses its detour sides afresh
  replan_ = true;
}

void GuidancePipeline::rejectPath(const std::string& why) {
  counters_.increment("rejected_paths");
  base_path_.clear();
  planned_.clear();
  reject_reason_ = why;
  los_.setPath({Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN())});  // -> hold fault
}

namespace {
// The finite ones; the others counted as bad_obstacles.
std::vector<SbbObstacle> finiteObstacles(const std::vector<SbbObstacle>& obstacles, Counters& counters) {
  std::vector<SbbObstacle> out;
  for (const auto& o : obstacles) {
    if (!o.origin.allFinite() || !std::isfinite(o.length) || !std::isfinite(o.width)) {
      counters.increment("bad_obstacles");
      continue;
    }
    out.push_back(o);
  }
  return out;
}
}  // namespace

void GuidancePipeline::setObstacles(const std::vector<SbbObstacle>& obstacles, double t) {
  const Eigen::Vector2d at = have_state_ ? Eigen::Vector2d(state_.position.head<2>()) : Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  std::vector<SbbObstacle> standing = finiteObstacles(obstacles, counters_);
  // a vessel under way is met by the rules where it is going, not boxed where it is (nor remembered there)
  standing.erase(std::remove_if(standing.begin(), standing.end(),
                                [&](const SbbObstacle& o) { return colregs_.isMovingTarget(o, t, p_.obstacles.match_gap); }),
                 standing.end());
  seen_.update(standing, at, state_.yaw, t);
  replan_ = true;
}

void GuidancePipeline::setKnownObstacles(const std::vector<SbbObstacle>& obstacles) {
  known_ = finiteObstacles(obstacles, counters_);
  replan_ = true;
}

std::vector<SbbObstacle> GuidancePipeline::obstacles(double t) const {
  std::vector<SbbObstacle> all;
  if (!p_.sbb_enabled) return all;
  all = seen_.active(t);
  all.insert(all.end(), known_.begin(), known_.end());
  return all;
}

void GuidancePipeline::setState(const VehicleState& s, double t) {
  state_ = s;
  state_time_ = t;
  have_state_ = true;
}

void GuidancePipeline::replan(const VehicleState& s, double t) {
  planned_round_ = obstacles(t);
  const std::vector<SbbObstacle>& obstacles = planned_round_;
  SbbPlan plan;
  double length = 0.0;
  for (std::size_t i = 1; i < base_path_.size(); ++i) length += (base_path_[i] - base_path_[i - 1]).head<2>().norm();
  // A path shorter than the corridor is a hold (the mission's lead-in to its station): no detour is planned round
  // it (the shoreline's boxes turned the hold into a detour and back every scan); the hold point keeps clear.
  if (obstacles.empty() || base_path_.size() < 2 || length < p_.sbb.corridor) {
    plan.path = base_path_;
    plan.status = "path clear";
  } else {
    plan = planSbb(base_path_, s.position.head<2>(), obstacles, p_.sbb, plan_.boxes);
    if (plan.blocked) counters_.increment("blocked_plans");
  }
  // Re-set the LOS path only when it really changed (slowly moving obstacles), resuming on the nearest leg.
  bool changed = new_path_ || plan.path.size() != planned_.size() || plan.detour != planned_detour_;
  for (std::size_t i = 0; !changed && i < plan.path.size(); ++i)
    changed = (plan.path[i] - planned_[i]).norm() > p_.replan_distance;
  if (changed) {
    planned_ = plan.path;
    planned_detour_ = plan.detour;
    if (!los_.setPath(planned_, !new_path_, planned_detour_)) counters_.increment("unusable_paths");
    planned_changed_ = true;
  }
  new_path_ = false;
  plan_ = plan;
  boxes_changed_ = true;
}

bool GuidancePipeline::update(double t, double dt, GuidanceOutput& out) {
  if (!have_state_) return false;  // nothing to report before the first pose
  VehicleState s = state_;
  const bool stale = t - state_time_ > p_.odom_timeout;
  if (stale) {
    counters_.increment("stale_odom");
    s.position = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());  // LOS holds the last good
  }
  planned_changed_ = boxes_changed_ = false;
  if (replan_ && s.position.allFinite()) {
    replan(s, t);
    replan_ = false;
  }
  if (s.position.allFinite() && !planned_.empty()) {
    // (seen replayed, tuning seed 33 run 350: the recovery's run-in 10 m off across a moored vessel's end; the
    // straight run set off the supervisor's all-stop every few seconds for 600 s, each hold where the wind had
    // pushed the boat, until the hull met a buoy)
    const bool blocked = finalRunBlocked(s.position.head<2>(), t);
    if (blocked && !final_run_blocked_) counters_.increment("final_run_blocked");
    final_run_blocked_ = blocked;
    los_.setFinalRunBlocked(blocked);
  }
  los_.holdIntegral(steering_);  // the cross-track of an alteration is not the current's: no integral wind-up
  out.los = los_.update(s, std::min(std::max(dt, 0.0), 1.0));
  if (stale) out.los.status_text = "odometry stale: holding the last good position";
  else if (!reject_reason_.empty() && out.los.mode == Mode::kHoldFault) out.los.status_text = reject_reason_;
  out.reference = referenceOf(out.los);
  avoidTraffic(s, t, out);
  if (out.reference.mode == ReferenceMode::kHold) keepHoldClear(t, out);
  if (out.reference.mode == ReferenceMode::kFollow && s.position.allFinite())
    out.reference.room_to_turn = roomToTurn(s.position.head<2>(), t);
  out.planned_changed = planned_changed_;
  out.boxes_changed = boxes_changed_;
  return true;
}

void GuidancePipeline::avoidTraffic(const VehicleState& s, double t, GuidanceOutput& out) {
  const bool follow = out.reference.mode == ReferenceMode::kFollow && s.position.allFinite();
  const Eigen::Vector2d v_ned(std::cos(s.yaw) * s.velocity.x() - std::sin(s.yaw) * s.velocity.y(),
                              std::sin(s.yaw) * s.velocity.x() + std::cos(s.yaw) * s.velocity.y());
  const double course = out.los.desired_heading + out.los.crab_angle;  // the course over ground LOS asks for
  out.colregs = colregs_.update(t, s.position.head<2>(), v_ned, out.los.path_angle, course, out.los.desired_surge,
                                std::max(hull_.longest(), p_.sbb.corridor), follow ? obstacles(t) : std::vector<SbbObstacle>(),
                                follow);
  steering_ = out.colregs.steer;
  const ColregsOutput& c = out.colregs;
  if (c.encounter == Encounter::kNone) return;
  std::ostringstream os;
  os << std::fixed << std::setprecision(0) << "; " << toString(c.encounter) << ", vessel " << c.contact
     << (c.action == EncounterAction::kStarboard ? ": altering to starboard, course " : ": standing on, CPA ");
  if (c.action == EncounterAction::kStarboard) os << rad2deg(wrapTwoPi(c.course)) << " deg";
  else os << c.cpa << " m in " << c.tcpa << " s";
  out.los.status_text += os.str();
  if (!c.steer) return;
  out.los.desired_heading = out.reference.heading = wrapAngle(c.course - out.los.crab_angle);
  out.reference.room_to_turn = false;  // under way among traffic: no turning on the spot
}

bool GuidancePipeline::finalRunBlocked(const Eigen::Vector2d& from, double t) const {
  const Eigen::Vector2d to = planned_.back().head<2>();
  const double reach = std::max(hull_.longest(), p_.sbb.corridor);
  for (const SbbObstacle& o : obstacles(t))
    if (o.boxed && segmentDistance(from, to, o.origin) < 0.5 * std::max(o.length, o.width) + reach) return true;
  return false;
}

bool GuidancePipeline::roomToTurn(const Eigen::Vector2d& at, double t) const {
  // every obstacle, boxed or not: the surfaced AUV beside the recovery's first leg is unboxed
  const double sweep = hull_.longest() + p_.sbb.hold_clearance;
  for (const SbbObstacle& o : obstacles(t))
    if ((o.origin - at).norm() < 0.5 * std::max(o.length, o.width) + sweep) return false;
  return true;
}

void GuidancePipeline::keepHoldClear(double t, GuidanceOutput& out) {
  std::vector<SbbObstacle> obstacles = this->obstacles(t);
  obstacles.erase(std::remove_if(obstacles.begin(), obstacles.end(), [](const SbbObstacle& o) { return !o.boxed; }),
                  obstacles.end());
  if (obstacles.empty()) return;
  const Eigen::Vector2d asked = out.reference.point.head<2>();
  // Another hold point: choose afresh. One a little off the last (a recovery's point follows the AUV's reported
  // position) keeps the last move as a hint, so the side it chose is kept.
  if ((refused_hold_ - asked).norm() > p_.sbb.hold_clearance) moved_hold_.reset();
  const SafeHold h = safeHoldPoint(asked, out.reference.heading, obstacles, p_.sbb, moved_hold_, hull_);
  if (!h.moved) return;
  if (!moved_hold_) counters_.increment("hold_point_in_box");
  refused_hold_ = asked;
  moved_hold_ = h.point;
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << "; hold point N " << asked.x() << " E " << asked.y()
     << " is too close to obstacle";
  for (auto id : h.refused_by) os << " " << id;
  os << ": holding at N " << h.point.x() << " E " << h.point.y() << " instead";
  out.los.status_text += os.str();
  out.reference.point.head<2>() = h.point;
}

}  // namespace guidance
}  // namespace offshore_gnc
