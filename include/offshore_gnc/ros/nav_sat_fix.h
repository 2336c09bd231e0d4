#pragma once
// A simulated receiver's fix as sensor_msgs/NavSatFix, for the simulators' GPS topics (the USV's GPS-compass, the
// Girona500's GPS at the surface): the horizontal sigma per axis, twice it vertically (a GPS's usual ratio).
#include <ros/time.h>
#include <sensor_msgs/NavSatFix.h>

#include <cstdint>
#include <string>

#include "offshore_gnc/geo/geo.h"

namespace offshore_gnc {
namespace ros_util {

inline sensor_msgs::NavSatFix navSatFix(const geo::LatLonAlt& fix, double sigma, const ros::Time& stamp,
                                        const std::string& frame_id, std::int8_t status) {
  sensor_msgs::NavSatFix f;
  f.header.stamp = stamp;
  f.header.frame_id = frame_id;
  f.status.status = status;
  f.status.service = sensor_msgs::NavSatStatus::SERVICE_GPS;
  f.latitude = fix.lat_deg;
  f.longitude = fix.lon_deg;
  f.altitude = fix.alt_m;
  const double var = sigma * sigma;
  f.position_covariance = {var, 0, 0, 0, var, 0, 0, 0, 4 * var};
  f.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
  return f;
}

}  // namespace ros_util
}  // namespace offshore_gnc
