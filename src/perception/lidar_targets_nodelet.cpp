// LidarTargets: PointCloud2 (usv/lidar) -> TargetArray in map_ned (/usv/obstacles), the targets followed over frames
// as tracks (/usv/tracks, perception::TargetTracker) + markers. Thin wrapper over perception::LidarTargetExtractor; reads the cloud's buffer in place (zero-copy in a manager). Each cloud is
// levelled with the sensor's roll and pitch from its IMU (`lidar/imu`, sensor_msgs/Imu: the MRS1000's built-in
// IMU) nearest its stamp; without one (none within ~imu_timeout) the cloud is taken as level and counted. The
// targets are then placed with the TF of the cloud's frame, whose base_link pose has no roll or pitch (the USV's
// navigation is a GPS-compass): the levelled points are what it expects.
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/transform_listener.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <deque>
#include <memory>
#include <mutex>
#include <vector>

#include "offshore_gnc/TargetArray.h"
#include "offshore_gnc/TrackArray.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/diagnostics.h"
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
      perception::LidarImuParams imu;
      ros_util::readParams(p, perception::LidarImuParams::table(), imu);
      imu_topic_ = imu.imu_topic;
      imu_timeout_ = imu.imu_timeout;
      extractor_ = std::make_unique<perception::LidarTargetExtractor>(cfg);
      perception::TrackerParams tp;
      ros_util::readParams(p, perception::TrackerParams::table(), tp, "tracker/");
      tracker_ = std::make_unique<perception::TargetTracker>(tp);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    tf_ = std::make_unique<tf2_ros::Buffer>();
    listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_, nh);
    targets_pub_ = nh.advertise<offshore_gnc::TargetArray>("obstacles", 5);
    tracks_pub_ = nh.advertise<offshore_gnc::TrackArray>("tracks", 5);
    markers_.advertise(nh, "markers", "lidar_targets");
    track_markers_.advertise(nh, "markers", "lidar_tracks");
    sub_ = nh.subscribe("lidar/points", 2, &LidarTargetsNodelet::onCloud, this);
    if (!imu_topic_.empty()) imu_sub_ = nh.subscribe(imu_topic_, 20, &LidarTargetsNodelet::onImu, this);
    diag_ = std::make_unique<perception_ros::Diagnostics>(
        nh, pnh, getName(), extractor_->counters(), [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
          s.add("frames", frames_.load());
          s.add("last_targets", last_targets_.load());
          s.add("last_processing_ms", last_ms_.load());
          s.add("confirmed_tracks", confirmed_tracks_.load());
          ros_util::addCounters(s, tracker_->counters(), {"non_finite_detection", "non_finite_time", "time_backwards"});
        });
    NODELET_INFO("LiDAR targets: gap %.2f m, range [%.1f, %.1f] m, z [%.1f, %.1f] m -> %s", cfg.gap, cfg.min_range,
                 cfg.max_range, cfg.min_z, cfg.max_z, target_frame_.c_str());
  }

  // Roll and pitch (REP-103) of the sensor, kept for the last second.
  void onImu(const sensor_msgs::Imu::ConstPtr& m) {
    if (m->orientation_covariance[0] < 0.0) return;  // no orientation in it
    double roll, pitch, yaw;
    tf2::Matrix3x3(tf2::Quaternion(m->orientation.x, m->orientation.y, m->orientation.z, m->orientation.w))
        .getRPY(roll, pitch, yaw);
    std::lock_guard<std::mutex> l(imu_mutex_);
    attitude_.push_back({m->header.stamp.toSec(), roll, pitch});
    while (attitude_.size() > 1 && attitude_.back().t - attitude_.front().t > 1.0) attitude_.pop_front();
  }
  // The levelling rotation of the attitude nearest `t`; identity (and counted) when none is within imu_timeout.
  Eigen::Matrix3d levelAt(double t) {
    std::lock_guard<std::mutex> l(imu_mutex_);
    const Attitude* best = nullptr;
    for (const auto& a : attitude_)
      if (!best || std::abs(a.t - t) < std::abs(best->t - t)) best = &a;
    if (!imu_topic_.empty() && (!best || std::abs(best->t - t) > imu_timeout_)) {
      extractor_->counters().increment("no_attitude");
      return Eigen::Matrix3d::Identity();
    }
    return best ? perception::levelling(best->roll, best->pitch) : Eigen::Matrix3d::Identity();
  }

  void onCloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
    const auto t0 = std::chrono::steady_clock::now();
    ++frames_;
    const perception::CloudView view = perception_ros::cloudView(*msg);
    perception::LidarResult bad;
    if (!extractor_->checkLayout(view, bad)) {
      NODELET_ERROR_THROTTLE(5.0, "rejected cloud (%s): %s", perception::toString(bad.error), bad.message.c_str());
      return;
    }
    Eigen::Isometry3d to_target;
    std::string err;
    if (!perception_ros::lookupPose(*tf_, target_frame_, msg->header.frame_id, msg->header.stamp, tf_timeout_,
                                    to_target, err)) {
      extractor_->counters().increment("no_transform");
      NODELET_WARN_THROTTLE(5.0, "dropping cloud: no transform %s <- %s at %.3f: %s", target_frame_.c_str(),
                            msg->header.frame_id.c_str(), msg->header.stamp.toSec(), err.c_str());
      return;
    }
    const perception::LidarResult r = extractor_->extract(view, levelAt(msg->header.stamp.toSec()));
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
    track(out);
    last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }

  // The frame's targets (their centroids in the target frame) into the tracker, its tracks out.
  void track(const offshore_gnc::TargetArray& targets) {
    std::vector<perception::Detection> d;
    for (const auto& t : targets.targets) {
      perception::Detection x;
      x.position = {t.centroid.x, t.centroid.y};
      x.length = t.length;
      x.width = t.width;
      d.push_back(x);
    }
    const double now = targets.header.stamp.toSec();
    if (!tracker_->update(now, d)) return;
    offshore_gnc::TrackArray out;
    out.header = targets.header;
    std::uint64_t confirmed = 0;
    for (const auto& tr : tracker_->tracks()) {
      out.tracks.push_back(perception_ros::toTrack(tr, now));
      out.tracks.back().header = out.header;
      confirmed += tr.confirmed;
    }
    confirmed_tracks_ = confirmed;
    track_markers_.publish(perception_ros::trackMarkers(tracker_->tracks()), out.header);
    tracks_pub_.publish(out);
  }

  struct Attitude {
    double t, roll, pitch;
  };
  std::string target_frame_, imu_topic_;
  double tf_timeout_ = 0.1, imu_timeout_ = 0.2;
  std::mutex imu_mutex_;
  std::deque<Attitude> attitude_;
  ros::Subscriber imu_sub_;
  std::unique_ptr<perception::LidarTargetExtractor> extractor_;
  std::unique_ptr<perception::TargetTracker> tracker_;
  std::unique_ptr<tf2_ros::Buffer> tf_;
  std::unique_ptr<tf2_ros::TransformListener> listener_;
  ros::Publisher targets_pub_, tracks_pub_;
  ros_util::NamespaceMarkers markers_, track_markers_;
  ros::Subscriber sub_;
  std::unique_ptr<perception_ros::Diagnostics> diag_;
  std::atomic<std::uint64_t> frames_{0}, last_targets_{0}, confirmed_tracks_{0};
  std::atomic<double> last_ms_{0.0};
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::LidarTargetsNodelet, nodelet::Nodelet)
