// AUV mission: mission::AuvMission fed the sonar targets, guidance's status, the navigation (/auv/odom), the USV
// mission's status (relayed), the safety supervisor's decision and whether GPS fixes come (/auv/gps/fix), on a
// timer; publishes the path it asks for (the coverage, the hold at the find, the ascent, the hold at the surface),
// the confirmed and refined target on /target in map_ned with its WGS84 position for the USV (relayed), and its
// status (relayed to the USV: its position at the surface is where the USV recovers it). Thin: parameters,
// messages, publishing.
#include <diagnostic_updater/diagnostic_updater.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/GuidanceStatus.h>
#include <offshore_gnc/SafetyState.h>
#include <offshore_gnc/Target.h>
#include <offshore_gnc/TargetArray.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/NavSatFix.h>
#include <std_msgs/String.h>

#include <cmath>
#include <memory>

#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/mission/mission.h"
#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/site.h"
#include "ros_mission.h"

namespace offshore_gnc {

class AuvMissionNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    mission::AuvMissionParams mp;
    geo::LatLonAlt origin;
    try {
      ros_util::readParams(p, mission::AuvMissionParams::table(), mp);
      // the coverage area comes from the mission config (~coverage) or, in simulation, the scenario file
      // loaded into ~scenario (its auv/coverage section)
      const bool sc = getPrivateNodeHandle().hasParam("scenario/auv/coverage");
      ros_util::readParams(p, mission::CoverageArea::table(), mp.coverage, sc ? "scenario/auv/coverage/" : "coverage/");
      origin = ros_util::readOrigin();
      mission_ = std::make_unique<mission::AuvMission>(mp);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    frame_ = std::make_unique<geo::LocalNed>(origin);
    path_pub_ = nh.advertise<nav_msgs::Path>("guidance/path", 1, true);
    target_pub_ = nh.advertise<Target>("/target", 1, true);
    status_pub_ = nh.advertise<MissionStatus>("mission/status", 10, true);
    targets_sub_ = nh.subscribe("sonar/targets", 10, &AuvMissionNodelet::onTargets, this);
    guidance_sub_ = nh.subscribe("guidance/status", 10, &AuvMissionNodelet::onGuidance, this);
    odom_sub_ = nh.subscribe("odom", 10, &AuvMissionNodelet::onOdom, this);
    safety_sub_ = nh.subscribe("safety/state", 10, &AuvMissionNodelet::onSafety, this);
    usv_sub_ = nh.subscribe("/usv/mission/status", 10, &AuvMissionNodelet::onUsvStatus, this);  // relayed
    gps_sub_ = nh.subscribe("/auv/gps/fix", 10, &AuvMissionNodelet::onGps, this);  // at the surface (Girona500)
    nav_status_sub_ = nh.subscribe("navigation/status", 1, &AuvMissionNodelet::onNavStatus, this);  // latched
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("auv_mission");
    updater_->add("mission", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, mission::toString(mission_->phase()));
      ros_util::addCounters(s, mission_->counters(), {"detection_not_finite", "target_resent"});
    });
    timer_ = nh.createTimer(ros::Duration(0.5), &AuvMissionNodelet::onTimer, this);
  }

  void onTimer(const ros::TimerEvent&) {
    const ros::Time now = ros::Time::now();
    if (now.isZero()) return;  // simulated time not running yet
    mission_->tick(now.toSec());
    publishOutputs();
    publishStatus();
    updater_->update();
  }

  void onTargets(const TargetArray::ConstPtr& msg) {
    for (const auto& t : msg->targets)
      if (mission_->onDetection({t.origin.x, t.origin.y, t.origin.z}, msg->header.stamp.toSec())) break;
    publishOutputs();
  }

  void onGuidance(const GuidanceStatus::ConstPtr& s) {
    mission_->onGuidance(static_cast<guidance::Mode>(s->mode), s->header.stamp.toSec());
    publishOutputs();
  }

  void onOdom(const nav_msgs::Odometry::ConstPtr& o) {
    const VehicleState s = ros_util::stateFromOdom(*o);
    mission_->onPose(s.position, s.yaw, o->header.stamp.toSec());
  }

  void onUsvStatus(const MissionStatus::ConstPtr& m) {
    const auto phase = mission::usvPhaseFromString(m->phase);
    if (!phase) {
      NODELET_WARN_THROTTLE(10.0, "USV status with an unknown phase '%s' ignored", m->phase.c_str());
      return;
    }
    mission_->onUsvStatus(*phase, {m->position.x, m->position.y}, {m->hold_point.x, m->hold_point.y},
                          ros::Time::now().toSec());
    publishOutputs();
  }

  // Only that a fix came: the navigation places and fuses it (and counts the ones it refuses).
  void onGps(const sensor_msgs::NavSatFix::ConstPtr& f) {
    if (f->status.status >= sensor_msgs::NavSatStatus::STATUS_FIX && std::isfinite(f->latitude) &&
        std::isfinite(f->longitude))
      mission_->onSurfaceFix(f->header.stamp.isZero() ? ros::Time::now().toSec() : f->header.stamp.toSec());
  }

  void onNavStatus(const std_msgs::String::ConstPtr& m) {
    mission_->onFixLost(m->data == ros_util::nav_status::kFixLost);
  }

  void onSafety(const SafetyState::ConstPtr& s) {
    if (!s->manual && s->action >= SafetyState::ACTION_SURFACE) {
      mission_->onSafetySurface(ros::Time::now().toSec());
      publishOutputs();
    }
  }

  void publishOutputs() {
    const auto path = mission_->takePath();
    const auto phase = mission_->phase();
    if (path) {
      path_pub_.publish(mission_ros::toPath(*path, ros::Time::now()));
      if (phase == mission::AuvPhase::Coverage) NODELET_INFO("coverage started: %zu waypoints", path->size());
    }
    const bool changed = phase != logged_;
    if (changed) {  // each phase once (the ascent sends a path every tick)
      NODELET_INFO("%s: %s", mission::toString(phase), mission_->detail().c_str());
      logged_ = phase;
    }
    if (const auto p = mission_->takeTarget()) {
      Target t;
      t.header.stamp = ros::Time::now();
      t.header.frame_id = "map_ned";
      t.source = Target::SOURCE_SONAR;
      t.origin.x = t.centroid.x = t.nearest.x = p->x();
      t.origin.y = t.centroid.y = t.nearest.y = p->y();
      t.origin.z = t.centroid.z = t.nearest.z = p->z();
      t.confidence = 1.0f;
      const geo::LatLonAlt ll = frame_->toGeodetic(*p);
      t.latitude = ll.lat_deg;
      t.longitude = ll.lon_deg;
      t.depth = p->z();
      target_pub_.publish(t);
      NODELET_INFO("%s (%.6f N %.6f E)", mission_->detail().c_str(), ll.lat_deg, ll.lon_deg);
    }
    if (changed) publishStatus();
  }

  void publishStatus() {
    const auto ph = mission_->phase();
    status_pub_.publish(mission_ros::status("auv", mission::toString(ph), mission_->detail(), mission_->finished(),
                                            ph == mission::AuvPhase::Recovered, mission_ros::kNaN,
                                            mission_->onStationSince(), position(), mission_->holdPoint(),
                                            mission_->stationary()));
  }

  Eigen::Vector3d position() const {  // NaN before the first estimate
    const auto& p = mission_->pose();
    return p ? *p : Eigen::Vector3d::Constant(mission_ros::kNaN);
  }

  std::unique_ptr<mission::AuvMission> mission_;
  std::unique_ptr<geo::LocalNed> frame_;
  mission::AuvPhase logged_ = mission::AuvPhase::Idle;
  ros::Publisher path_pub_, target_pub_, status_pub_;
  ros::Subscriber targets_sub_, guidance_sub_, odom_sub_, safety_sub_, usv_sub_, gps_sub_, nav_status_sub_;
  ros::Timer timer_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::AuvMissionNodelet, nodelet::Nodelet)
