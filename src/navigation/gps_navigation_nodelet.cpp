// GpsNavigation: /usv_gps + /usv_heading (+ /usv/gps/velocity when the receiver reports velocity) -> /usv/odom and TF map -> usv/base_link (geo::LocalNed), the USV's
// navigation in simulation and on hardware alike (the GPS-compass is the USV's position and heading source).
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/NavSatFix.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>

#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/navigation/gps_navigator.h"
#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/site.h"

namespace offshore_gnc {

class GpsNavigationNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    geo::LatLonAlt o;
    navigation::GpsNavigatorConfig cfg;
    try {
      o = ros_util::readOrigin();
      ros_util::readParams(p, navigation::GpsNavigatorConfig::table(), cfg);
      navigation::GpsNavigationParams np;
      ros_util::readParams(p, navigation::GpsNavigationParams::table(), np);
      use_rate_of_turn_ = np.use_rate_of_turn;
      base_frame_ = np.base_frame;
      world_frame_ = np.world_frame;
      nav_ = std::make_unique<navigation::GpsNavigator>(o, cfg);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    odom_pub_ = nh.advertise<nav_msgs::Odometry>("/usv/odom", 10);
    heading_sub_ = nh.subscribe("/usv_heading", 10, &GpsNavigationNodelet::onHeading, this);
    gps_sub_ = nh.subscribe("/usv_gps", 10, &GpsNavigationNodelet::onFix, this);
    vel_sub_ = nh.subscribe("/usv/gps/velocity", 10, &GpsNavigationNodelet::onVelocity, this);
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("gps_navigation");
    updater_->add("navigation", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
      std::lock_guard<std::mutex> l(mutex_);
      ros_util::addCounters(s, nav_->counters(), {"bad_fix", "bad_heading", "bad_velocity", "fix_without_heading", "stale_fix"});
    });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->force_update(); });
  }

  void onHeading(const geometry_msgs::QuaternionStamped::ConstPtr& m) {
    const auto& q = m->quaternion;
    double yaw_enu = NAN;
    if (std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w) &&
        q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w > 1e-6) {
      double r, p;
      tf2::Matrix3x3(tf2::Quaternion(q.x, q.y, q.z, q.w)).getRPY(r, p, yaw_enu);
    }
    std::lock_guard<std::mutex> l(mutex_);
    if (!nav_->heading(m->header.stamp.toSec(), geo::enuYawToNed(yaw_enu)))
      NODELET_ERROR_THROTTLE(1.0, "rejected /usv_heading: not a finite, non-zero quaternion");
  }

  // ENU linear velocity over ground, angular.z counter-clockwise (the CAN gateway's convention)
  void onVelocity(const geometry_msgs::TwistStamped::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    const double rate = use_rate_of_turn_ ? -m->twist.angular.z : NAN;
    if (!nav_->velocity(m->header.stamp.toSec(), {m->twist.linear.y, m->twist.linear.x}, rate))
      NODELET_ERROR_THROTTLE(1.0, "rejected /usv/gps/velocity: not finite");
  }

  void onFix(const sensor_msgs::NavSatFix::ConstPtr& m) {
    std::optional<VehicleState> s;
    {
      std::lock_guard<std::mutex> l(mutex_);
      if (m->status.status < sensor_msgs::NavSatStatus::STATUS_FIX) {
        NODELET_WARN_THROTTLE(5.0, "GPS reports no fix");
        return;
      }
      s = nav_->fix(m->header.stamp.toSec(), {m->latitude, m->longitude, m->altitude});
    }
    if (!s) {
      NODELET_WARN_THROTTLE(1.0, "unusable /usv_gps fix (NaN, stale, or no heading within the timeout)");
      return;
    }
    auto o = ros_util::toOdometry(*s, world_frame_, base_frame_);
    o.header.stamp = m->header.stamp;
    const double v = m->position_covariance_type != sensor_msgs::NavSatFix::COVARIANCE_TYPE_UNKNOWN
                         ? m->position_covariance[0]
                         : 1.0;
    o.pose.covariance[0] = o.pose.covariance[7] = v;
    odom_pub_.publish(o);
    tf_.sendTransform(ros_util::toTransform(o));
  }

  std::mutex mutex_;
  std::unique_ptr<navigation::GpsNavigator> nav_;
  std::string base_frame_, world_frame_;
  bool use_rate_of_turn_ = true;
  ros::Publisher odom_pub_;
  ros::Subscriber gps_sub_, heading_sub_, vel_sub_;
  tf2_ros::TransformBroadcaster tf_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diag_timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::GpsNavigationNodelet, nodelet::Nodelet)
