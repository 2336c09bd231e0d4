#pragma once
// Sensor simulators: each produces what the real sensor's driver would emit, from the vehicle's true state
// and the world. Deterministic for a given seed (one std::mt19937_64 per sensor). ROS-free, NED / body FRD.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/state.h"
#include "offshore_gnc/sim/world.h"

namespace offshore_gnc {
namespace sim {

// Body (FRD) <- sensor transform of a sensor mounted at `mount_frd` with `yaw_frd` about the body's z axis, then
// `pitch_frd` about its y axis (nose up positive: a sonar head tilted down has a negative pitch); the sensor's own
// frame is FRD (the sonar head, SonarBeam.msg) or FLU (the LiDAR's cloud). The simulators publish it as the static
// TF and the ROS-free loops position their sensor data with it.
Eigen::Isometry3d sensorMount(const Eigen::Vector3d& mount_frd, double yaw_frd, bool frd_sensor, double pitch_frd = 0.0);

// ---------------------------------------------------------------- GPS-compass (USV)
// An SBAS GPS-compass (e.g. a Hemisphere Vector): its position error is mostly slow (ionosphere, multipath) with
// a little receiver jitter on top, so it is a first-order Gauss-Markov process plus white noise, not white noise
// alone (white 0.3 m at 10 Hz would make any speed from differenced fixes useless). Like the real receiver it also
// reports Doppler speed over ground and the rate of turn of its gyro, which the navigation uses directly.
// Beyond that slow error the fix jumps now and then (a satellite or its SBAS correction entering or leaving the
// solution, a reflection off a passing hull: the error steps and holds for a while) and the receiver loses its
// fix for a moment now and then (it then reports nothing: heading too, which comes from the same antennas).
// Altogether about the data sheet's SBAS figure, 0.3 m horizontal RMS (0.2 m per axis slow, the jumps' share, the
// jitter: 0.31 m); it was 0.3 m per axis (0.42 m horizontal), half as much error again.
struct GpsCompassConfig {
  double rate_hz = 10.0;
  double position_sigma = 0.2;          // slow horizontal error, each axis, 1-sigma [m]
  double position_tau = 60.0;           // its correlation time [s]; 0 makes it white
  double position_white_sigma = 0.02;   // receiver jitter per fix [m]
  double altitude_sigma = 0.5;          // [m]
  double heading_sigma = deg2rad(0.2);  // [rad]
  double velocity_sigma = 0.05;         // Doppler speed over ground, per axis [m/s]
  double rate_sigma = deg2rad(0.3);     // rate of turn [rad/s]
  Eigen::Vector3d antenna{0, 0, -2.5};  // antenna in body FRD [m]
  double jump_interval = 120.0;         // mean time between jumps (Poisson) [s]; 0: none
  double jump_sigma = 0.3;              // a jump's offset, each horizontal axis, 1-sigma [m]
  double jump_duration = 10.0;          // mean time a jump holds (exponential) [s]
  double outage_interval = 600.0;       // mean time between outages (Poisson) [s]; 0: none
  double outage_duration = 2.0;         // an outage lasts uniformly 0.2 s .. this [s]
  static const ParamTable<GpsCompassConfig>& table();  // names as the UsvSim nodelet reads them (gps/...)
};
struct GpsCompassReading {
  double t;
  geo::LatLonAlt fix;
  double heading;                // NED yaw of the vessel [rad], wrapped to (-pi, pi]
  Eigen::Vector2d velocity_ned;  // the antenna's velocity over ground, NED [m/s]
  double rate_of_turn;           // NED yaw rate [rad/s]
  double position_sigma, heading_sigma, velocity_sigma;
  bool valid = true;             // false in an outage: the receiver reports nothing (the simulations drop it)
};
class GpsCompass {
 public:
  GpsCompass(const GpsCompassConfig& cfg, const geo::LocalNed& frame, std::uint64_t seed);
  GpsCompassReading measure(const VehicleState& s);
  const GpsCompassConfig& config() const { return cfg_; }
  // The jump offset in force at the last reading (NED north, east) [m]: zero between jumps.
  const Eigen::Vector2d& jump() const { return jump_; }

 private:
  GpsCompassConfig cfg_;
  geo::LocalNed frame_;
  std::mt19937_64 rng_;
  Eigen::Vector2d slow_error_ = Eigen::Vector2d::Zero();  // the Gauss-Markov part of the position error
  Eigen::Vector2d jump_ = Eigen::Vector2d::Zero();
  double jump_until_ = -1.0, outage_until_ = -1.0;
  bool valid_ = true;  // the last reading was (no outage)
  double last_t_ = 0.0;
  bool started_ = false;
  std::normal_distribution<double> n_{0.0, 1.0};
  std::uniform_real_distribution<double> u_{0.0, 1.0};
};

// ---------------------------------------------------------------- LiDAR (SICK MRS1000-like)
// What the water and the air add to a LiDAR on a boat (docs/simulation.md, "The LiDAR on the water": each figure
// and its source). Whitecaps return the beams that land on them (a calm or rippled surface reflects them away);
// the bow throws spray that returns beams near the hull; some returns drop out; the sensor's built-in IMU (the
// MRS1000's option) reports its roll and pitch with each frame.
struct LidarSeaConfig {
  double foam_patch = 1.0;     // [m] size of a whitecap
  double foam_life = 3.0;      // [s] how long one stays white
  double spray_rate = 15.0;    // spray returns per frame for one unit of sea: Hs / 1 m + (speed / 4 m/s)^2
  double spray_range = 5.0;    // [m] from the sensor: the spray zone about the bow
  double spray_sector = deg2rad(180.0);  // centred ahead
  double spray_height = 1.5;   // [m] above the water
  double dropout = 0.01;       // a return is lost (wet, dark or grazing surfaces)
  double imu_sigma = deg2rad(0.2);  // roll and pitch noise of the built-in IMU
  static const ParamTable<LidarSeaConfig>& table();
};
struct LidarConfig {
  double rate_hz = 12.5;
  int layers = 4;
  std::vector<double> layer_elevation{deg2rad(-2.5), 0.0, deg2rad(2.5), deg2rad(5.0)};  // 7.5 deg in all
  double aperture = deg2rad(275.0);
  double step = deg2rad(0.25);
  double min_range = 0.2, max_range = 64.0;
  double range_sigma = 0.03;    // [m]
  Eigen::Vector3d mount{1.5, 0.0, -1.0};  // sensor in body FRD [m]: on the bow, 1 m above the waterline
  double mount_yaw = 0.0;
  LidarSeaConfig sea;
  static const ParamTable<LidarConfig>& table();  // the UsvSim nodelet's lidar/...: rate, noise, mount, the sea's
};
// One frame: ranges[layer * beams + beam], NaN = no return. Beam b's azimuth (clockwise, sensor frame) is
// -aperture/2 + b * step; layer elevation positive = up.
struct LidarScan {
  double t = 0.0;
  int layers = 0, beams = 0;
  std::vector<float> ranges;
  std::vector<double> azimuth, elevation;
  double roll = 0.0, pitch = 0.0;  // the built-in IMU: the sensor frame's attitude (FRD Euler) at the frame [rad]
  // Point of one return in the sensor frame, FRD (x forward, y starboard, z down).
  Eigen::Vector3d pointFrd(int layer, int beam) const;
};
// A frame as the driver publishes it (sensor_msgs/PointCloud2 layout): organised, one row per layer, in the
// sensor's FLU frame (x forward, y left, z up); per point x, y, z (float32) and ring (uint16); NaN for no
// return. The UsvSim nodelet publishes these bytes and the ROS-free loops read them, so both see one frame.
struct PackedCloud {
  static constexpr std::uint32_t kPointStep = 16, kX = 0, kY = 4, kZ = 8, kRing = 12;
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> data;
};
void packCloud(const LidarScan& scan, PackedCloud& out);

class Lidar {
 public:
  // `env`: the sea (its surface, whitecaps, waves); none = a calm, flat surface. Kept by pointer: it must outlive
  // the LiDAR.
  Lidar(const LidarConfig& cfg, const World& world, std::uint64_t seed, const models::Environment* env = nullptr);
  // Scans the world from the vehicle's state: position (heave included), roll, pitch and yaw. Reuses `out`'s
  // storage.
  void scan(const VehicleState& s, LidarScan& out);
  // What it sees from the next scan on (an obstacle that appears: the collision fault).
  void setWorld(const World& world) { world_ = world; }
  const LidarConfig& config() const { return cfg_; }
  int beams() const { return beams_; }

 private:
  void spray(const VehicleState& s, const Eigen::Vector3d& sensor, const Eigen::Matrix3d& to_ned, LidarScan& out);

  LidarConfig cfg_;
  World world_;
  const models::Environment* env_;
  int beams_;
  std::vector<double> cos_az_, sin_az_;  // per beam, fixed: the scan's trigonometry once
  RayScene scene_;
  std::vector<Hit2d> hits_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n_{0.0, 1.0};
  std::uniform_real_distribution<double> u_{0.0, 1.0};
};

// ---------------------------------------------------------------- Mechanical imaging sonar (Micron-like)
// What the water adds to the sonar picture (docs/simulation.md, "The sonar in the water": each figure and its
// source). Reverberation from the surface (rising with the wind) and from a flat bottom where the beam's vertical
// pattern reaches them; echoes from the buoys' mooring lines and the floating hulls' undersides; volume clutter
// (fish, bubbles, debris): point scatterers drawn anew every ping. Intensities on the sonar's 0-255 scale.
struct SonarWaterConfig {
  double surface_reverb = 2.0;    // surface reverberation on the beam's axis, per (m/s of wind)^2
  double bottom_reverb = 120.0;   // bottom reverberation on the beam's axis
  double mooring_echo = 110.0;    // a mooring line in the beam
  double hull_echo = 200.0;       // a floating hull's underside in the beam
  double clutter_density = 0.02;  // volume scatterers per m^3 of insonified water
  double clutter_echo = 60.0;     // their mean intensity (exponentially distributed)
  static const ParamTable<SonarWaterConfig>& table();
};
struct SonarConfig {
  double ping_rate_hz = 20.0;    // beams per second at 10 m range
  double step = deg2rad(1.8);
  double sector = deg2rad(90.0);  // centred on the head's forward axis
  double range = 10.0;
  int bins = 200;
  double beam_width = deg2rad(3.0);  // horizontal
  double vertical_width = deg2rad(35.0);
  double near_field = 1.5;       // clutter from the vehicle structure inside this range [m]
  double noise_level = 12.0;     // mean speckle intensity
  Eigen::Vector3d mount{0.6, 0.0, -0.2};  // head in body FRD [m]
  // The head tilted down [rad], as it is set up to search a lake's floor: its 35 deg fan then spans 2.5 deg above
  // the horizon to 32.5 deg below it, so the surface stays out of the beam (docs/simulation.md).
  double tilt = deg2rad(15.0);
  SonarWaterConfig water;
  static const ParamTable<SonarConfig>& table();  // the AuvSim nodelet's sonar/...: the head's scan, the water's
};
struct SonarBeamReading {
  double t = 0.0;
  double bearing = 0.0;  // head angle, clockwise from forward, [0, 2 pi)
  double beam_width = 0.0, range_resolution = 0.0, range_offset = 0.0;
  std::uint16_t head_status = 0;  // SonarBeam.msg STATUS_* bits
  std::vector<std::uint8_t> intensities;
};
// SonarBeam.msg status bits, repeated here so the core does not include generated messages.
enum SonarStatus : std::uint16_t {
  kHeadReady = 1, kMotorOn = 2, kCentring = 4, kScanCw = 8, kSectorReverse = 16, kFault = 32
};
class Sonar {
 public:
  // `env`: the sea (wind for the surface's roughness, the surface's elevation); none = calm. Kept by pointer.
  Sonar(const SonarConfig& cfg, const World& world, std::uint64_t seed, const models::Environment* env = nullptr);
  // Next beam: the head steps, pings, and the echoes of targets and walls are drawn into the bins.
  void ping(const VehicleState& s, SonarBeamReading& out);
  const SonarConfig& config() const { return cfg_; }
  int binOfRange(double r) const;

 private:
  // Mean reverberation of a boundary at elevation `off` from the beam's axis [rad], at slant range r: the two-way
  // vertical beam pattern (Gaussian, -3 dB one way at the beam's edge) there.
  double reverb(double level, double off, double r) const;

  SonarConfig cfg_;
  World world_;
  const models::Environment* env_;
  double angle_;  // signed head angle, (-sector/2 .. sector/2)
  int direction_ = 1;
  bool reversed_ = false;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n_{0.0, 1.0};
  std::uniform_real_distribution<double> u_{0.0, 1.0};
};

// ---------------------------------------------------------------- AUV depth and AHRS
struct DepthConfig {
  double rate_hz = 10.0;
  double sigma_pa = 20.0;          // ~2 mm of water
  double atmosphere_pa = 101325.0;
  double water_density = 1000.0;   // fresh water (Pyhäjärvi); 1025 at sea
  static const ParamTable<DepthConfig>& table();  // depth/...
};
struct DepthReading {
  double t, pressure_pa, sigma_pa;
};
class DepthSensor {
 public:
  DepthSensor(const DepthConfig& cfg, std::uint64_t seed);
  DepthReading measure(const VehicleState& s);
  double depthOf(double pressure_pa) const;
  const DepthConfig& config() const { return cfg_; }

 private:
  DepthConfig cfg_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n_{0.0, 1.0};
};

// A MEMS AHRS with a magnetometer (e.g. an Xsens MTi-300 class unit: roll and pitch 0.2 deg, heading 1 deg RMS in
// its data sheet). Its heading error is not only white: a bias fixed for the run (the residual of the hard- and
// soft-iron calibration, the vehicle's own field) and a slow drift (first-order Gauss-Markov: thruster currents,
// temperature) come on top of the noise; together about the data sheet's 1 deg RMS.
struct AhrsConfig {
  double rate_hz = 50.0;
  double attitude_sigma = deg2rad(0.2);  // roll, pitch [rad]
  double heading_sigma = deg2rad(0.5);  // yaw [rad] (magnetic compass)
  double gyro_sigma = 0.002;       // [rad/s]
  double accel_sigma = 0.02;       // [m/s^2]
  double heading_bias_sigma = deg2rad(0.7);   // the run's heading bias, drawn once, 1-sigma [rad]
  double heading_drift_sigma = deg2rad(0.5);  // the slow heading drift, 1-sigma [rad]
  double heading_drift_tau = 300.0;           // its correlation time [s]
  static const ParamTable<AhrsConfig>& table();  // ahrs/...
};
struct AhrsReading {
  double t;
  double roll, pitch, yaw;           // NED / FRD Euler angles [rad]
  Eigen::Vector3d angular_rate;      // body FRD [rad/s]
  Eigen::Vector3d specific_force;    // body FRD, includes gravity reaction (-g on z at rest) [m/s^2]
  double attitude_sigma, heading_sigma, gyro_sigma, accel_sigma;
};
class Ahrs {
 public:
  Ahrs(const AhrsConfig& cfg, std::uint64_t seed);
  // `accel_body` is the body-frame linear acceleration of the vehicle (from the model, or finite differences).
  AhrsReading measure(const VehicleState& s, const Eigen::Vector3d& accel_body);
  const AhrsConfig& config() const { return cfg_; }
  double headingError() const { return bias_ + drift_; }  // bias + drift at the last reading [rad]

 private:
  AhrsConfig cfg_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n_{0.0, 1.0};
  double bias_ = 0.0, drift_ = 0.0, last_t_ = 0.0;
  bool started_ = false;
};

// ---------------------------------------------------------------- DVL (Girona500)
// A Doppler velocity log in bottom lock: the vehicle's velocity over ground in its body frame (FRD). Mounted at the
// body origin (no lever arm). Beyond its white noise it has the errors a data sheet's long-term accuracy covers,
// each fixed for the run: a scale error (sound speed at the transducer, beam angles), a misalignment about the
// vertical (how well it was mounted) and a small offset per axis. It locks on the bottom only between its minimum
// and maximum altitude (Nortek DVL1000 class: about 75 m); outside that it reports nothing. The water's depth
// under the vehicle is `bottom_depth`, one value until the scenario has a bottom (then it feeds this parameter).
struct DvlConfig {
  double rate_hz = 5.0;
  double velocity_sigma = 0.02;                // per axis [m/s]
  double scale_sigma = 0.002;                  // scale error, drawn once, 1-sigma [-]
  double misalignment_sigma = deg2rad(0.5);    // misalignment about z, drawn once, 1-sigma [rad]
  double offset_sigma = 0.001;                 // offset per axis, drawn once, 1-sigma [m/s]
  double min_altitude = 0.3, max_altitude = 75.0;  // bottom lock between these altitudes [m]
  double bottom_depth = 10.0;                  // the water's depth under the vehicle [m]
  static const ParamTable<DvlConfig>& table();  // dvl/...
};
struct DvlReading {
  double t;
  Eigen::Vector3d velocity;  // over ground, body FRD [m/s]
  double velocity_sigma;     // [m/s]
  double altitude;           // above the bottom [m]
};
class Dvl {
 public:
  Dvl(const DvlConfig& cfg, std::uint64_t seed);
  // Nothing without bottom lock (above max_altitude, below min_altitude).
  std::optional<DvlReading> measure(const VehicleState& s);
  const DvlConfig& config() const { return cfg_; }
  // The run's bias: the reading is (1 + scale) R_z(misalignment) v + offset + noise.
  double scale() const { return scale_; }
  double misalignment() const { return misalignment_; }
  const Eigen::Vector3d& offset() const { return offset_; }

 private:
  DvlConfig cfg_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n_{0.0, 1.0};
  double scale_, misalignment_;
  Eigen::Vector3d offset_;
};

// ---------------------------------------------------------------- AUV GPS at the surface
// The Girona500's GPS (COLA2's navigator fuses it at the surface; IQUA Robotics' data sheet lists GPS among the
// standard sensors): a fix while the antenna is out of the water (the vehicle no deeper than max_depth), white
// noise on each horizontal axis of a consumer receiver. The aColor (a BlueROV2-class frame on ArduSub) has none.
struct SurfaceGpsConfig {
  double rate_hz = 1.0;    // fixes per second at the surface
  double sigma = 1.5;      // horizontal, each axis [m]
  double max_depth = 0.3;  // deeper, the antenna is under water: no fix [m]
  static const ParamTable<SurfaceGpsConfig>& table();  // surface_gps/...
};
struct SurfaceGpsReading {
  double t;
  geo::LatLonAlt fix;
  double sigma;  // [m], each horizontal axis
};
class SurfaceGps {
 public:
  SurfaceGps(const SurfaceGpsConfig& cfg, const geo::LocalNed& frame, std::uint64_t seed);
  std::optional<SurfaceGpsReading> measure(const VehicleState& s);  // nothing under water

 private:
  SurfaceGpsConfig cfg_;
  geo::LocalNed frame_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n_{0.0, 1.0};
};

// ---------------------------------------------------------------- AUV navigation estimate (simulation only)
// Stands in for a DVL-aided INS (e.g. COLA2's navigator on Girona500): ground truth plus white noise and a
// horizontal random-walk drift, the error such a filter shows between USBL fixes. Simulation only.
struct InsConfig {
  double position_sigma = 0.05;    // white noise [m]
  double drift_per_sqrt_s = 0.02;  // horizontal random walk [m / sqrt(s)]
  double depth_sigma = 0.02;       // [m]
  double yaw_sigma = deg2rad(0.5);
  double velocity_sigma = 0.01;    // [m/s]
};
class InsEstimate {
 public:
  InsEstimate(const InsConfig& cfg, std::uint64_t seed);
  VehicleState estimate(const VehicleState& truth);
  Eigen::Vector2d drift() const { return drift_; }

 private:
  InsConfig cfg_;
  Eigen::Vector2d drift_{0, 0};
  double last_t_ = -1.0;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n_{0.0, 1.0};
};

}  // namespace sim
}  // namespace offshore_gnc
