#pragma once
// Where a sensor's targets are put: the world frame and how long a frame or beam waits for the vehicle's pose at
// its stamp before it is dropped (tf2 in the nodelets, navigation::PoseHistory in the ROS-free loops).
#include <string>

#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace perception {

struct SensorFrameParams {
  std::string target_frame = "map_ned";
  double tf_timeout = 0.1;  // [s]
  static const ParamTable<SensorFrameParams>& table() {
    using P = SensorFrameParams;
    static const ParamTable<P> t = ParamTable<P>()
        .choice("target_frame", &P::target_frame, {"map_ned", "map"}, "world frame of the targets")
        .number("tf_timeout", &P::tf_timeout, 0.0, 10.0, "s",
                "a frame or beam waits this long for the pose at its stamp, then it is dropped");
    return t;
  }
};

// The LiDAR's own IMU (the MRS1000's), whose roll and pitch level each cloud before its targets are placed.
struct LidarImuParams {
  std::string imu_topic = "lidar/imu";  // empty: clouds taken as level
  double imu_timeout = 0.2;             // [s]
  static const ParamTable<LidarImuParams>& table() {
    using P = LidarImuParams;
    static const ParamTable<P> t = ParamTable<P>()
        .string("imu_topic", &P::imu_topic, "sensor_msgs/Imu of the LiDAR's own IMU (empty: clouds taken as level)")
        .number("imu_timeout", &P::imu_timeout, 0.0, 10.0, "s",
                "a cloud without an IMU sample this close to its stamp is taken as level (and counted)");
    return t;
  }
};

}  // namespace perception
}  // namespace offshore_gnc
