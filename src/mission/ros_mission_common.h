#pragma once
// Shared by the two mission nodelets: message conversions and the status message.
#include <nav_msgs/Path.h>
#include <offshore_gnc/MissionStatus.h>
#include <ros/ros.h>

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

inline MissionStatus status(const std::string& vehicle, const std::string& phase, const std::string& detail,
                            bool finished, bool success,
                            double distance_to_go = std::numeric_limits<double>::quiet_NaN()) {
  MissionStatus s;
  s.header.stamp = ros::Time::now();
  s.vehicle = vehicle;
  s.phase = phase;
  s.detail = detail;
  s.finished = finished;
  s.success = success;
  s.distance_to_go = distance_to_go;
  return s;
}

}  // namespace mission_ros
}  // namespace offshore_gnc
