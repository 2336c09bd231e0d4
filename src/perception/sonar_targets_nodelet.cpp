// SonarTargets: SonarBeam (auv/sonar) -> per sweep TargetArray (/auv/sonar/targets), the sweep as a
// PointCloud2 (/auv/sonar/sweep), a Cartesian sonar image (/auv/sonar/image) and markers. Each beam is
// positioned with the tf2 pose at its own stamp. Thin wrapper over SonarTargetExtractor and SonarImage. The only
// nodelet that assembles sweeps: WallDetection takes its sweep cloud.
#include <boost/make_shared.hpp>
#include <cv_bridge/cv_bridge.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/image_encodings.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_ros/transform_listener.h>

#include <atomic>
#include <memory>

#include "offshore_gnc/TargetArray.h"
#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/perception/sonar_image.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/markers.h"
#include "ros_perception.h"

namespace offshore_gnc {

class SonarTargetsNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    ros_util::ParamReader p(pnh);
    try {
      sonar_.readParams(p);
      perception::SonarImageParams ip;
      ros_util::readParams(p, perception::SonarImageParams::table(), ip);
      image_ = std::make_unique<perception::SonarImage>(ip.image_range, ip.image_radius_px);
      image_every_ = ip.image_every_beams;
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    sonar_.connect(nh);
    targets_pub_ = nh.advertise<offshore_gnc::TargetArray>("sonar/targets", 5);
    sweep_pub_ = nh.advertise<sensor_msgs::PointCloud2>("sonar/sweep", 2);
    image_pub_ = nh.advertise<sensor_msgs::Image>("sonar/image", 2);
    markers_.advertise(nh, "markers", "sonar_targets");
    sub_ = nh.subscribe("sonar/beam", 200, &SonarTargetsNodelet::onBeam, this);
    diag_ = std::make_unique<perception_ros::Diagnostics>(
        nh, pnh, getName(), sonar_.extractor->counters(), [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
          s.add("beams", beams_.load());
          s.add("sweeps", sweeps_.load());
          s.add("last_targets", last_targets_.load());
        });
  }

  void onBeam(const offshore_gnc::SonarBeam::ConstPtr& msg) {
    ++beams_;
    const auto fed = sonar_.feed(*msg, getName());
    if (fed == perception_ros::BeamFed::Rejected) return;
    // The image is in the sonar frame: it needs no pose.
    image_->addBeam(msg->bearing, msg->beam_width, msg->range_resolution, msg->range_offset, msg->intensities.data(),
                    msg->intensities.size());
    if (beams_ % static_cast<std::uint64_t>(image_every_) == 0) publishImage(msg->header);
    if (sonar_.extractor->sweepReady()) publishSweep(sonar_.extractor->takeSweep());
  }

  void publishImage(const std_msgs::Header& beam_header) {
    cv_bridge::CvImage img(beam_header, sensor_msgs::image_encodings::MONO8, image_->render());
    image_pub_.publish(img.toImageMsg());
  }

  void publishSweep(const perception::SonarSweep& s) {
    ++sweeps_;
    std_msgs::Header h;
    h.stamp = ros::Time(s.end_stamp);
    h.frame_id = sonar_.target_frame;
    offshore_gnc::TargetArray out;
    out.header = h;
    for (const auto& st : s.targets) {
      auto t = perception_ros::toTarget(st.geometry, Eigen::Isometry3d::Identity(), offshore_gnc::Target::SOURCE_SONAR,
                                        st.geometry.bearing);
      t.header.frame_id = sonar_.target_frame;
      t.header.stamp = ros::Time(st.stamp);
      t.depth = st.geometry.origin.z();  // map_ned: z is down
      out.targets.push_back(t);
    }
    last_targets_ = out.targets.size();
    targets_pub_.publish(out);
    markers_.publish(perception_ros::targetMarkers(out.targets, 1.0f, 0.0f, 0.0f), h);

    // Published as a shared pointer: WallDetection in the same manager gets it without a copy or serialisation.
    const auto msg = boost::make_shared<sensor_msgs::PointCloud2>();
    sensor_msgs::PointCloud2& cloud = *msg;
    cloud.header = h;
    sensor_msgs::PointCloud2Modifier mod(cloud);
    mod.setPointCloud2Fields(4, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32, "z",
                             1, sensor_msgs::PointField::FLOAT32, "intensity", 1, sensor_msgs::PointField::FLOAT32);
    mod.resize(s.detections.size());
    if (!s.detections.empty()) {  // the iterators read data.front(): undefined on an empty sweep
      sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z"), in(cloud, "intensity");
      for (const auto& d : s.detections) {
        *x = float(d.point.x()); *y = float(d.point.y()); *z = float(d.point.z()); *in = float(d.intensity);
        ++x; ++y; ++z; ++in;
      }
    }
    sweep_pub_.publish(msg);
  }

  int image_every_ = 20;
  perception_ros::SonarFeed sonar_;
  std::unique_ptr<perception::SonarImage> image_;
  ros::Publisher targets_pub_, sweep_pub_, image_pub_;
  ros_util::NamespaceMarkers markers_;
  ros::Subscriber sub_;
  std::unique_ptr<perception_ros::Diagnostics> diag_;
  std::atomic<std::uint64_t> beams_{0}, sweeps_{0}, last_targets_{0};
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::SonarTargetsNodelet, nodelet::Nodelet)
