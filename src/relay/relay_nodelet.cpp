// Relay nodelet: ros_relay.h's RelayRos in a nodelet manager (the relay_node executable runs the same class
// without the manager and the plugin loading, for the fastest start).
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "ros_relay.h"

namespace offshore_gnc {

class RelayNodelet : public nodelet::Nodelet {
  void onInit() override { relay_.start(getNodeHandle(), getPrivateNodeHandle(), getName()); }
  RelayRos relay_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::RelayNodelet, nodelet::Nodelet)
