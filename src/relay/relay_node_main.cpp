// relay_node: the multi-master relay as a plain node (RelayRos of ros_relay.h, as the Relay nodelet). Linked
// with the relay's own sources only, without the plugin loading and the rest of the stack's libraries, it is
// up in about a tenth of a second, so that the first message crosses soon after both sides start.
#include <ros/ros.h>

#include "ros_relay.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "relay");
  ros::NodeHandle nh, pnh("~");
  offshore_gnc::RelayRos relay;
  try {
    relay.start(nh, pnh, ros::this_node::getName());
  } catch (const std::exception&) {
    return 1;  // already reported (ROS_FATAL naming the parameter)
  }
  ros::spin();
  return 0;
}
