#include "offshore_gnc/usbl/config.h"

#include "offshore_gnc/common/angles.h"

namespace offshore_gnc {
namespace usbl {

const ParamTable<Mounting>& mountingTable() {
  using M = Mounting;
  static const ParamTable<M> t = ParamTable<M>()
      .numberAt("mount/x", [](M& m) -> double& { return m.offset.x(); }, -50, 50, "m", "transceiver forward of the GPS point")
      .numberAt("mount/y", [](M& m) -> double& { return m.offset.y(); }, -50, 50, "m", "to starboard")
      .numberAt("mount/z", [](M& m) -> double& { return m.offset.z(); }, -50, 50, "m", "below the GPS point")
      .degrees("mount/roll", &M::roll, -180, 180, "transceiver roll in the body frame")
      .degrees("mount/pitch", &M::pitch, -90, 90, "pitch")
      .degrees("mount/yaw", &M::yaw, -180, 180, "yaw (the transceiver's x from the bow)");
  return t;
}

const ParamTable<QualityLimits>& qualityLimitsTable() {
  using Q = QualityLimits;
  static const ParamTable<Q> t = ParamTable<Q>()
      .number("max_fit_error", &Q::max_fit_error, 0.01, 300, "", "SeaTrac USBL fit error above this: rejected")
      .number("max_age", &Q::max_age_s, 0.01, 60, "s", "a fix older than this when processed: stale")
      .number("max_pose_gap", &Q::max_pose_gap_s, 0.01, 10, "s", "the USV's GPS and heading this close to the fix time")
      .number("max_pose_wait", &Q::max_pose_wait_s, 0.0, 60, "s",
              "a fix waits this long for the relayed USV pose to reach its time (below max_age)")
      .number("max_depth_error", &Q::max_depth_error_m, 0.01, 1000, "m", "|USBL depth - the AUV's depth sensor| above this: rejected")
      .number("max_depth_gap", &Q::max_depth_gap_s, 0.01, 10, "s", "a depth sample this close to the fix, else no depth gate")
      .number("water_sound_speed", &Q::water_sound_speed, 0, 1700, "m/s",
              "the water's measured velocity of sound: ranges from the travel time with it (0: the transceiver's)");
  return t;
}

const ParamTable<BeaconSimConfig>& beaconSimTable() {
  using B = BeaconSimConfig;
  static const ParamTable<B> t = ParamTable<B>()
      .number("sound_speed", &B::sound_speed, 1300, 1700, "m/s", "simulated speed of sound (times the replies)")
      .number("range_sigma", &B::range_sigma, 0, 100, "m", "simulated range noise")
      .degrees("angle_sigma_deg", &B::angle_sigma, 0, 45, "simulated azimuth and elevation noise")
      .number("dropout_probability", &B::dropout_probability, 0, 1, "", "a ping that gets no reply")
      .number("max_range", &B::max_range, 1, 20000, "m", "beyond it every ping times out")
      .number("timeout", &B::timeout, 0.05, 30, "s", "the transceiver's response timeout before PING_ERROR")
      .number("fit_error", &B::fit_error, 0, 300, "",
              "the fit error of a direct arrival at short range with the USV steady (it grows with the angle noise)")
      .number("sound_speed_error", &B::sound_speed_error, -200, 200, "m/s",
              "the transceiver's velocity of sound minus the water's: ranges scaled by (c + this) / c")
      .number("snr_range", &B::snr_range, 1, 1e5, "m",
              "angle noise grows as sqrt(1 + (range / this)^2): the signal weakens with spreading")
      .number("motion_time", &B::motion_time, 0, 10, "s",
              "the USV's rotation over this long blurs the angles (reception, the transceiver's AHRS lag)")
      .number("fit_error_scatter", &B::fit_error_scatter, 0, 3, "",
              "lognormal spread of the reported fit error about what the conditions give")
      .number("multipath_probability", &B::multipath_probability, 0, 1, "",
              "a reply that came by a reflected path (surface, bottom, a hull): an outlier")
      .number("multipath_extra_range", &B::multipath_extra_range, 0, 1000, "m",
              "a reflected path's extra length, mean (exponential)")
      .degrees("multipath_angle_deg", &B::multipath_angle, 0, 180,
               "a reflected path's direction error, azimuth and elevation each, 1-sigma")
      .number("multipath_fit_error", &B::multipath_fit_error, 0, 300, "", "a reflected path's fit error, median")
      .number("burst_probability", &B::burst_probability, 0, 1, "",
              "per ping: a burst of dropouts starts (shadowing, the USV's jet bubbles)")
      .number("burst_pings", &B::burst_pings, 1, 1e4, "", "mean pings a dropout burst lasts (geometric)");
  return t;
}

const ParamTable<UsblNodeParams>& UsblNodeParams::table() {
  using P = UsblNodeParams;
  static const ParamTable<P> t = ParamTable<P>()
      .string("port", &P::port, "the transceiver's serial port")
      .integer("baud", &P::baud, 9600, 230400, "its baud rate")
      .number("reconnect_period", &P::reconnect_period, 0.05, 60, "s", "between attempts to open the port")
      .nest("", &P::pressure, geo::PressureDepth::table())
      .string("frame_id", &P::frame_id, "the transceiver's frame");
  return t;
}

const ParamTable<BeaconSimNodeParams>& BeaconSimNodeParams::table() {
  using P = BeaconSimNodeParams;
  static const ParamTable<P> t = ParamTable<P>()
      .string("port", &P::port, "the pseudo-terminal's path (a symlink): the Usbl nodelet's `port`")
      .integer("local_beacon_id", &P::local_beacon_id, 1, 15, "the transceiver's own beacon id")
      .integer("remote_beacon_id", &P::remote_beacon_id, 1, 15, "the only remote beacon in the water")
      .list("gps_antenna", 3, -50, 50, "m", "the simulated USV's GPS antenna in its body frame (x fwd, y stbd, z down)",
            [](const P& p) { return std::vector<double>{p.gps_antenna.x(), p.gps_antenna.y(), p.gps_antenna.z()}; },
            [](P& p, const std::vector<double>& v) { p.gps_antenna = {v[0], v[1], v[2]}; })
      .integer("seed", &P::seed, 0, 1 << 30, "the acoustics' random seed");
  return t;
}

}  // namespace usbl
}  // namespace offshore_gnc
