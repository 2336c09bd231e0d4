// Guidance nodelet (issue 3): path + odometry (+ obstacles, USV) -> SBB planner -> LOS guidance ->
// GuidanceStatus at the control rate, safety boxes, the planned path and rviz markers. Thin: the maths is in
// guidance::LosGuidance and guidance::planSbb.
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <nav_msgs/Path.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/GuidanceConfig.h>
#include <offshore_gnc/GuidanceStatus.h>
#include <offshore_gnc/SafetyBoxArray.h>
#include <offshore_gnc/TargetArray.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include <memory>
#include <mutex>

#include "offshore_gnc/guidance/los.h"
#include "offshore_gnc/guidance/sbb.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/markers.h"
#include "offshore_gnc/ros/params.h"
#include "ros_convert.h"

namespace offshore_gnc {

class GuidanceNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    ros_util::ParamReader p(pnh);
    guidance::LosParams lp;
    try {
      vehicle_ = p.choice("vehicle", "usv", {"usv", "auv"});
      const bool auv = vehicle_ == "auv";
      lp.kp = p.number("los/kp", auv ? 0.0333 : 0.1, 1e-4, 10.0);
      lp.ki = p.number("los/ki", auv ? 0.0 : 0.001, 0.0, 1.0);
      lp.integral_limit = p.number("los/integral_limit", 0.35, 0.0, 1.57);
      lp.adaptive_crab = p.flag("los/adaptive_crab", true);
      lp.crab_gain = p.number("los/crab_gain", 0.002, 0.0, 1.0);
      lp.crab_limit = p.number("los/crab_limit", 0.6, 0.0, 1.57);
      lp.sphere = p.flag("los/sphere", auv);
      lp.acceptance_radius = p.number("los/acceptance_radius", auv ? 3.0 : 16.0, 0.01, 1000.0);
      lp.surge_speed = p.number("los/surge_speed", auv ? 0.3 : 1.5, 0.0, 20.0);
      lp.final_radius = p.number("los/final_radius", 0.0, 0.0, 1000.0);
      lp.detour_radius = p.number("los/detour_radius", 0.0, 0.0, 1000.0);
      lp.approach_distance = p.number("los/approach_distance", 0.0, 0.0, 1e4);
      lp.approach_speed = p.number("los/approach_speed", 0.3, 0.0, 20.0);
      sbb_.safety_x = p.number("sbb/safety_x", 5.0, 0.0, 1000.0);
      sbb_.safety_y = p.number("sbb/safety_y", 5.0, 0.0, 1000.0);
      sbb_.corridor = p.number("sbb/corridor", 2.0, 0.0, 100.0);
      sbb_.max_offset = p.number("sbb/max_offset", 50.0, 0.0, 10000.0);
      sbb_.stop_margin = p.number("sbb/stop_margin", 2.0, 0.0, 100.0);
      sbb_.approach = p.number("sbb/approach", 0.0, 0.0, 1000.0);
      sbb_on_ = p.flag("sbb/enabled", !auv);
      obstacle_timeout_ = p.number("sbb/obstacle_timeout", 5.0, 0.1, 3600.0);
      replan_distance_ = p.number("sbb/replan_distance", 0.5, 0.0, 100.0);
      rate_ = p.number("rate", 10.0, 0.1, 100.0);
      odom_timeout_ = p.number("odom_timeout", 1.0, 0.01, 60.0);
      frame_ = p.text("frame_id", "map_ned");
      los_ = std::make_unique<guidance::LosGuidance>(lp);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    status_pub_ = nh.advertise<GuidanceStatus>("guidance/status", 10);
    boxes_pub_ = nh.advertise<SafetyBoxArray>("guidance/safety_boxes", 1, true);
    planned_pub_ = nh.advertise<nav_msgs::Path>("guidance/planned_path", 1, true);
    markers_.advertise(nh, "markers", "sbb", true);
    path_sub_ = nh.subscribe("guidance/path", 1, &GuidanceNodelet::onPath, this);
    odom_sub_ = nh.subscribe("odom", 10, &GuidanceNodelet::onOdom, this);
    if (sbb_on_) obstacles_sub_ = nh.subscribe("obstacles", 1, &GuidanceNodelet::onObstacles, this);

    reconfigure_ = std::make_unique<dynamic_reconfigure::Server<GuidanceConfig>>(reconf_mutex_, pnh);
    GuidanceConfig c = GuidanceConfig::__getDefault__();  // a bare one copies unset group flags (UBSan)
    c.kp = lp.kp, c.ki = lp.ki, c.integral_limit = lp.integral_limit, c.adaptive_crab = lp.adaptive_crab;
    c.crab_gain = lp.crab_gain, c.crab_limit = lp.crab_limit, c.acceptance_radius = lp.acceptance_radius;
    c.surge_speed = lp.surge_speed, c.final_radius = lp.final_radius, c.approach_distance = lp.approach_distance;
    c.detour_radius = lp.detour_radius;
    c.safety_x = sbb_.safety_x, c.safety_y = sbb_.safety_y;
    c.corridor = sbb_.corridor, c.max_offset = sbb_.max_offset;
    reconfigure_->updateConfig(c);
    reconfigure_->setCallback([this](GuidanceConfig& c, uint32_t) { onReconfigure(c); });

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, getName());
    updater_->setHardwareID(vehicle_ + "_guidance");
    updater_->add("guidance", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      std::lock_guard<std::mutex> l(mutex_);
      const bool fault = last_.mode == guidance::Mode::kHoldFault;
      s.summary(fault ? diagnostic_msgs::DiagnosticStatus::WARN : diagnostic_msgs::DiagnosticStatus::OK,
                last_.status_text.empty() ? "idle" : last_.status_text);
      ros_util::addCounters(s, los_->counters(), {"nan_pose", "bad_path", "bad_dt"});
      ros_util::addCounters(s, counters_, {"stale_odom", "bad_obstacles"});
    });
    timer_ = nh.createTimer(ros::Duration(1.0 / rate_), &GuidanceNodelet::onTimer, this);
    NODELET_INFO("%s guidance: LOS kp %.4f ki %.4f crab %s, R %.1f m (%s), SBB %s", vehicle_.c_str(), lp.kp, lp.ki,
                 lp.adaptive_crab ? "adaptive" : "off", lp.acceptance_radius, lp.sphere ? "sphere" : "circle",
                 sbb_on_ ? "on" : "off");
  }

  void onReconfigure(const GuidanceConfig& c) {
    std::lock_guard<std::mutex> l(mutex_);
    guidance::LosParams lp = los_->params();
    lp.kp = c.kp, lp.ki = c.ki, lp.integral_limit = c.integral_limit, lp.adaptive_crab = c.adaptive_crab;
    lp.crab_gain = c.crab_gain, lp.crab_limit = c.crab_limit, lp.acceptance_radius = c.acceptance_radius;
    lp.surge_speed = c.surge_speed, lp.final_radius = c.final_radius, lp.approach_distance = c.approach_distance;
    lp.detour_radius = c.detour_radius;
    guidance::SbbParams sp = sbb_;
    sp.safety_x = c.safety_x, sp.safety_y = c.safety_y, sp.corridor = c.corridor, sp.max_offset = c.max_offset;
    try {
      lp.validate();
      sp.validate();
      los_->setParams(lp);
      sbb_ = sp;
      replan_ = true;
    } catch (const ConfigError& e) {
      NODELET_ERROR("reconfigure rejected: %s", e.what());
    }
  }

  void onPath(const nav_msgs::Path::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    base_path_.clear();
    for (const auto& ps : m->poses)
      base_path_.emplace_back(ps.pose.position.x, ps.pose.position.y, ps.pose.position.z);
    if (!m->header.frame_id.empty() && m->header.frame_id != frame_) {
      NODELET_ERROR_THROTTLE(5.0, "path in frame '%s', expected '%s': rejected", m->header.frame_id.c_str(),
                             frame_.c_str());
      counters_.increment("bad_path_frame");
      base_path_.clear();
      los_->setPath({V3(NAN, NAN, NAN)});  // reports the rejection as a hold fault
      return;
    }
    new_path_ = true;
    boxes_.clear();  // a new route chooses its detour sides afresh
    replan_ = true;
  }

  void onOdom(const nav_msgs::Odometry::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    state_ = ros_util::stateFromOdom(*m);
    odom_time_ = ros::Time::now();
    have_odom_ = true;
  }

  void onObstacles(const TargetArray::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    obstacles_.clear();
    for (const auto& t : m->targets) {
      guidance::SbbObstacle o;
      o.id = t.id;
      o.origin = Eigen::Vector2d(t.origin.x, t.origin.y);
      o.length = t.length;
      o.width = t.width;
      if (!o.origin.allFinite() || !std::isfinite(o.length) || !std::isfinite(o.width)) {
        counters_.increment("bad_obstacles");
        NODELET_WARN_THROTTLE(5.0, "obstacle %u with non-finite geometry ignored", t.id);
        continue;
      }
      obstacles_.push_back(o);
    }
    obstacles_time_ = ros::Time::now();
    replan_ = true;
  }

  using V3 = Eigen::Vector3d;

  void replan() {
    if (!sbb_on_ || (ros::Time::now() - obstacles_time_).toSec() > obstacle_timeout_) obstacles_.clear();
    guidance::SbbPlan plan;
    if (obstacles_.empty() || base_path_.size() < 2) {
      plan.path = base_path_;
      plan.status = "path clear";
    } else {
      plan = guidance::planSbb(base_path_, state_.position.head<2>(), obstacles_, sbb_, boxes_);
      if (plan.blocked) NODELET_WARN_THROTTLE(5.0, "%s", plan.status.c_str());
    }
    // Re-set the LOS path only when it really changed (slowly moving obstacles), resuming on the nearest leg.
    bool changed = new_path_ || plan.path.size() != planned_.size() || plan.detour != planned_detour_;
    for (std::size_t i = 0; !changed && i < plan.path.size(); ++i)
      changed = (plan.path[i] - planned_[i]).norm() > replan_distance_;
    if (changed) {
      planned_ = plan.path;
      planned_detour_ = plan.detour;
      if (!los_->setPath(planned_, !new_path_, planned_detour_))
        NODELET_ERROR_THROTTLE(5.0, "path rejected (%zu waypoints): holding", base_path_.size());
      publishPlanned();
    }
    new_path_ = false;
    boxes_ = plan.boxes;
    publishBoxes(plan);
  }

  void onTimer(const ros::TimerEvent& ev) {
    std::lock_guard<std::mutex> l(mutex_);
    const double dt = ev.last_real.isZero() ? 1.0 / rate_ : (ev.current_real - ev.last_real).toSec();
    VehicleState s = state_;
    if (!have_odom_) return;  // nothing to report before the first pose
    if ((ros::Time::now() - odom_time_).toSec() > odom_timeout_) {
      counters_.increment("stale_odom");
      NODELET_WARN_THROTTLE(5.0, "odometry older than %.2f s: holding", odom_timeout_);
      s.position = V3::Constant(NAN);  // LosGuidance holds the last good position
    }
    if (replan_ && s.position.allFinite()) {
      replan();
      replan_ = false;
    }
    last_ = los_->update(s, std::min(dt, 1.0));
    if (!s.position.allFinite() && (ros::Time::now() - odom_time_).toSec() > odom_timeout_)
      last_.status_text = "odometry stale: holding the last good position";
    if (last_.mode == guidance::Mode::kHoldFault)
      NODELET_WARN_THROTTLE(5.0, "guidance holding: %s", last_.status_text.c_str());
    GuidanceStatus g;
    g.header.stamp = ros::Time::now();
    g.header.frame_id = frame_;
    g.mode = static_cast<uint8_t>(last_.mode);
    g.active_leg = static_cast<uint32_t>(last_.active_leg);
    g.num_waypoints = static_cast<uint32_t>(last_.num_waypoints);
    g.cross_track_error = last_.cross_track_error;
    g.along_track_distance = last_.along_track_distance;
    g.distance_to_go = last_.distance_to_go;
    g.path_angle = last_.path_angle;
    g.desired_heading = last_.desired_heading;
    g.desired_depth = vehicle_ == "auv" ? last_.desired_depth : NAN;
    g.desired_surge = last_.desired_surge;
    g.crab_angle = last_.crab_angle;
    g.acceptance_radius = last_.acceptance_radius;
    g.status_text = last_.status_text;
    status_pub_.publish(g);
  }

  void publishPlanned() {
    nav_msgs::Path m;
    m.header.stamp = ros::Time::now();
    m.header.frame_id = frame_;
    for (const auto& w : planned_) {
      geometry_msgs::PoseStamped ps;
      ps.header = m.header;
      ps.pose.position.x = w.x(), ps.pose.position.y = w.y(), ps.pose.position.z = w.z();
      ps.pose.orientation.w = 1.0;
      m.poses.push_back(ps);
    }
    planned_pub_.publish(m);
  }

  void publishBoxes(const guidance::SbbPlan& plan) {
    SafetyBoxArray a;
    a.header.stamp = ros::Time::now();
    a.header.frame_id = frame_;
    std::vector<visualization_msgs::Marker> ma;
    for (const auto& b : plan.boxes) {
      SafetyBox m;
      m.header = a.header;
      m.obstacle_ids = b.ids;
      m.center.x = b.center.x(), m.center.y = b.center.y();
      m.path_angle = b.path_angle;
      m.length = b.length;
      m.width = b.width;
      for (int i = 0; i < 4; ++i) m.corners[i].x = b.corners[i].x(), m.corners[i].y = b.corners[i].y();
      m.cuts_path = b.cuts_path;
      m.side = static_cast<int8_t>(b.side);
      a.boxes.push_back(m);
      visualization_msgs::Marker mk;
      mk.type = visualization_msgs::Marker::LINE_STRIP;
      mk.scale.x = 0.3;
      mk.color.a = 1.0;
      mk.color.r = b.cuts_path ? 1.0 : 0.5;
      mk.color.g = b.cuts_path ? 0.0 : 0.5;
      mk.pose.orientation.w = 1.0;
      for (int i = 0; i <= 4; ++i) mk.points.push_back(m.corners[i % 4]);
      ma.push_back(mk);
    }
    boxes_pub_.publish(a);
    markers_.publish(std::move(ma), a.header);
  }

  std::string vehicle_, frame_;
  double rate_ = 10, odom_timeout_ = 1, obstacle_timeout_ = 5, replan_distance_ = 0.5;
  bool sbb_on_ = true, have_odom_ = false, new_path_ = false, replan_ = false;
  guidance::SbbParams sbb_;
  std::unique_ptr<guidance::LosGuidance> los_;
  guidance::LosOutput last_;
  std::vector<V3> base_path_, planned_;
  std::vector<bool> planned_detour_;
  std::vector<guidance::SbbBox> boxes_;  // the last plan's: their sides are kept while safe
  std::vector<guidance::SbbObstacle> obstacles_;
  VehicleState state_;
  ros::Time odom_time_, obstacles_time_;
  Counters counters_;
  std::mutex mutex_;
  boost::recursive_mutex reconf_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<GuidanceConfig>> reconfigure_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::Publisher status_pub_, boxes_pub_, planned_pub_;
  ros_util::NamespaceMarkers markers_;
  ros::Subscriber path_sub_, odom_sub_, obstacles_sub_;
  ros::Timer timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::GuidanceNodelet, nodelet::Nodelet)
