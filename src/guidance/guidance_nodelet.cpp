// Guidance nodelet: path + odometry (+ obstacles and tracks, USV) -> guidance::GuidancePipeline (SBB planner,
// replanning, COLREGs avoidance of moving tracks, LOS) -> GuidanceStatus (with the reference control follows) at the guidance rate, the safety boxes, the
// planned path and rviz markers. Thin: parameters, message conversion, publishing.
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <nav_msgs/Path.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/GuidanceConfig.h>
#include <offshore_gnc/GuidanceStatus.h>
#include <offshore_gnc/SafetyBoxArray.h>
#include <offshore_gnc/TargetArray.h>
#include <offshore_gnc/TrackArray.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include <memory>
#include <mutex>

#include "offshore_gnc/guidance/pipeline.h"
#include "offshore_gnc/models/hull.h"
#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/markers.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/reconfigure.h"
#include "ros_obstacles.h"

namespace offshore_gnc {

class GuidanceNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    ros_util::ParamReader p(pnh);
    guidance::GuidanceParams gp;
    try {
      guidance::GuidanceParams v;  // the vehicle first: its preset is what the other parameters replace
      ros_util::readParam(p, guidance::GuidanceParams::table(), "vehicle", v);
      gp = guidance::GuidanceParams::preset(v.vehicle);
      ros_util::readParams(p, guidance::GuidanceParams::table(), gp);
      frame_ = gp.frame_id;
      pipeline_ = std::make_unique<guidance::GuidancePipeline>(gp);
      if (gp.vehicle == "usv") {  // a hold keeps the hull clear: its outline of the vehicle config (vehicle/outline)
        models::HullFootprint hull;
        ros_util::readParams(ros_util::ParamReader(nh), models::HullFootprint::table(), hull);
        hull.validate();
        pipeline_->setHullReach({hull.ahead(), hull.astern(), hull.abeam()});
      }
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    status_pub_ = nh.advertise<GuidanceStatus>("guidance/status", 10);
    boxes_pub_ = nh.advertise<SafetyBoxArray>("guidance/safety_boxes", 1, true);
    planned_pub_ = nh.advertise<nav_msgs::Path>("guidance/planned_path", 1, true);
    obstacles_pub_ = nh.advertise<TargetArray>("guidance/obstacles", 1, true);
    markers_.advertise(nh, "markers", "sbb", true);
    path_sub_ = nh.subscribe("guidance/path", 1, &GuidanceNodelet::onPath, this);
    odom_sub_ = nh.subscribe("odom", 10, &GuidanceNodelet::onOdom, this);
    if (gp.sbb_enabled) {
      obstacles_sub_ = nh.subscribe("obstacles", 1, &GuidanceNodelet::onObstacles, this);
      keep_clear_sub_ = nh.subscribe("mission/keep_clear", 1, &GuidanceNodelet::onKeepClear, this);  // latched
      tracks_sub_ = nh.subscribe("tracks", 1, &GuidanceNodelet::onTracks, this);  // LidarTargets' (issue 33)
    }

    reconfigure_ = std::make_unique<dynamic_reconfigure::Server<GuidanceConfig>>(reconf_mutex_, pnh);
    reconfigure_->updateConfig(ros_util::toReconfigure<GuidanceConfig>(guidance::GuidanceParams::table(), gp));
    reconfigure_->setCallback([this](GuidanceConfig& c, uint32_t) { onReconfigure(c); });

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, getName());
    updater_->setHardwareID(gp.vehicle + "_guidance");
    updater_->add("guidance", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      std::lock_guard<std::mutex> l(mutex_);
      const bool fault = last_.los.mode == guidance::Mode::kHoldFault;
      s.summary(fault ? diagnostic_msgs::DiagnosticStatus::WARN : diagnostic_msgs::DiagnosticStatus::OK,
                last_.los.status_text.empty() ? "idle" : last_.los.status_text);
      ros_util::addCounters(s, pipeline_->losCounters(), {"nan_pose", "bad_path", "bad_dt"});
      ros_util::addCounters(s, pipeline_->counters(), {"stale_odom", "bad_obstacles", "rejected_paths"});
      ros_util::addCounters(s, pipeline_->colregsCounters(),
                            {"bad_tracks", "unknown_track_id", "encounters", "give_way", "stand_on_acted", "no_safe_course"});
      if (last_.colregs.encounter != guidance::Encounter::kNone)
        s.add("encounter", std::string(guidance::toString(last_.colregs.encounter)) + " with track " +
                               std::to_string(last_.colregs.contact));
      s.add("obstacles_remembered", pipeline_->remembered());  // kept from memory, out of the LiDAR's view
    });
    timer_ = nh.createTimer(ros::Duration(1.0 / gp.rate), &GuidanceNodelet::onTimer, this);
    NODELET_INFO("%s guidance: LOS kp %.4f ki %.4f crab %s, R %.1f m (%s), SBB %s", gp.vehicle.c_str(), gp.los.kp,
                 gp.los.ki, gp.los.adaptive_crab ? "adaptive" : "off", gp.los.acceptance_radius,
                 gp.los.sphere ? "sphere" : "circle", gp.sbb_enabled ? "on" : "off");
  }

  void onReconfigure(const GuidanceConfig& c) {
    std::lock_guard<std::mutex> l(mutex_);
    try {
      pipeline_->setParams(ros_util::fromReconfigure(c, guidance::GuidanceParams::table(), pipeline_->params()));
    } catch (const ConfigError& e) {
      NODELET_ERROR("reconfigure rejected: %s", e.what());
    }
  }

  void onPath(const nav_msgs::Path::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    if (!m->header.frame_id.empty() && m->header.frame_id != frame_) {
      NODELET_ERROR_THROTTLE(5.0, "path in frame '%s', expected '%s': rejected", m->header.frame_id.c_str(),
                             frame_.c_str());
      pipeline_->rejectPath("path rejected: frame '" + m->header.frame_id + "', expected '" + frame_ + "'");
      return;
    }
    std::vector<Eigen::Vector3d> path;
    for (const auto& ps : m->poses) path.emplace_back(ps.pose.position.x, ps.pose.position.y, ps.pose.position.z);
    pipeline_->setPath(path);
  }

  void onOdom(const nav_msgs::Odometry::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    pipeline_->setState(ros_util::stateFromOdom(*m), ros::Time::now().toSec());
  }

  void onObstacles(const TargetArray::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    pipeline_->setObstacles(guidance_ros::obstaclesOf(*m), ros::Time::now().toSec());
  }

  // the confirmed moving ones are met by the rules, and not boxed where they stand
  void onTracks(const TrackArray::ConstPtr& m) {
    std::vector<guidance::Contact> contacts;
    contacts.reserve(m->tracks.size());
    for (const auto& tr : m->tracks) {
      guidance::Contact c;
      c.id = tr.id;
      c.position = {tr.position.x, tr.position.y};
      c.velocity = {tr.velocity.x, tr.velocity.y};
      for (int i = 0; i < 16; ++i) c.covariance(i / 4, i % 4) = tr.covariance[i];  // row-major
      c.length = tr.length;
      c.width = tr.width;
      c.confirmed = tr.status == Track::CONFIRMED;
      contacts.push_back(c);
    }
    std::lock_guard<std::mutex> l(mutex_);
    // the tracks' time: their frame's stamp (positions are predicted from it), as the obstacles' is taken now
    const double t = m->header.stamp.isZero() ? ros::Time::now().toSec() : m->header.stamp.toSec();
    pipeline_->setTracks(contacts, t);
  }

  // the mission's (the surfaced AUV it recovers): kept until the next message
  void onKeepClear(const TargetArray::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    pipeline_->setKnownObstacles(guidance_ros::obstaclesOf(*m));
  }

  void onTimer(const ros::TimerEvent& ev) {
    std::lock_guard<std::mutex> l(mutex_);
    const double dt = ev.last_real.isZero() ? 1.0 / pipeline_->params().rate : (ev.current_real - ev.last_real).toSec();
    if (!pipeline_->update(ros::Time::now().toSec(), dt, last_)) return;
    if (last_.los.mode == guidance::Mode::kHoldFault)
      NODELET_WARN_THROTTLE(5.0, "guidance holding: %s", last_.los.status_text.c_str());
    if (last_.planned_changed) publishPlanned();
    if (last_.boxes_changed) publishBoxes();
    const auto& o = last_.los;
    GuidanceStatus g;
    g.header.stamp = ros::Time::now();
    g.header.frame_id = frame_;
    g.mode = static_cast<uint8_t>(o.mode);
    g.active_leg = static_cast<uint32_t>(o.active_leg);
    g.num_waypoints = static_cast<uint32_t>(o.num_waypoints);
    g.cross_track_error = o.cross_track_error;
    g.along_track_distance = o.along_track_distance;
    g.distance_to_go = o.distance_to_go;
    g.crab_angle = o.crab_angle;
    g.acceptance_radius = o.acceptance_radius;
    g.status_text = o.status_text;
    ros_util::fillReference(last_.reference, g);
    g.encounter = static_cast<uint8_t>(last_.colregs.encounter);
    g.encounter_contact = last_.colregs.contact;
    g.encounter_action = static_cast<uint8_t>(last_.colregs.action);
    status_pub_.publish(g);
  }

  void publishPlanned() {
    nav_msgs::Path m;
    m.header.stamp = ros::Time::now();
    m.header.frame_id = frame_;
    for (const auto& w : pipeline_->plannedPath()) {
      geometry_msgs::PoseStamped ps;
      ps.header = m.header;
      ps.pose.position.x = w.x(), ps.pose.position.y = w.y(), ps.pose.position.z = w.z();
      ps.pose.orientation.w = 1.0;
      m.poses.push_back(ps);
    }
    planned_pub_.publish(m);
  }

  void publishBoxes() {
    const auto& plan = pipeline_->plan();
    if (plan.blocked) NODELET_WARN_THROTTLE(5.0, "%s", plan.status.c_str());
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
    // what the boxes were planned round, those kept out of the LiDAR's view among them (the mission's recovery)
    obstacles_pub_.publish(guidance_ros::targetsOf(pipeline_->plannedRound(), a.header, Target::SOURCE_LIDAR));
  }

  std::string frame_;
  std::unique_ptr<guidance::GuidancePipeline> pipeline_;
  guidance::GuidanceOutput last_;
  std::mutex mutex_;
  boost::recursive_mutex reconf_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<GuidanceConfig>> reconfigure_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::Publisher status_pub_, boxes_pub_, planned_pub_, obstacles_pub_;
  ros_util::NamespaceMarkers markers_;
  ros::Subscriber path_sub_, odom_sub_, obstacles_sub_, keep_clear_sub_, tracks_sub_;
  ros::Timer timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::GuidanceNodelet, nodelet::Nodelet)
