// LidarTargets: PointCloud2 (usv/lidar) -> TargetArray in map_ned (/usv/obstacles) + markers. Thin wrapper
// over perception::LidarTargetExtractor; reads the cloud's buffer in place (zero-copy in a manager).
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/transform_listener.h>

#include <atomic>
#include <chrono>
#include <memory>

#include "offshore_gnc/TargetArray.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/markers.h"
#include "offshore_gnc/perception/sensor_frame.h"
#include "ros_perception.h"

namespace offshore_gnc {

class LidarTargetsNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    ros_util::ParamReader p(pnh);
    perception::LidarConfig cfg;
    try {
      ros_util::readParams(p, perception::LidarConfig::table(), cfg);
      perception::SensorFrameParams f;
      ros_util::readParams(p, perception::SensorFrameParams::table(), f);
      target_frame_ = f.target_frame;
      tf_timeout_ = f.tf_timeout;
      extractor_ = std::make_unique<perception::LidarTargetExtractor>(cfg);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    tf_ = std::make_unique<tf2_ros::Buffer>();
    listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_, nh);
    targets_pub_ = nh.advertise<offshore_gnc::TargetArray>("obstacles", 5);
    markers_.advertise(nh, "markers", "lidar_targets");
    sub_ = nh.subscribe("lidar/points", 2, &LidarTargetsNodelet::onCloud, this);
    diag_ = std::make_unique<perception_ros::Diagnostics>(
        nh, pnh, getName(), extractor_->counters(), [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
          s.add("frames", frames_.load());
          s.add("last_targets", last_targets_.load());
          s.add("last_processing_ms", last_ms_.load());
        });
    NODELET_INFO("LiDAR targets: gap %.2f m, range [%.1f, %.1f] m, z [%.1f, %.1f] m -> %s", cfg.gap, cfg.min_range,
                 cfg.max_range, cfg.min_z, cfg.max_z, target_frame_.c_str());
  }

  void onCloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
    const auto t0 = std::chrono::steady_clock::now();
    ++frames_;
    Eigen::Isometry3d to_target;
    std::string err;
    if (!perception_ros::lookupPose(*tf_, target_frame_, msg->header.frame_id, msg->header.stamp, tf_timeout_,
                                    to_target, err)) {
      extractor_->counters().increment("no_transform");
      NODELET_WARN_THROTTLE(5.0, "dropping cloud: no transform %s <- %s at %.3f: %s", target_frame_.c_str(),
                            msg->header.frame_id.c_str(), msg->header.stamp.toSec(), err.c_str());
      return;
    }
    const perception::LidarResult r = extractor_->extract(perception_ros::cloudView(*msg));
    if (r.error != perception::CloudError::None) {
      NODELET_ERROR_THROTTLE(5.0, "rejected cloud (%s): %s", perception::toString(r.error), r.message.c_str());
      return;
    }
    offshore_gnc::TargetArray out;
    out.header.stamp = msg->header.stamp;
    out.header.frame_id = target_frame_;
    for (const auto& g : r.targets) {
      // Sensor frame is ROS (x forward, y left): clockwise bearing = -atan2(y, x).
      auto t = perception_ros::toTarget(g, to_target, offshore_gnc::Target::SOURCE_LIDAR, -g.bearing);
      t.header = out.header;
      out.targets.push_back(t);
    }
    last_targets_ = out.targets.size();
    markers_.publish(perception_ros::targetMarkers(out.targets, 1.0f, 0.5f, 0.0f), out.header);
    targets_pub_.publish(out);
    last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }

  std::string target_frame_;
  double tf_timeout_ = 0.1;
  std::unique_ptr<perception::LidarTargetExtractor> extractor_;
  std::unique_ptr<tf2_ros::Buffer> tf_;
  std::unique_ptr<tf2_ros::TransformListener> listener_;
  ros::Publisher targets_pub_;
  ros_util::NamespaceMarkers markers_;
  ros::Subscriber sub_;
  std::unique_ptr<perception_ros::Diagnostics> diag_;
  std::atomic<std::uint64_t> frames_{0}, last_targets_{0};
  std::atomic<double> last_ms_{0.0};
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::LidarTargetsNodelet, nodelet::Nodelet)
