#pragma once
// rviz markers of one publisher on a topic that several nodelets share (/<vehicle>/markers), each in its own
// namespace. Debian's rviz 1.14 clears EVERY namespace of a MarkerArray display on DELETEALL (whatever its ns),
// so one nodelet's refresh would erase the others' markers: instead each publisher replaces only its own, with
// DELETE actions for the ids it drew last time and no longer uses.
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <utility>
#include <vector>

namespace offshore_gnc {
namespace ros_util {

class NamespaceMarkers {
 public:
  NamespaceMarkers() = default;
  explicit NamespaceMarkers(std::string ns) : ns_(std::move(ns)) {}

  void advertise(ros::NodeHandle& nh, const std::string& topic, std::string ns, bool latch = false) {
    ns_ = std::move(ns);
    pub_ = nh.advertise<visualization_msgs::MarkerArray>(topic, 5, latch);
  }

  // Draws exactly `markers` in this namespace (ids 0..n-1, header h) and deletes the rest of the last set.
  void publish(std::vector<visualization_msgs::Marker> markers, const std_msgs::Header& h) {
    pub_.publish(replace(std::move(markers), h));
  }

  // The MarkerArray that publish() sends; remembers how many markers it drew for the next call.
  visualization_msgs::MarkerArray replace(std::vector<visualization_msgs::Marker> markers, const std_msgs::Header& h) {
    visualization_msgs::MarkerArray a;
    int id = 0;
    for (auto& m : markers) {
      m.header = h;
      m.ns = ns_;
      m.id = id++;
      m.action = visualization_msgs::Marker::ADD;
      if (m.pose.orientation.x == 0 && m.pose.orientation.y == 0 && m.pose.orientation.z == 0) m.pose.orientation.w = 1.0;
      a.markers.push_back(std::move(m));
    }
    for (int stale = id; stale < last_count_; ++stale) {
      visualization_msgs::Marker d;
      d.header = h;
      d.ns = ns_;
      d.id = stale;
      d.action = visualization_msgs::Marker::DELETE;
      a.markers.push_back(d);
    }
    last_count_ = id;
    return a;
  }

 private:
  std::string ns_;
  int last_count_ = 0;
  ros::Publisher pub_;
};

}  // namespace ros_util
}  // namespace offshore_gnc
