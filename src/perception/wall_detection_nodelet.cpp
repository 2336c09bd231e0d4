// WallDetection: the sonar targets' sweep cloud (/auv/sonar/sweep, one point per detection in acquisition order)
// -> split-and-merge walls -> nav_msgs/Path of two waypoints at a set distance from the chosen wall
// (/auv/sonar/wall_path, in the sweep's frame) + markers (Algorithm 1 of Publication II per sweep). The beams
// are positioned and assembled into sweeps once, by SonarTargets; this nodelet never sees them.
#include <nav_msgs/Path.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/transform_listener.h>

#include <atomic>
#include <memory>

#include "offshore_gnc/perception/sensor_frame.h"
#include "offshore_gnc/perception/wall_detection.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/markers.h"
#include "ros_perception.h"

namespace offshore_gnc {

class WallDetectionNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    ros_util::ParamReader p(pnh);
    try {
      perception::WallConfig cfg;
      ros_util::readParams(p, perception::WallConfig::table(), cfg);
      detector_ = std::make_unique<perception::WallDetector>(cfg);
      ros_util::readParams(p, perception::SensorFrameParams::table(), frame_);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    tf_ = std::make_unique<tf2_ros::Buffer>();
    listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_, nh);
    path_pub_ = nh.advertise<nav_msgs::Path>("sonar/wall_path", 2, true);
    markers_.advertise(nh, "markers", "sonar_walls");
    sub_ = nh.subscribe("sonar/sweep", 5, &WallDetectionNodelet::onSweep, this);
    diag_ = std::make_unique<perception_ros::Diagnostics>(
        nh, pnh, getName(), detector_->counters(), [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
          s.add("sweeps", sweeps_.load());
          s.add("last_walls", last_walls_.load());
          s.add("paths", paths_.load());
        });
  }

  void onSweep(const sensor_msgs::PointCloud2::ConstPtr& msg) {
    ++sweeps_;
    // The path goes where the sweep is: a sweep in another frame than this nodelet's is a configuration error
    // (the two nodelets read the same file), named rather than planned in a frame guidance does not expect.
    if (msg->header.frame_id != frame_.target_frame) {
      detector_->counters().increment("wrong_frame");
      NODELET_ERROR_THROTTLE(5.0, "sweep in frame '%s', expected '%s' (target_frame): dropped",
                             msg->header.frame_id.c_str(), frame_.target_frame.c_str());
      return;
    }
    const perception::SweepWalls r = detector_->detect(perception_ros::cloudView(*msg));
    if (r.error != perception::CloudError::None) {
      NODELET_ERROR_THROTTLE(5.0, "bad sweep cloud dropped: %s (counters in diagnostics)", r.message.c_str());
      return;
    }
    if (r.non_finite)
      NODELET_ERROR_THROTTLE(5.0, "%zu non-finite points dropped from a sweep of %zu (counters in diagnostics)",
                             r.non_finite, r.non_finite + r.points.size());
    const auto& walls = r.walls;
    last_walls_ = walls.size();
    const ros::Time stamp = msg->header.stamp;  // the sweep's last beam
    Eigen::Isometry3d vehicle;
    std::string err;
    if (!perception_ros::lookupPose(*tf_, frame_.target_frame, detector_->config().base_frame, stamp,
                                    frame_.tf_timeout, vehicle, err)) {
      detector_->counters().increment("no_transform");
      NODELET_WARN_THROTTLE(5.0, "no vehicle pose for the wall path: %s", err.c_str());
      return;
    }
    // Heading: the body's forward axis expressed in the target frame (works for ENU or NED body conventions).
    const Eigen::Vector3d fwd = vehicle.linear() * Eigen::Vector3d::UnitX();
    const double yaw = std::atan2(fwd.y(), fwd.x());
    const auto plan = detector_->plan(walls, vehicle.translation().head<2>(), yaw);
    std_msgs::Header h;
    h.stamp = stamp;
    h.frame_id = frame_.target_frame;
    publishMarkers(walls, plan, h);
    if (!plan.ok) {
      NODELET_WARN_THROTTLE(10.0, "no wall of at least %.1f m in the last sweep (%zu points)",
                            detector_->config().min_length, r.points.size());
      return;
    }
    nav_msgs::Path path;
    path.header = h;
    const Eigen::Vector2d dir = plan.wp2 - plan.wp1;
    const double path_yaw = std::atan2(dir.y(), dir.x());  // about the frame's z (down in map_ned)
    for (const Eigen::Vector2d& w : {plan.wp1, plan.wp2}) {
      geometry_msgs::PoseStamped ps;
      ps.header = h;
      ps.pose.position = perception_ros::toPoint(Eigen::Vector3d(w.x(), w.y(), vehicle.translation().z()));
      ps.pose.orientation.z = std::sin(path_yaw / 2);
      ps.pose.orientation.w = std::cos(path_yaw / 2);
      path.poses.push_back(ps);
    }
    ++paths_;
    path_pub_.publish(path);
  }

  void publishMarkers(const std::vector<perception::WallSegment>& walls, const perception::WallPath& plan,
                      const std_msgs::Header& h) {
    std::vector<visualization_msgs::Marker> a;
    visualization_msgs::Marker lines;
    lines.type = visualization_msgs::Marker::LINE_LIST;
    lines.scale.x = 0.15;
    lines.color.g = 1.0f;
    lines.color.b = 1.0f;
    lines.color.a = 1.0f;
    for (const auto& w : walls) {
      lines.points.push_back(perception_ros::toPoint(Eigen::Vector3d(w.a.x(), w.a.y(), 0)));
      lines.points.push_back(perception_ros::toPoint(Eigen::Vector3d(w.b.x(), w.b.y(), 0)));
    }
    if (!lines.points.empty()) a.push_back(lines);
    if (plan.ok) {
      visualization_msgs::Marker wp = lines;
      wp.type = visualization_msgs::Marker::SPHERE_LIST;
      wp.scale.x = wp.scale.y = wp.scale.z = 0.5;
      wp.color.r = 1.0f; wp.color.g = 1.0f; wp.color.b = 0.0f;
      wp.points = {perception_ros::toPoint(Eigen::Vector3d(plan.wp1.x(), plan.wp1.y(), 0)),
                   perception_ros::toPoint(Eigen::Vector3d(plan.wp2.x(), plan.wp2.y(), 0))};
      a.push_back(wp);
    }
    markers_.publish(std::move(a), h);
  }

  std::unique_ptr<perception::WallDetector> detector_;
  perception::SensorFrameParams frame_;
  std::unique_ptr<tf2_ros::Buffer> tf_;
  std::unique_ptr<tf2_ros::TransformListener> listener_;
  ros::Publisher path_pub_;
  ros_util::NamespaceMarkers markers_;
  ros::Subscriber sub_;
  std::unique_ptr<perception_ros::Diagnostics> diag_;
  std::atomic<std::uint64_t> sweeps_{0}, last_walls_{0}, paths_{0};
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::WallDetectionNodelet, nodelet::Nodelet)
