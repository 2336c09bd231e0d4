// USV mission: mission::UsvMission fed the navigation pose, /target and the AUV mission's status (both relayed from
// the AUV), guidance's status, manual commands and the relay's link status; publishes the path it asks for (station
// keeping where it starts, the straight transit with a waypoint every 10 m, the recovery beside the surfaced AUV:
// the SBB planner in guidance inserts the avoidance), its status (relayed to the AUV: its arrival starts the AUV's
// ascent) and the received target for rviz. Thin: parameters, messages, publishing.
#include <diagnostic_updater/diagnostic_updater.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/GuidanceStatus.h>
#include <offshore_gnc/JoystickCommand.h>
#include <offshore_gnc/LinkStatus.h>
#include <offshore_gnc/Target.h>
#include <offshore_gnc/TargetArray.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

#include "offshore_gnc/mission/mission.h"
#include "offshore_gnc/models/hull.h"
#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/safety/supervisor.h"
#include "ros_mission.h"
#include "../guidance/ros_obstacles.h"

namespace offshore_gnc {

class UsvMissionNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    mission::UsvMissionParams mp;
    try {
      ros_util::readParams(p, mission::UsvMissionParams::table(), mp);
      mission_ = std::make_unique<mission::UsvMission>(mp);
      // Targets are checked against the operating region of the vehicle's safety supervisor, read as the
      // supervisor reads it (its preset and the parameters of `safety` beside this node, launch/safety.launch):
      // one region, defined once.
      safety::SupervisorConfig sc = safety::usvDefaults();
      ros_util::readParams(ros_util::ParamReader(ros::NodeHandle(nh, "safety")), safety::SupervisorConfig::table(), sc);
      if (!sc.region.empty()) mission_->setRegion(safety::Region::fromList(sc.region));
      // the recovery distance is the bow's: the hull's outline of the vehicle config (/usv/vehicle/outline)
      models::HullFootprint hull;
      ros_util::readParams(ros_util::ParamReader(nh), models::HullFootprint::table(), hull);
      hull.validate();
      mission_->setHullReach({hull.ahead(), hull.astern(), hull.abeam()});
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    path_pub_ = nh.advertise<nav_msgs::Path>("guidance/path", 1, true);
    keep_clear_pub_ = nh.advertise<TargetArray>("mission/keep_clear", 1, true);
    status_pub_ = nh.advertise<MissionStatus>("mission/status", 10, true);
    markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("mission/markers", 1, true);
    target_sub_ = nh.subscribe("/target", 10, &UsvMissionNodelet::onTarget, this);
    odom_sub_ = nh.subscribe("odom", 10, &UsvMissionNodelet::onOdom, this);
    guidance_sub_ = nh.subscribe("guidance/status", 10, &UsvMissionNodelet::onGuidance, this);
    manual_sub_ = nh.subscribe("manual_cmd", 10, &UsvMissionNodelet::onManual, this);
    link_sub_ = nh.subscribe("/relay/link_status", 10, &UsvMissionNodelet::onLink, this);
    auv_sub_ = nh.subscribe("/auv/mission/status", 10, &UsvMissionNodelet::onAuvStatus, this);  // relayed
    obstacles_sub_ = nh.subscribe("guidance/obstacles", 1, &UsvMissionNodelet::onObstacles, this);
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("usv_mission");
    updater_->add("mission", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      const auto ph = mission_->phase();
      s.summary(ph == mission::UsvPhase::PeerLost ? diagnostic_msgs::DiagnosticStatus::WARN
                                                  : diagnostic_msgs::DiagnosticStatus::OK,
                mission::toString(ph));
      ros_util::addCounters(s, mission_->counters(), {"target_not_finite", "pose_not_finite", "target_outside_region", "recovery_side_blocked"});
    });
    timer_ = nh.createTimer(ros::Duration(0.5), &UsvMissionNodelet::onTimer, this);
  }

  void onOdom(const nav_msgs::Odometry::ConstPtr& o) {
    const VehicleState s = ros_util::stateFromOdom(*o);
    mission_->onPose(s.position.head<2>(), s.yaw, o->header.stamp.toSec());
    publishPath();
  }

  void publishPath() {
    if (auto path = mission_->takePath()) {
      // what guidance must plan round besides its LiDAR's (the surfaced AUV), current before the path arrives
      std_msgs::Header h;
      h.stamp = ros::Time::now();
      h.frame_id = "map_ned";
      keep_clear_pub_.publish(guidance_ros::targetsOf(mission_->keepClear(), h, Target::SOURCE_MISSION));
      std::vector<Eigen::Vector3d> pts;
      for (const auto& w : *path) pts.emplace_back(w.x(), w.y(), 0.0);
      path_pub_.publish(mission_ros::toPath(pts, ros::Time::now()));
    }
  }

  void onTarget(const Target::ConstPtr& t) {
    const int before = mission_->pathVersion();
    const auto refused = mission_->counters().get("target_outside_region");
    mission_->onTarget({t->origin.x, t->origin.y}, ros::Time::now().toSec());
    if (mission_->counters().get("target_outside_region") != refused) {
      NODELET_ERROR("target at N %.1f E %.1f refused: %s", t->origin.x, t->origin.y, mission_->refusal().c_str());
    } else if (mission_->pathVersion() != before) {
      markers_pub_.publish(mission_ros::targetMarker(t->origin.x, t->origin.y, t->origin.z, ros::Time::now()));
      NODELET_INFO("target received: %s", mission_->detail().c_str());
    } else {
      NODELET_DEBUG("target ignored: %s", mission_->detail().c_str());
    }
    publishPath();
    publishStatus();
  }

  // what guidance plans round: the recovery's side keeps the hull clear of it
  void onObstacles(const TargetArray::ConstPtr& m) { mission_->setObstacles(guidance_ros::obstaclesOf(*m)); }

  void onGuidance(const GuidanceStatus::ConstPtr& s) {
    const auto before = mission_->phase();
    const bool holds = s->reference_mode == GuidanceStatus::REFERENCE_HOLD;
    mission_->onGuidance(static_cast<guidance::Mode>(s->mode), s->distance_to_go, s->header.stamp.toSec(),
                         holds ? Eigen::Vector2d(s->reference_point.x, s->reference_point.y) : mission::kNoPoint);
    if (mission_->phase() != before) {
      NODELET_INFO("%s", mission_->detail().c_str());
      publishStatus();
    }
  }

  void onManual(const JoystickCommand::ConstPtr& c) {
    if (c->priority >= JoystickCommand::PRIORITY_MANUAL) mission_->onManualCommand(ros::Time::now().toSec());
  }

  void onLink(const LinkStatus::ConstPtr& l) {
    if (l->up) mission_->onPeerAlive(ros::Time::now().toSec());
  }

  void onAuvStatus(const MissionStatus::ConstPtr& m) {
    const auto phase = mission::auvPhaseFromString(m->phase);
    if (!phase) {
      NODELET_WARN_THROTTLE(10.0, "AUV status with an unknown phase '%s' ignored", m->phase.c_str());
      return;
    }
    const auto before = mission_->phase();
    mission_->onAuvStatus(*phase, {m->position.x, m->position.y, m->position.z}, m->stationary,
                          ros::Time::now().toSec());
    afterChange(before);
  }

  void afterChange(mission::UsvPhase before) {
    publishPath();
    if (mission_->phase() != before) {
      NODELET_INFO("%s: %s", mission::toString(mission_->phase()), mission_->detail().c_str());
      publishStatus();
    }
  }

  void onTimer(const ros::TimerEvent&) {
    const ros::Time now = ros::Time::now();
    if (now.isZero()) return;
    const auto before = mission_->phase();
    mission_->tick(now.toSec());
    afterChange(before);
    publishStatus();
    updater_->update();
  }

  void publishStatus() {
    const auto ph = mission_->phase();
    const auto& pose = mission_->pose();
    const auto& station = mission_->stationPoint();
    const double nan = mission_ros::kNaN;
    status_pub_.publish(mission_ros::status(
        "usv", mission::toString(ph), mission_->detail(), mission_->finished(), ph == mission::UsvPhase::Recovered,
        mission_->distanceToGo(), mission_->onStationSince(),
        pose ? Eigen::Vector3d(pose->x(), pose->y(), 0.0) : Eigen::Vector3d::Constant(nan),
        station ? Eigen::Vector3d(station->x(), station->y(), 0.0) : Eigen::Vector3d::Constant(nan), false));
  }

  std::unique_ptr<mission::UsvMission> mission_;
  ros::Publisher path_pub_, keep_clear_pub_, status_pub_, markers_pub_;
  ros::Subscriber target_sub_, odom_sub_, guidance_sub_, manual_sub_, link_sub_, auv_sub_, obstacles_sub_;
  ros::Timer timer_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::UsvMissionNodelet, nodelet::Nodelet)
