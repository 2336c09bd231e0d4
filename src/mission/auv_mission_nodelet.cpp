// AUV mission: publishes the coverage path, turns sonar targets into the first confirmed detection, then stops
// the vehicle (empty path) and publishes /target in map_ned with its WGS84 position for the USV (relayed).
#include <diagnostic_updater/diagnostic_updater.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/GuidanceStatus.h>
#include <offshore_gnc/Target.h>
#include <offshore_gnc/TargetArray.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/mission/mission.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "ros_mission.h"

namespace offshore_gnc {

class AuvMissionNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    ros_util::ParamReader vehicle(nh);
    mission::AuvMissionParams mp;
    geo::LatLonAlt origin;
    try {
      mp.confirm_detections = p.integer("confirm_detections", mp.confirm_detections, 1, 100);
      mp.confirm_radius = p.number("confirm_radius", mp.confirm_radius, 0.1, 50);
      mp.detection_max_age = p.number("detection_max_age", mp.detection_max_age, 1, 1e5);
      // the coverage area comes from the mission config (~coverage) or, in simulation, the scenario file
      // loaded into ~scenario (its auv/coverage section)
      const std::string c =
          getPrivateNodeHandle().hasParam("scenario/auv/coverage") ? "scenario/auv/coverage/" : "coverage/";
      area_.north_min = p.requiredNumber(c + "north_min", -1e4, 1e4);
      area_.north_max = p.requiredNumber(c + "north_max", -1e4, 1e4);
      area_.east_min = p.requiredNumber(c + "east_min", -1e4, 1e4);
      area_.east_max = p.requiredNumber(c + "east_max", -1e4, 1e4);
      area_.depth = p.requiredNumber(c + "depth", 0, 1000);
      area_.spacing = p.number(c + "spacing", 5.0, 0.5, 1000);
      start_delay_ = p.number("start_delay", 2.0, 0, 3600);
      origin.lat_deg = vehicle.number("origin/latitude", geo::kPyhajarviOrigin.lat_deg, -90, 90);
      origin.lon_deg = vehicle.number("origin/longitude", geo::kPyhajarviOrigin.lon_deg, -180, 180);
      mission_ = std::make_unique<mission::AuvMission>(mp);
      if (mission::coveragePath(area_).empty()) throw ConfigError("parameter '~coverage' is an empty rectangle");
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
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("auv_mission");
    updater_->add("mission", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, mission::toString(mission_->phase()));
      ros_util::addCounters(s, mission_->counters(), {"detection_not_finite"});
    });
    timer_ = nh.createTimer(ros::Duration(0.5), &AuvMissionNodelet::onTimer, this);
  }

  void onTimer(const ros::TimerEvent&) {
    const ros::Time now = ros::Time::now();
    if (now.isZero()) return;  // simulated time not running yet
    if (first_.isZero()) first_ = now;
    if (mission_->phase() == mission::AuvPhase::Idle && (now - first_).toSec() >= start_delay_) {
      mission_->start(now.toSec());
      const auto pts = mission::coveragePath(area_);
      path_pub_.publish(mission_ros::toPath(pts, now));
      NODELET_INFO("coverage started: %zu waypoints at %.1f m depth", pts.size(), area_.depth);
    }
    publishStatus();
    updater_->update();
  }

  void onTargets(const TargetArray::ConstPtr& msg) {
    if (mission_->phase() != mission::AuvPhase::Coverage) return;
    for (const auto& t : msg->targets) {
      const Eigen::Vector3d p(t.origin.x, t.origin.y, t.origin.z);
      if (mission_->onDetection(p, msg->header.stamp.toSec())) {
        found();
        return;
      }
    }
  }

  void onGuidance(const GuidanceStatus::ConstPtr& s) {
    // end of the coverage path: guidance switches from path following to holding at the last waypoint
    if (s->mode == GuidanceStatus::MODE_FOLLOW_PATH) following_ = true;
    if (following_ && s->mode == GuidanceStatus::MODE_STATION_KEEPING && mission_->phase() == mission::AuvPhase::Coverage) {
      mission_->onCoverageFinished(s->header.stamp.toSec());
      path_pub_.publish(mission_ros::toPath({}, ros::Time::now()));  // stop
      NODELET_WARN("%s", mission_->detail().c_str());
      publishStatus();
    }
  }

  void found() {
    const Eigen::Vector3d p = *mission_->target();
    path_pub_.publish(mission_ros::toPath({}, ros::Time::now()));  // stop: thrusters off
    Target t;
    t.header.stamp = ros::Time::now();
    t.header.frame_id = "map_ned";
    t.source = Target::SOURCE_SONAR;
    t.origin.x = t.centroid.x = t.nearest.x = p.x();
    t.origin.y = t.centroid.y = t.nearest.y = p.y();
    t.origin.z = t.centroid.z = t.nearest.z = p.z();
    t.confidence = 1.0f;
    const geo::LatLonAlt ll = frame_->toGeodetic(p);
    t.latitude = ll.lat_deg;
    t.longitude = ll.lon_deg;
    t.depth = p.z();
    target_pub_.publish(t);
    NODELET_INFO("%s (%.6f N %.6f E)", mission_->detail().c_str(), ll.lat_deg, ll.lon_deg);
    publishStatus();
  }

  void publishStatus() {
    const auto ph = mission_->phase();
    status_pub_.publish(mission_ros::status("auv", mission::toString(ph), mission_->detail(), mission_->finished(),
                                            ph == mission::AuvPhase::TargetFound));
  }

  mission::CoverageArea area_;
  double start_delay_ = 2.0;
  bool following_ = false;
  ros::Time first_;
  std::unique_ptr<mission::AuvMission> mission_;
  std::unique_ptr<geo::LocalNed> frame_;
  ros::Publisher path_pub_, target_pub_, status_pub_;
  ros::Subscriber targets_sub_, guidance_sub_;
  ros::Timer timer_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::AuvMissionNodelet, nodelet::Nodelet)
