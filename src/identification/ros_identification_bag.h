#pragma once
// ROS side of model_fit: a rosbag recorded by our launch files -> the identification's log (models/ident_log.h).
#include <string>

#include "offshore_gnc/identification/ident_log.h"
#include "offshore_gnc/identification/identification.h"

namespace offshore_gnc {
namespace identification_ros {

struct BagOptions {
  double nozzle_max = 10000.0;   // WaterjetStatus.nozzle_position (-1..1) -> P_nozzle
  double manual_timeout = 1.0;   // /usv/manual_cmd wins while younger than this (as the USV simulator) [s]
};

// USV: /usv/waterjet/applied_cmd if recorded, else /usv/manual_cmd over /usv/joystick_cmd; /usv_gps,
// /usv_heading, /usv/gps/velocity (u, v, rate of turn), /usv/waterjet/status (port jet: rpm, nozzle).
// Girona500: /auv/thruster_setpoints and /auv/odom. One row per time stamp; the log starts at the first
// command. Throws ConfigError naming what is missing.
identification::IdentLog readIdentLogBag(const std::string& path, identification::FitVehicle v, int thrusters,
                                 const BagOptions& opt);

}  // namespace identification_ros
}  // namespace offshore_gnc
