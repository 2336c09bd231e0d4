// relay_node: the multi-master relay as a plain node (RelayRos of ros_relay.h, as the Relay nodelet). Linked
// with the relay's own sources only, without the plugin loading and the rest of the stack's libraries, it is
// up in about a tenth of a second, so that the first message crosses soon after both sides start.
//
//   relay_node [ROS args]            the relay (parameters in ~, docs/relay.md)
//   relay_node --check-key FILE      checks a deployment key without ROS: prints its fingerprint and exits 0,
//                                    or says why it may not be used on hardware and how to make one (exit 1).
//                                    launch/relay.launch runs it when sim is false, so a launch stops first.
#include <ros/ros.h>

#include <unistd.h>

#include <cstring>
#include <iostream>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/relay/key.h"
#include "ros_relay.h"

namespace {
int checkKey(const char* path) {
  using namespace offshore_gnc::relay;
  try {
    const std::string key = readKeyFile(path);
    const std::string why = deploymentKeyProblem(key);
    if (!why.empty()) {
      std::cerr << "relay: refusing key_file '" << path << "' on hardware: the key " << why << ".\n"
                << kMakeKeyHint << ".\n";
      return 1;
    }
    std::cout << keyFingerprint(key) << (isatty(1) ? "\n" : "");  // as a roslaunch command parameter: no newline
    return 0;
  } catch (const offshore_gnc::ConfigError& e) {
    std::cerr << e.what() << ".\n" << kMakeKeyHint << ".\n";
    return 1;
  }
}
}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "--check-key") == 0) {
    if (argc != 3) {
      std::cerr << "usage: relay_node --check-key FILE\n";
      return 2;
    }
    return checkKey(argv[2]);
  }
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
