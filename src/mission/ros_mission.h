#pragma once
// Shared by the two mission nodelets: message conversions and the status message.
#include <nav_msgs/Path.h>
#include <offshore_gnc/MissionStatus.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

namespace offshore_gnc {
namespace mission_ros {

inline nav_msgs::Path toPath(const std::vector<Eigen::Vector3d>& pts, const ros::Time& stamp) {
  nav_msgs::Path p;
  p.header.stamp = stamp;
  p.header.frame_id = "map_ned";  // guidance works in NED (docs/architecture.md)
  for (const auto& v : pts) {
    geometry_msgs::PoseStamped ps;
    ps.header = p.header;
    ps.pose.position.x = v.x();
    ps.pose.position.y = v.y();
    ps.pose.position.z = v.z();
    ps.pose.orientation.w = 1.0;
    p.poses.push_back(ps);
  }
  return p;
}

// The target as this vehicle knows it (a magenta sphere in map_ned), for rviz: on the USV it is the one the AUV
// sent across, so a user sees where the USV is heading and how it compares with the LiDAR picture.
inline visualization_msgs::MarkerArray targetMarker(double north, double east, double depth, const ros::Time& stamp) {
  visualization_msgs::Marker m;
  m.header.stamp = stamp;
  m.header.frame_id = "map_ned";
  m.ns = "mission_target";
  m.type = visualization_msgs::Marker::SPHERE;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.position.x = north;
  m.pose.position.y = east;
  m.pose.position.z = depth;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = 2.0;
  m.color.r = 1.0f;
  m.color.b = 1.0f;
  m.color.a = 1.0f;
  visualization_msgs::MarkerArray a;
  a.markers.push_back(m);
  return a;
}

inline geometry_msgs::Point point(double north, double east, double down = 0.0) {
  geometry_msgs::Point p;
  p.x = north;
  p.y = east;
  p.z = down;
  return p;
}

// The status; position and hold point in map_ned (NaN when unknown), as the other vehicle reads them.
inline MissionStatus status(const std::string& vehicle, const std::string& phase, const std::string& detail,
                            bool finished, bool success, double distance_to_go, double on_station_since,
                            const Eigen::Vector3d& position, const Eigen::Vector3d& hold_point, bool stationary) {
  MissionStatus s;
  s.header.stamp = ros::Time::now();
  s.vehicle = vehicle;
  s.phase = phase;
  s.detail = detail;
  s.finished = finished;
  s.success = success;
  s.distance_to_go = distance_to_go;
  s.on_station_since = on_station_since;
  s.position = point(position.x(), position.y(), position.z());
  s.hold_point = point(hold_point.x(), hold_point.y(), hold_point.z());
  s.stationary = stationary;
  return s;
}

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace mission_ros
}  // namespace offshore_gnc
