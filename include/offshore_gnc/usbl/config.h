#pragma once
// The parameter tables of config/usbl/usbl.yaml, read through them by the Usbl nodelet, its simulator's nodelet and
// the ROS-free mission alike: the transceiver's mounting, the quality gates and the simulated beacon pair.
#include "offshore_gnc/common/param_table.h"
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

}  // namespace usbl
}  // namespace offshore_gnc
