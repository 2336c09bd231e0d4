#pragma once
// The parameter tables of config/usbl/usbl.yaml, read through them by the Usbl nodelet, its simulator's nodelet and
// the ROS-free mission alike: the transceiver's mounting, the quality gates and the simulated beacon pair.
#include <Eigen/Core>
#include <string>

#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/geo/pressure_depth.h"
#include "offshore_gnc/usbl/beacon_sim.h"
#include "offshore_gnc/usbl/positioning.h"

namespace offshore_gnc {
namespace usbl {

// mount/{x,y,z} [m] in the USV body frame (x forward, y starboard, z down) from the point /usv_gps reports,
// mount/{roll,pitch,yaw} [deg].
const ParamTable<Mounting>& mountingTable();
// max_fit_error, max_age, max_pose_gap, max_pose_wait, max_depth_error, max_depth_gap, water_sound_speed (the
// positioning's ranges)
const ParamTable<QualityLimits>& qualityLimitsTable();
// The simulated pair's acoustics: sound_speed, range_sigma, angle_sigma_deg, dropout_probability, max_range,
// timeout, fit_error and the field's effects (sound speed error, SNR and motion, multipath, dropout bursts; the
// beacon ids and the seed are set by whoever runs it, the mounting by mountingTable).
const ParamTable<BeaconSimConfig>& beaconSimTable();

// The Usbl nodelet's own parameters: the transceiver's line and the frame of its fixes; the AUV's depth from its
// pressure (the depth gate's) as the AUV navigation converts it.
struct UsblNodeParams {
  std::string port = "/dev/ttyUSB0";
  int baud = 115200;
  double reconnect_period = 1.0;  // [s]
  geo::PressureDepth pressure;
  std::string frame_id = "usv/usbl";
  static const ParamTable<UsblNodeParams>& table();
};

// The UsblSim nodelet's own parameters beside beaconSimTable's: its pseudo-terminal, the beacon ids, the seed, and
// the simulated USV's GPS antenna (the mounting is from the point /usv_gps reports, the poses it gets are the hull's).
struct BeaconSimNodeParams {
  std::string port = "/tmp/seatrac_sim";
  int local_beacon_id = 1, remote_beacon_id = 2;
  Eigen::Vector3d gps_antenna{0.0, 0.0, -2.5};  // [m] body frame (sim_usv's gps/antenna)
  int seed = 1;
  static const ParamTable<BeaconSimNodeParams>& table();
};

}  // namespace usbl
}  // namespace offshore_gnc
