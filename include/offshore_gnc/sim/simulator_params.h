#pragma once
// The simulator nodelets' own parameters beside the simulations' (UsvSimulation::Config, AuvSimulation::Config and
// the sensors' tables): the run (scenario, time control, step, seed) and each vehicle's model and ROS names.
#include <string>

#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace sim {

// Both simulators: `scenario` is required (checked by the nodelet); the seed's default is the vehicle's (USV 1, AUV 2).
struct RunParams {
  std::string scenario;
  double rate = 1.0;  // x real time; 0: as fast as the CPU allows
  bool lockstep = false;
  double dt = 0.01;  // [s]
  int seed = 1;
  static const ParamTable<RunParams>& table();
};

struct UsvSimNodeParams {
  std::string model_params;  // config/models/*.yaml (models module); empty: the built-in USV
  std::string model = "dynamic";
  double manual_timeout = 1.0;  // [s]
  std::string command_topic = "/usv/joystick_cmd";
  std::string jet_command_topic;  // empty: none
  std::string base_frame = "usv/base_link";
  static const ParamTable<UsvSimNodeParams>& table();
};

struct AuvSimNodeParams {
  bool odom_enabled = true;  // false: the navigation nodelet publishes /auv/odom + TF
  std::string vehicle_model = "girona500";
  std::string model_params;  // config/models/*.yaml (models module), over vehicle_model's
  std::string base_frame = "auv/base_link";
  static const ParamTable<AuvSimNodeParams>& table();
};

}  // namespace sim
}  // namespace offshore_gnc
