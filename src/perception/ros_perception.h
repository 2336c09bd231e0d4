#pragma once
// ROS edge of the perception module, shared by its three nodelets: message -> core views (zero-copy),
// tf2 pose at a stamp, core targets -> offshore_gnc/Target, markers, and the diagnostics heartbeat.
#include <Eigen/Geometry>
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/Point.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <functional>
#include <memory>
#include <string>

#include "offshore_gnc/SonarBeam.h"
#include "offshore_gnc/Target.h"
#include "offshore_gnc/Track.h"
#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/perception/lidar_targets.h"
#include "offshore_gnc/perception/sonar_targets.h"
#include "offshore_gnc/perception/target_tracker.h"
#include "offshore_gnc/ros/params.h"

namespace offshore_gnc {
namespace perception_ros {

// Field layout of a PointCloud2 (x, y, z, optional ring): a LiDAR frame, or a sonar sweep as SonarTargets
// publishes it; the buffer is referenced, not copied.
perception::CloudView cloudView(const sensor_msgs::PointCloud2& m);
perception::SonarBeamView beamView(const offshore_gnc::SonarBeam& m);

// Pose of `source` in `target` at `stamp`, waiting up to `timeout`. False (with the reason) when tf2 has no
// transform for that time: callers drop the data, they never fall back to an older pose.
bool lookupPose(const tf2_ros::Buffer& tf, const std::string& target, const std::string& source,
                const ros::Time& stamp, double timeout, Eigen::Isometry3d& pose, std::string& error);

// SonarTargets' beam input: the sonar parameters, a tf listener for the pose of every beam, and the extractor
// that assembles the beams into sweeps (once: WallDetection takes the sweeps SonarTargets publishes).
enum class BeamFed { Rejected, NoPose, Added };
struct SonarFeed {
  void readParams(const ros_util::ParamReader& p);  // SonarConfig + target_frame, tf_timeout; throws ConfigError
  void connect(ros::NodeHandle& nh);                 // tf buffer and listener
  // Validates one beam, looks up the sonar pose at its stamp and feeds it to the extractor; logs (throttled,
  // prefixed with `who`) and counts what it rejects or cannot position.
  BeamFed feed(const offshore_gnc::SonarBeam& msg, const std::string& who);
  std::unique_ptr<perception::SonarTargetExtractor> extractor;
  std::unique_ptr<tf2_ros::Buffer> tf;
  std::unique_ptr<tf2_ros::TransformListener> listener;
  std::string target_frame = "map_ned";
  double tf_timeout = 0.1;
};

geometry_msgs::Point toPoint(const Eigen::Vector3d& v);

// Target message from core geometry given in the sensor frame (or already in the target frame with
// `to_target` = identity). Geodetic fields NaN: perception has no geodetic reference.
offshore_gnc::Target toTarget(const perception::TargetGeometry& g, const Eigen::Isometry3d& to_target,
                              std::uint8_t source, double bearing_cw);

// One cylinder per target at its origin, sized by its extent (for ros_util::NamespaceMarkers::publish).
std::vector<visualization_msgs::Marker> targetMarkers(const std::vector<offshore_gnc::Target>& targets, float r,
                                                    float g, float b);

// A track as the message carries it, its age and time unseen at `now` [s].
offshore_gnc::Track toTrack(const perception::Track& tr, double now);

// Per confirmed track: its id and speed as text above it, and an arrow of its velocity (5 s of travel) when it moves.
std::vector<visualization_msgs::Marker> trackMarkers(const std::vector<perception::Track>& tracks);

// diagnostic_updater with the core's counters, updated once a second; `extra` adds module figures.
class Diagnostics {
 public:
  Diagnostics(ros::NodeHandle& nh, ros::NodeHandle& pnh, const std::string& name, const Counters& counters,
              std::function<void(diagnostic_updater::DiagnosticStatusWrapper&)> extra);

 private:
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer timer_;
};

}  // namespace perception_ros
}  // namespace offshore_gnc
