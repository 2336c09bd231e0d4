// USV mission: station keeping until /target arrives (relayed from the AUV), then a straight path with a
// waypoint every 10 m to the stand-off point (the SBB planner in guidance inserts the avoidance), then station
// keeping. Manual joystick or steering wheel commands suspend it; a silent AUV side is reported.
#include <diagnostic_updater/diagnostic_updater.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/GuidanceStatus.h>
#include <offshore_gnc/JoystickCommand.h>
#include <offshore_gnc/LinkStatus.h>
#include <offshore_gnc/Target.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/mission/mission.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "ros_mission.h"

namespace offshore_gnc {

class UsvMissionNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    mission::UsvMissionParams mp;
    try {
      mp.waypoint_spacing = p.number("waypoint_spacing", mp.waypoint_spacing, 0.5, 1000);
      mp.standoff = p.number("standoff", mp.standoff, 0, 500);
      mp.min_distance = p.number("min_distance", mp.min_distance, 0, 100);
      mp.peer_timeout = p.number("peer_timeout", mp.peer_timeout, 1, 1e5);
      manual_timeout_ = p.number("manual_timeout", 1.0, 0.05, 60);
      mission_ = std::make_unique<mission::UsvMission>(mp);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    path_pub_ = nh.advertise<nav_msgs::Path>("guidance/path", 1, true);
    status_pub_ = nh.advertise<MissionStatus>("mission/status", 10, true);
    markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("mission/markers", 1, true);
    target_sub_ = nh.subscribe("/target", 10, &UsvMissionNodelet::onTarget, this);
    odom_sub_ = nh.subscribe("odom", 10, &UsvMissionNodelet::onOdom, this);
    guidance_sub_ = nh.subscribe("guidance/status", 10, &UsvMissionNodelet::onGuidance, this);
    manual_sub_ = nh.subscribe("manual_cmd", 10, &UsvMissionNodelet::onManual, this);
    link_sub_ = nh.subscribe("/relay/link_status", 10, &UsvMissionNodelet::onLink, this);
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("usv_mission");
    updater_->add("mission", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      const auto ph = mission_->phase();
      s.summary(ph == mission::UsvPhase::PeerLost ? diagnostic_msgs::DiagnosticStatus::WARN
                                                  : diagnostic_msgs::DiagnosticStatus::OK,
                mission::toString(ph));
      ros_util::addCounters(s, mission_->counters(), {"target_not_finite", "pose_not_finite"});
    });
    timer_ = nh.createTimer(ros::Duration(0.5), &UsvMissionNodelet::onTimer, this);
  }

  void onOdom(const nav_msgs::Odometry::ConstPtr& o) {
    // odometry is in map (ENU): north = y, east = x; ENU yaw -> NED heading
    const auto& q = o->pose.pose.orientation;
    const double yaw_enu = std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
    mission_->onPose({o->pose.pose.position.y, o->pose.pose.position.x}, o->header.stamp.toSec());
    if (!holding_published_ && mission_->pathVersion() == 0 && mission_->stationPoint()) {
      // dynamic positioning where the mission starts, until a target arrives (paper 3.2.3)
      publishPath(mission::holdPath(*mission_->stationPoint(), geo::enuYawToNed(yaw_enu)));
      holding_published_ = true;
    }
  }

  void publishPath(const std::vector<Eigen::Vector2d>& path) {
    std::vector<Eigen::Vector3d> pts;
    for (const auto& w : path) pts.emplace_back(w.x(), w.y(), 0.0);
    path_pub_.publish(mission_ros::toPath(pts, ros::Time::now()));
  }

  void onTarget(const Target::ConstPtr& t) {
    const int before = mission_->pathVersion();
    const bool transit = mission_->onTarget({t->origin.x, t->origin.y}, ros::Time::now().toSec());
    if (mission_->pathVersion() != before) {
      markers_pub_.publish(mission_ros::targetMarker(t->origin.x, t->origin.y, t->origin.z, ros::Time::now()));
      publishPath(mission_->path().empty() ? mission::holdPath(*mission_->stationPoint(), 0.0) : mission_->path());
      following_ = false;
      NODELET_INFO("target received: %s", mission_->detail().c_str());
    } else if (!transit) {
      NODELET_DEBUG("target ignored: %s", mission_->detail().c_str());
    }
    publishStatus();
  }

  void onGuidance(const GuidanceStatus::ConstPtr& s) {
    distance_to_go_ = s->distance_to_go;
    if (mission_->phase() != mission::UsvPhase::Transit) return;
    if (s->mode == GuidanceStatus::MODE_FOLLOW_PATH) following_ = true;
    if (following_ && s->mode == GuidanceStatus::MODE_STATION_KEEPING) {
      mission_->onPathFinished(s->header.stamp.toSec());
      NODELET_INFO("%s", mission_->detail().c_str());
      publishStatus();
    }
  }

  void onManual(const JoystickCommand::ConstPtr& c) {
    last_manual_ = ros::Time::now();
    if (c->priority >= JoystickCommand::PRIORITY_MANUAL) mission_->onManual(true, last_manual_.toSec());
  }

  void onLink(const LinkStatus::ConstPtr& l) {
    if (l->up) mission_->onPeerAlive(ros::Time::now().toSec());
  }

  void onTimer(const ros::TimerEvent&) {
    const ros::Time now = ros::Time::now();
    if (now.isZero()) return;
    if (!last_manual_.isZero() && (now - last_manual_).toSec() > manual_timeout_) mission_->onManual(false, now.toSec());
    mission_->tick(now.toSec());
    publishStatus();
    updater_->update();
  }

  void publishStatus() {
    const auto ph = mission_->phase();
    const double dtg = ph == mission::UsvPhase::Transit ? distance_to_go_ : std::numeric_limits<double>::quiet_NaN();
    status_pub_.publish(mission_ros::status("usv", mission::toString(ph), mission_->detail(), mission_->finished(),
                                            ph == mission::UsvPhase::Arrived, dtg));
  }

  double manual_timeout_ = 1.0, distance_to_go_ = std::numeric_limits<double>::quiet_NaN();
  bool following_ = false, holding_published_ = false;
  ros::Time last_manual_;
  std::unique_ptr<mission::UsvMission> mission_;
  ros::Publisher path_pub_, status_pub_, markers_pub_;
  ros::Subscriber target_sub_, odom_sub_, guidance_sub_, manual_sub_, link_sub_;
  ros::Timer timer_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::UsvMissionNodelet, nodelet::Nodelet)
