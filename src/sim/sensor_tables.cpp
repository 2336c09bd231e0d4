// The sensor simulators' parameter tables (include/offshore_gnc/sim/sensors.h): names, ranges and docs of what the
// simulator nodelets read and docs/parameters.md prints; kept apart from the models in sensors.cpp.
#include "offshore_gnc/sim/sensors.h"

namespace offshore_gnc {
namespace sim {

const ParamTable<GpsCompassConfig>& GpsCompassConfig::table() {
  using P = GpsCompassConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("gps/rate", &P::rate_hz, 0.1, 100, "Hz", "fixes per second")
      .number("gps/position_sigma", &P::position_sigma, 0, 100, "m", "slow horizontal error (Gauss-Markov), 1-sigma")
      .number("gps/position_tau", &P::position_tau, 0, 1e5, "s", "its correlation time (0: white)")
      .number("gps/position_white_sigma", &P::position_white_sigma, 0, 100, "m", "receiver jitter per fix")
      .number("gps/altitude_sigma", &P::altitude_sigma, 0, 100, "m", "altitude noise")
      .degrees("gps/heading_sigma_deg", &P::heading_sigma, 0, 45, "heading noise")
      .number("gps/velocity_sigma", &P::velocity_sigma, 0, 10, "m/s", "Doppler velocity noise, each axis")
      .numberAt("gps/rate_sigma_deg", [](P& p) -> double& { return p.rate_sigma; }, 0, 45, "deg/s",
                "rate-of-turn noise", kPi / 180.0)
      .list("gps/antenna", 3, -50, 50, "m", "the antenna in the body frame (x forward, y starboard, z down)",
            [](const P& p) { return std::vector<double>{p.antenna.x(), p.antenna.y(), p.antenna.z()}; },
            [](P& p, const std::vector<double>& v) { p.antenna = {v[0], v[1], v[2]}; })
      .number("gps/jump_interval", &P::jump_interval, 0, 1e6, "s",
              "mean time between jumps of the fix (multipath, SBAS corrections; Poisson); 0: none")
      .number("gps/jump_sigma", &P::jump_sigma, 0, 100, "m", "a jump's offset, each horizontal axis, 1-sigma")
      .number("gps/jump_duration", &P::jump_duration, 0.01, 1e5, "s", "mean time a jump holds (exponential)")
      .number("gps/outage_interval", &P::outage_interval, 0, 1e6, "s",
              "mean time between outages (no fix, no heading; Poisson); 0: none")
      .number("gps/outage_duration", &P::outage_duration, 0.2, 600, "s", "an outage lasts uniformly 0.2 s .. this");
  return t;
}

const ParamTable<LidarSeaConfig>& LidarSeaConfig::table() {
  using P = LidarSeaConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("foam_patch", &P::foam_patch, 0.05, 100.0, "m", "size of a whitecap (its returns are one patch)")
      .number("foam_life", &P::foam_life, 0.1, 600.0, "s", "how long a whitecap stays white")
      .number("spray_rate", &P::spray_rate, 0.0, 1000.0, "",
              "spray returns per frame for one unit of sea (Hs / 1 m + (speed / 4 m/s)^2)")
      .number("spray_range", &P::spray_range, 0.0, 50.0, "m", "the spray zone's reach from the sensor")
      .degrees("spray_sector_deg", &P::spray_sector, 0.0, 360.0, "the spray zone's width, centred ahead")
      .number("spray_height", &P::spray_height, 0.0, 10.0, "m", "the spray zone's height above the water")
      .number("dropout", &P::dropout, 0.0, 1.0, "", "probability that a return is lost")
      .degrees("imu_sigma_deg", &P::imu_sigma, 0.0, 10.0, "roll and pitch noise of the built-in IMU");
  return t;
}

const ParamTable<LidarConfig>& LidarConfig::table() {
  using P = LidarConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("rate", &P::rate_hz, 0.1, 100.0, "Hz", "frames per second")
      .number("range_sigma", &P::range_sigma, 0.0, 10.0, "m", "range noise of a return")
      .list("mount", 3, -50.0, 50.0, "m", "sensor in the body frame (x forward, y starboard, z down)",
            [](const P& p) { return std::vector<double>{p.mount.x(), p.mount.y(), p.mount.z()}; },
            [](P& p, const std::vector<double>& v) { p.mount = {v[0], v[1], v[2]}; })
      .nest("", &P::sea, LidarSeaConfig::table());
  return t;
}

const ParamTable<SonarWaterConfig>& SonarWaterConfig::table() {
  using P = SonarWaterConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("surface_reverb", &P::surface_reverb, 0.0, 100.0, "",
              "surface reverberation on the beam's axis per (m/s of wind)^2 (0-255 scale)")
      .number("bottom_reverb", &P::bottom_reverb, 0.0, 255.0, "", "bottom reverberation on the beam's axis")
      .number("mooring_echo", &P::mooring_echo, 0.0, 255.0, "", "echo of a buoy's mooring line in the beam")
      .number("hull_echo", &P::hull_echo, 0.0, 255.0, "", "echo of a floating hull's underside in the beam")
      .number("clutter_density", &P::clutter_density, 0.0, 100.0, "1/m^3", "volume scatterers per m^3, new every ping")
      .number("clutter_echo", &P::clutter_echo, 0.0, 255.0, "", "their mean intensity (exponentially distributed)");
  return t;
}

const ParamTable<SonarConfig>& SonarConfig::table() {
  using P = SonarConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("ping_rate", &P::ping_rate_hz, 0.1, 100.0, "Hz", "beams per second at 10 m range")
      .number("range", &P::range, 1.0, 100.0, "m", "the scan's range")
      .degrees("step_deg", &P::step, 0.45, 7.2, "head step between beams")
      .degrees("sector_deg", &P::sector, 1.8, 360.0, "scanned sector, centred on the head's forward axis")
      .integer("bins", &P::bins, 8, 1500, "range bins of a beam")
      .list("mount", 3, -10.0, 10.0, "m", "head in the body frame (x forward, y starboard, z down)",
            [](const P& p) { return std::vector<double>{p.mount.x(), p.mount.y(), p.mount.z()}; },
            [](P& p, const std::vector<double>& v) { p.mount = {v[0], v[1], v[2]}; })
      .degrees("tilt_deg", &P::tilt, -90.0, 90.0, "the head tilted down (its fan then clears the surface)")
      .nest("", &P::water, SonarWaterConfig::table());
  return t;
}

const ParamTable<DepthConfig>& DepthConfig::table() {
  using P = DepthConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("depth/rate", &P::rate_hz, 0.1, 100, "Hz", "pressure readings per second")
      .number("depth/sigma", &P::sigma_pa, 0, 1e5, "Pa", "pressure noise (100 Pa: 1 cm of water)")
      .number("depth/water_density", &P::water_density, 900, 1100, "kg/m^3", "1000 fresh water, 1025 at sea");
  return t;
}

const ParamTable<AhrsConfig>& AhrsConfig::table() {
  using P = AhrsConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("ahrs/rate", &P::rate_hz, 0.1, 100, "Hz", "readings per second")
      .degrees("ahrs/attitude_sigma_deg", &P::attitude_sigma, 0, 45, "roll and pitch noise")
      .degrees("ahrs/heading_sigma_deg", &P::heading_sigma, 0, 45, "heading noise")
      .number("ahrs/gyro_sigma", &P::gyro_sigma, 0, 1, "rad/s", "angular rate noise")
      .number("ahrs/accel_sigma", &P::accel_sigma, 0, 10, "m/s^2", "specific force noise")
      .degrees("ahrs/heading_bias_sigma_deg", &P::heading_bias_sigma, 0, 45,
               "heading bias, drawn once per run (calibration residual, the vehicle's own field), 1-sigma")
      .degrees("ahrs/heading_drift_sigma_deg", &P::heading_drift_sigma, 0, 45,
               "slow heading drift (first-order Gauss-Markov), 1-sigma")
      .number("ahrs/heading_drift_tau", &P::heading_drift_tau, 1, 1e6, "s", "the drift's correlation time");
  return t;
}

const ParamTable<DvlConfig>& DvlConfig::table() {
  using P = DvlConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("dvl/rate", &P::rate_hz, 0.1, 100, "Hz", "readings per second")
      .number("dvl/sigma", &P::velocity_sigma, 0, 10, "m/s", "velocity noise, each axis")
      .number("dvl/scale_sigma", &P::scale_sigma, 0, 0.5, "", "scale error, drawn once per run, 1-sigma")
      .degrees("dvl/misalignment_sigma_deg", &P::misalignment_sigma, 0, 45,
               "mounting misalignment about the vertical, drawn once per run, 1-sigma")
      .number("dvl/offset_sigma", &P::offset_sigma, 0, 1, "m/s", "velocity offset per axis, drawn once per run, 1-sigma")
      .number("dvl/min_altitude", &P::min_altitude, 0, 100, "m", "no bottom lock closer to the bottom")
      .number("dvl/max_altitude", &P::max_altitude, 0.1, 1e4, "m", "no bottom lock farther from the bottom")
      .number("dvl/bottom_depth", &P::bottom_depth, 0.1, 12000, "m",
              "the water's depth under the vehicle (the scenario's bottom, when it has one)");
  return t;
}

const ParamTable<SurfaceGpsConfig>& SurfaceGpsConfig::table() {
  using P = SurfaceGpsConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("surface_gps/rate", &P::rate_hz, 0.1, 20.0, "Hz", "the Girona500's GPS fixes per second at the surface")
      .number("surface_gps/sigma", &P::sigma, 0.0, 50.0, "m", "their horizontal noise, each axis")
      .number("surface_gps/max_depth", &P::max_depth, 0.0, 5.0, "m", "deeper than this the antenna is under water: no fix");
  return t;
}

}  // namespace sim
}  // namespace offshore_gnc
