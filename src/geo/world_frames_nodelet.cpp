// WorldFrames: publishes the static map (ENU) -> map_ned (NED) transform and the local frames' geodetic
// origin, so that every node and rviz agree on one origin. Thin wrapper over geo::LocalNed.
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/TransformStamped.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/NavSatFix.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <memory>

#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/ros/params.h"

namespace offshore_gnc {

class WorldFramesNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    geo::LatLonAlt o;
    try {
      o.lat_deg = p.number("origin/latitude", geo::kPyhajarviOrigin.lat_deg, -90, 90);
      o.lon_deg = p.number("origin/longitude", geo::kPyhajarviOrigin.lon_deg, -180, 180);
      o.alt_m = p.number("origin/altitude", 0.0, -1000, 10000);
      world_frame_ = p.text("world_frame", "map");
      ned_frame_ = p.text("ned_frame", "map_ned");
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    frame_ = std::make_unique<geo::LocalNed>(o);
    const geo::Tm35 tm = geo::toTm35fin(o);

    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time(0);  // static: valid at all times, also under simulated /clock
    t.header.frame_id = world_frame_;
    t.child_frame_id = ned_frame_;
    // NED axes in ENU: x_ned = y_enu, y_ned = x_enu, z_ned = -z_enu: 180 deg about (1, 1, 0)/sqrt(2).
    t.transform.rotation.x = M_SQRT1_2;
    t.transform.rotation.y = M_SQRT1_2;
    t.transform.rotation.z = 0.0;
    t.transform.rotation.w = 0.0;
    broadcaster_.sendTransform(t);

    origin_pub_ = nh.advertise<sensor_msgs::NavSatFix>("origin", 1, true);
    sensor_msgs::NavSatFix fix;
    fix.header.frame_id = ned_frame_;
    fix.latitude = o.lat_deg;
    fix.longitude = o.lon_deg;
    fix.altitude = o.alt_m;
    fix.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
    fix.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_UNKNOWN;
    origin_pub_.publish(fix);

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("world_frames");
    updater_->add("origin", [o, tm](diagnostic_updater::DiagnosticStatusWrapper& s) {
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, "origin set");
      s.add("latitude_deg", o.lat_deg);
      s.add("longitude_deg", o.lon_deg);
      s.add("tm35fin_easting_m", tm.easting_m);
      s.add("tm35fin_northing_m", tm.northing_m);
    });
    timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->force_update(); });
    NODELET_INFO("local origin %.6f N %.6f E (TM35FIN %.1f E %.1f N), %s -> %s", o.lat_deg, o.lon_deg,
                 tm.easting_m, tm.northing_m, world_frame_.c_str(), ned_frame_.c_str());
  }

  std::string world_frame_, ned_frame_;
  std::unique_ptr<geo::LocalNed> frame_;
  tf2_ros::StaticTransformBroadcaster broadcaster_;
  ros::Publisher origin_pub_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::WorldFramesNodelet, nodelet::Nodelet)
