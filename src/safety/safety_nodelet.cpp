// SafetySupervisor nodelet: the vehicle's inputs and heartbeats -> safety::Supervisor (docs/safety.md) at `rate`
// -> /<vehicle>/safety/state (latched: on every change of action, active rule(s) or manual, and at 1 Hz), each
// rule transition logged (WARN on activation, INFO on release) and published on /<vehicle>/safety/transitions
// (not latched: a bag records every one), diagnostics (OK: no action, WARN: warn, ERROR: hold and above).
//   vehicle: usv -> /usv_gps (gps: fixes only), /usv/odom (navigation, position), /usv/lidar/points (lidar),
//                   /relay/link_status (link, while up), /usv/joystick_cmd (command), /usv/manual_cmd (manual),
//                   /usv/waterjet/answering (jet), /usv/can/bus_state (bus_off: off or down), and for the collision
//                   rule the time to collision (safety::timeToCollision: /usv/obstacles on the course /usv/odom
//                   gives) with the safe side from /usv/guidance/safety_boxes (safety::safeSideExists)
//   vehicle: auv -> /auv/odom (navigation, position, depth), /auv/sonar/beam (sonar: valid beams),
//                   /auv/usbl/fix (usbl: QUALITY_OK fixes), /auv/pressure (depth sensor), /relay/link_status (link),
//                   /auv/thruster_setpoints and /auv/rc_channels (command: whichever the vehicle's control publishes)
// Times: the message's header stamp when non-zero, else ros::Time::now(). Thin: parameters, message conversion,
// the core, publishing. The Control nodelet enforces the decision (docs/safety.md).
#include <diagnostic_updater/diagnostic_updater.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/CanBusState.h>
#include <offshore_gnc/JoystickCommand.h>
#include <offshore_gnc/LinkStatus.h>
#include <offshore_gnc/RcChannels.h>
#include <offshore_gnc/SafetyBoxArray.h>
#include <offshore_gnc/SafetyState.h>
#include <offshore_gnc/SonarBeam.h>
#include <offshore_gnc/TargetArray.h>
#include <offshore_gnc/ThrusterSetpoints.h>
#include <offshore_gnc/UsblFix.h>
#include <offshore_gnc/WaterjetAnswering.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/PointCloud2.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/safety/collision.h"
#include "offshore_gnc/safety/supervisor.h"

namespace offshore_gnc {

// The message's constants are the core's enum (the priority order).
static_assert(SafetyState::ACTION_NONE == static_cast<int>(safety::Action::kNone) &&
              SafetyState::ACTION_WARN == static_cast<int>(safety::Action::kWarn) &&
              SafetyState::ACTION_HOLD == static_cast<int>(safety::Action::kHold) &&
              SafetyState::ACTION_NEUTRAL == static_cast<int>(safety::Action::kNeutral) &&
              SafetyState::ACTION_SURFACE == static_cast<int>(safety::Action::kSurface) &&
              SafetyState::ACTION_ABORT == static_cast<int>(safety::Action::kAbort),
              "SafetyState.msg's ACTION_* must match safety::Action");

class SafetySupervisorNodelet : public nodelet::Nodelet {
  using Source = safety::Source;

  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    ros_util::ParamReader p(pnh);
    double rate = 10.0;
    try {
      // No default: which preset guards a vehicle is never guessed.
      if (!pnh.hasParam("vehicle"))
        throw ConfigError("required parameter '" + p.full("vehicle") + "' is missing (usv or auv)");
      safety::SupervisorNodeParams np;
      ros_util::readParams(p, safety::SupervisorNodeParams::table(), np);
      vehicle_ = np.vehicle;
      safety::SupervisorConfig cfg = vehicle_ == "usv" ? safety::usvDefaults() : safety::auvDefaults();
      ros_util::readParams(p, safety::SupervisorConfig::table(), cfg);  // names and ranges: the core's table
      rate = np.rate;
      if (vehicle_ == "usv") manual_timeout_ = np.manual_timeout;
      sup_ = std::make_unique<safety::Supervisor>(cfg);  // validates the table's ranges and the region
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }

    const std::string ns = "/" + vehicle_ + "/safety/";
    state_pub_ = nh.advertise<SafetyState>(ns + "state", 1, true);
    transitions_pub_ = nh.advertise<SafetyState>(ns + "transitions", 100);

    subs_.push_back(nh.subscribe("/relay/link_status", 10, &SafetySupervisorNodelet::onLink, this));
    if (vehicle_ == "usv") {
      subs_.push_back(nh.subscribe("/usv_gps", 10, &SafetySupervisorNodelet::onGps, this));
      subs_.push_back(nh.subscribe("/usv/odom", 10, &SafetySupervisorNodelet::onOdom, this));
      subs_.push_back(nh.subscribe("/usv/lidar/points", 2, &SafetySupervisorNodelet::onLidar, this));
      subs_.push_back(nh.subscribe("/usv/joystick_cmd", 10, &SafetySupervisorNodelet::onJoystick, this));
      subs_.push_back(nh.subscribe("/usv/manual_cmd", 10, &SafetySupervisorNodelet::onManual, this));
      subs_.push_back(nh.subscribe("/usv/waterjet/answering", 10, &SafetySupervisorNodelet::onAnswering, this));
      subs_.push_back(nh.subscribe("/usv/can/bus_state", 10, &SafetySupervisorNodelet::onBus, this));
      subs_.push_back(nh.subscribe("/usv/obstacles", 5, &SafetySupervisorNodelet::onObstacles, this));
      subs_.push_back(nh.subscribe("/usv/guidance/safety_boxes", 5, &SafetySupervisorNodelet::onBoxes, this));
    } else {
      subs_.push_back(nh.subscribe("/auv/odom", 10, &SafetySupervisorNodelet::onOdom, this));
      subs_.push_back(nh.subscribe("/auv/sonar/beam", 50, &SafetySupervisorNodelet::onSonar, this));
      subs_.push_back(nh.subscribe("/auv/usbl/fix", 10, &SafetySupervisorNodelet::onUsbl, this));
      subs_.push_back(nh.subscribe("/auv/pressure", 10, &SafetySupervisorNodelet::onPressure, this));
      subs_.push_back(nh.subscribe("/auv/thruster_setpoints", 10, &SafetySupervisorNodelet::onThrusters, this));
      subs_.push_back(nh.subscribe("/auv/rc_channels", 10, &SafetySupervisorNodelet::onRc, this));
    }

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, getName());
    updater_->setHardwareID(vehicle_ + "_safety");
    updater_->add("safety supervisor", [this](diagnostic_updater::DiagnosticStatusWrapper& s) { diagnose(s); });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->force_update(); });
    timer_ = nh.createTimer(ros::Duration(1.0 / rate), &SafetySupervisorNodelet::onTimer, this);

    std::string rules;
    for (const auto& r : safety::ruleTable(sup_->config()))
      rules += (rules.empty() ? "" : ", ") + r.name + " -> " + safety::actionName(r.action);
    NODELET_INFO("%s safety supervisor at %.1f Hz: %s", vehicle_.c_str(), rate, rules.c_str());
  }

  // ---------------------------------------------------------------- inputs
  // The input's time: its stamp when set, else now; false while there is no clock yet (simulated time before
  // the first /clock), so that the supervisor's start is never taken at time 0.
  static bool stampOf(const std_msgs::Header& h, double& t) {
    const ros::Time s = h.stamp.isZero() ? ros::Time::now() : h.stamp;
    t = s.toSec();
    return !s.isZero();
  }
  void heard(Source s, const std_msgs::Header& h) {
    double t;
    if (!stampOf(h, t)) return;
    std::lock_guard<std::mutex> l(mutex_);
    sup_->heard(s, t);
  }

  // The link is a state, not a stream: the relay publishes its status on change and once a (wall) second, so
  // the link counts as heard at every tick while the relay last said up (its own heartbeats decide that).
  void onLink(const LinkStatus::ConstPtr& m) {
    link_up_ = m->up;
    if (m->up) heard(Source::kLink, m->header);
  }
  void onGps(const sensor_msgs::NavSatFix::ConstPtr& m) {  // a receiver reporting no fix is not delivering fixes
    if (m->status.status >= sensor_msgs::NavSatStatus::STATUS_FIX && std::isfinite(m->latitude) &&
        std::isfinite(m->longitude))
      heard(Source::kGps, m->header);
  }
  void onLidar(const sensor_msgs::PointCloud2::ConstPtr& m) { heard(Source::kLidar, m->header); }
  void onJoystick(const JoystickCommand::ConstPtr& m) { heard(Source::kCommand, m->header); }
  void onThrusters(const ThrusterSetpoints::ConstPtr& m) { heard(Source::kCommand, m->header); }
  void onRc(const RcChannels::ConstPtr& m) { heard(Source::kCommand, m->header); }
  void onSonar(const SonarBeam::ConstPtr& m) {  // a beam the head itself flags as not valid is no sonar data
    if (!(m->head_status & (SonarBeam::STATUS_FAULT | SonarBeam::STATUS_CENTRING))) heard(Source::kSonar, m->header);
  }
  void onUsbl(const UsblFix::ConstPtr& m) {
    if (m->quality == UsblFix::QUALITY_OK) heard(Source::kUsbl, m->header);
  }
  void onPressure(const sensor_msgs::FluidPressure::ConstPtr& m) {
    if (std::isfinite(m->fluid_pressure)) heard(Source::kDepth, m->header);
  }

  // Odometry in map (ENU): the position to local NED for the operating region; the AUV's depth is -z. The USV's
  // course over ground for the time to collision.
  void onOdom(const nav_msgs::Odometry::ConstPtr& m) {
    double t;
    if (!stampOf(m->header, t)) return;
    const auto& q = m->pose.pose.position;
    std::lock_guard<std::mutex> l(mutex_);
    if (std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z)) sup_->heard(Source::kNavigation, t);
    sup_->position(t, q.y, q.x);             // north, east; a non-finite pose is counted as bad input
    if (vehicle_ == "auv") sup_->depth(t, -q.z);
    if (vehicle_ != "usv") return;
    const VehicleState s = ros_util::stateFromOdom(*m);
    position_ = s.position.head<2>();
    velocity_ = Eigen::Rotation2Dd(s.yaw) * s.velocity.head<2>();  // body -> NED
    have_course_ = true;
    checkCollision(t);
  }

  // The LiDAR's obstacles (map_ned), each frame replacing the last.
  void onObstacles(const TargetArray::ConstPtr& m) {
    double t;
    if (!stampOf(m->header, t)) return;
    std::lock_guard<std::mutex> l(mutex_);
    obstacles_.clear();
    for (const auto& o : m->targets) {
      safety::SeenObstacle so;
      so.origin = {o.origin.x, o.origin.y};
      so.axis = {o.axis.x, o.axis.y};
      so.length = o.length;
      so.width = o.width;
      obstacles_.push_back(so);
    }
    checkCollision(t);
  }
  // The guidance's safety boxes after each replan (map_ned), for the safe side.
  void onBoxes(const SafetyBoxArray::ConstPtr& m) {
    double t;
    if (!stampOf(m->header, t)) return;
    std::lock_guard<std::mutex> l(mutex_);
    boxes_.clear();
    for (const auto& b : m->boxes) {
      safety::SafetyBoxView v;
      for (int i = 0; i < 4; ++i) v.corners[i] = {b.corners[i].x, b.corners[i].y};
      v.cuts_path = b.cuts_path;
      v.blocked = b.side == SafetyBox::SIDE_BLOCKED;
      boxes_.push_back(v);
    }
    checkCollision(t);
  }
  void checkCollision(double t) {  // under mutex_
    if (!have_course_) return;
    collision_ = safety::timeToCollision(position_, velocity_, obstacles_, sup_->config().collision_radius);
    if (collision_.skipped) counters_.increment("bad_obstacles", collision_.skipped);
    safe_side_ = safety::safeSideExists(boxes_, position_);
    sup_->timeToCollision(t, collision_.ttc, safe_side_);  // NaN (a bad course): refused and counted there
  }

  // What the CAN gateway (the simulator, in simulation) reports of the bus and the jets.
  void onAnswering(const WaterjetAnswering::ConstPtr& m) {
    double t;
    if (!stampOf(m->header, t)) return;
    std::lock_guard<std::mutex> l(mutex_);
    for (int i = 0; i < 2; ++i) sup_->jetAnswering(t, i, m->answering[i]);
  }
  void onBus(const CanBusState::ConstPtr& m) {
    double t;
    if (!stampOf(m->header, t)) return;
    std::lock_guard<std::mutex> l(mutex_);
    sup_->busOff(t, m->state == CanBusState::STATE_BUS_OFF || m->state == CanBusState::STATE_DOWN);
  }

  // Manual joystick / steering wheel seen from the bridge (the CAN gateway): manual until manual_timeout after
  // the last one, as the USV mission and simulator take it.
  void onManual(const JoystickCommand::ConstPtr& m) {
    if (m->priority < JoystickCommand::PRIORITY_MANUAL) return;
    double t;
    if (!stampOf(m->header, t)) return;
    std::lock_guard<std::mutex> l(mutex_);
    last_manual_ = manual_ ? std::max(last_manual_, t) : t;
    if (!manual_) sup_->setManual(true);
    manual_ = true;
  }

  // ---------------------------------------------------------------- the decision
  void onTimer(const ros::TimerEvent&) {
    const ros::Time now = ros::Time::now();
    if (now.isZero()) return;  // no clock yet
    std::vector<SafetyState> transitions;
    SafetyState state;
    bool publish = false;
    {
      std::lock_guard<std::mutex> l(mutex_);
      if (manual_ && now.toSec() - last_manual_ > manual_timeout_) {
        manual_ = false;
        sup_->setManual(false);
      }
      if (link_up_) sup_->heard(Source::kLink, now.toSec());
      const safety::SupervisorOutput out = sup_->update(now.toSec());
      const safety::Decision& d = out.decision;
      std::vector<std::string> active;
      for (std::size_t i = 0; i < safety::kRuleCount; ++i)
        if (sup_->active(safety::Rule(i))) active.push_back(safety::ruleName(safety::Rule(i)));

      for (const auto& tr : out.transitions) {  // "manual" is a transition too (its reason says which way)
        if (tr.rule == "manual" && tr.to_active)
          NODELET_WARN("safety: %s", tr.reason.c_str());
        else if (tr.rule == "manual")
          NODELET_INFO("safety: %s", tr.reason.c_str());
        else if (tr.to_active)
          NODELET_WARN("safety: %s active (%s): %s", tr.rule.c_str(), safety::actionName(tr.action), tr.reason.c_str());
        else
          NODELET_INFO("safety: %s released: %s", tr.rule.c_str(), tr.reason.c_str());
        SafetyState m = message(tr.to_active ? tr.action : safety::Action::kNone, tr.rule, tr.reason, d.manual, active);
        m.header.stamp = ros::Time(tr.t);
        transitions.push_back(std::move(m));
      }

      const bool changed = !published_ || d.action != decision_.action || d.active_rule != decision_.active_rule ||
                           d.manual != decision_.manual || active != active_;
      publish = changed || !out.transitions.empty() || now < last_publish_ ||
                now - last_publish_ >= ros::Duration(1.0);
      decision_ = d;
      active_ = active;
      if (publish) {
        state = message(d.action, d.active_rule, d.reason, d.manual, active);
        state.header.stamp = now;
        last_publish_ = now;
        published_ = true;
      }
    }
    for (const auto& m : transitions) transitions_pub_.publish(m);
    if (publish) state_pub_.publish(state);
  }

  SafetyState message(safety::Action a, const std::string& rule, const std::string& reason, bool manual,
                      const std::vector<std::string>& active) const {
    SafetyState m;
    m.vehicle = vehicle_;
    m.action = static_cast<std::uint8_t>(a);
    m.action_name = safety::actionName(a);
    m.active_rule = rule;
    m.reason = reason;
    m.manual = manual;
    m.active_rules = active;
    return m;
  }

  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& s) {
    using DS = diagnostic_msgs::DiagnosticStatus;
    std::lock_guard<std::mutex> l(mutex_);
    const safety::Decision& d = decision_;
    const unsigned char level = d.action == safety::Action::kNone   ? DS::OK
                                : d.action == safety::Action::kWarn ? DS::WARN
                                                                    : DS::ERROR;
    std::string text;
    if (d.manual)
      text = "manual control: no automatic action" + (d.active_rule.empty() ? "" : " (" + d.active_rule + ": " + d.reason + ")");
    else if (d.action == safety::Action::kNone)
      text = "no action";
    else
      text = std::string(safety::actionName(d.action)) + " (" + d.active_rule + "): " + d.reason;
    s.summary(level, text);
    std::string active;
    for (const auto& r : active_) active += (active.empty() ? "" : ", ") + r;
    s.add("vehicle", vehicle_);
    s.add("action", safety::actionName(d.action));
    s.add("active_rule", d.active_rule);
    s.add("reason", d.reason);
    s.add("manual", d.manual ? "true" : "false");
    s.add("active_rules", active);
    if (vehicle_ == "usv") {
      s.addf("time_to_collision_s", "%.1f", collision_.ttc);
      s.add("safe_side", safe_side_ ? "yes" : "none (a safety box on the path is blocked, or the USV is inside one)");
      ros_util::addCounters(s, counters_, {"bad_obstacles"});
    }
    const auto counts = sup_->counters().snapshot();  // both shown from the start, zero until they move
    for (const char* k : {"bad_input", "transitions"})
      if (!counts.count(k)) s.add(k, 0);
    ros_util::addCounters(s, sup_->counters(), {"bad_input"});
  }

  std::atomic<bool> link_up_{false};
  // the time to collision's inputs (USV)
  Eigen::Vector2d position_ = Eigen::Vector2d::Zero(), velocity_ = Eigen::Vector2d::Zero();
  bool have_course_ = false, safe_side_ = true;
  std::vector<safety::SeenObstacle> obstacles_;
  std::vector<safety::SafetyBoxView> boxes_;
  safety::Collision collision_;
  Counters counters_;
  std::mutex mutex_;  // the core and the decision: callbacks and timers may run concurrently
  std::unique_ptr<safety::Supervisor> sup_;
  std::string vehicle_;
  double manual_timeout_ = 1.0, last_manual_ = 0.0;  // [s]
  bool manual_ = false;
  safety::Decision decision_;
  std::vector<std::string> active_;
  bool published_ = false;
  ros::Time last_publish_;
  ros::Publisher state_pub_, transitions_pub_;
  std::vector<ros::Subscriber> subs_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diag_timer_;
  ros::Timer timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::SafetySupervisorNodelet, nodelet::Nodelet)
