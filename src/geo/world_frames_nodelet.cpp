// WorldFrames: publishes the static map (ENU) -> map_ned (NED) transform and the local frames' geodetic
// origin (the site's, /site/origin: ros/site.h), so that every node and rviz agree on one origin; reports the
// origin in its map grid (UTM/UPS of its own zone; ETRS-TM35FIN too where ~national_grid asks for it and applies).
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/TransformStamped.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/NavSatFix.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <memory>
#include <vector>

#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/site.h"

namespace offshore_gnc {

class WorldFramesNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    geo::LatLonAlt o;
    std::vector<geo::GridPoint> grids;  // the origin's UTM/UPS zone, then the national grid when asked for
    try {
      o = ros_util::readOrigin();
      geo::WorldFramesParams wp;
      ros_util::readParams(p, geo::WorldFramesParams::table(), wp);
      world_frame_ = wp.world_frame;
      ned_frame_ = wp.ned_frame;
      grids.push_back(geo::toUtmUps(o));
      if (wp.national_grid == "etrs-tm35fin") grids.push_back(geo::toTm35fin(o));
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    frame_ = std::make_unique<geo::LocalNed>(o);

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
    updater_->add("origin", [o, grids](diagnostic_updater::DiagnosticStatusWrapper& s) {
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, "origin set");
      s.add("latitude_deg", o.lat_deg);
      s.add("longitude_deg", o.lon_deg);
      s.add("altitude_m", o.alt_m);
      s.add("grid", geo::gridName(grids[0]));
      s.add("grid_easting_m", grids[0].easting_m);
      s.add("grid_northing_m", grids[0].northing_m);
      if (grids.size() > 1) {
        s.add("tm35fin_easting_m", grids[1].easting_m);
        s.add("tm35fin_northing_m", grids[1].northing_m);
      }
    });
    timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->force_update(); });
    NODELET_INFO("local origin %.6f N %.6f E (%s %.1f E %.1f N), %s -> %s", o.lat_deg, o.lon_deg,
                 geo::gridName(grids[0]).c_str(), grids[0].easting_m, grids[0].northing_m, world_frame_.c_str(),
                 ned_frame_.c_str());
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
