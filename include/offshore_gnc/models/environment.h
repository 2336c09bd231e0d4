#pragma once
// Environment shared by both vehicle models (ROS-free): ocean/lake current (constant plus a slow seeded
// variation), wind acting on the USV, and wave-frequency (WF) motion superposed on the low-frequency vehicle
// motion as in Fossen's two-time-scale model, at frequencies in the 0.1-0.4 rad/s band the control notch
// filters target. Deterministic: the same params (seed included) give the same values for the same t.
#include <cstdint>

#include <Eigen/Core>

#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace models {

struct EnvironmentParams {
  // Current, NED [m/s]: constant part plus two slow sinusoids (periods current_period and 1.37x it) with
  // seeded phases and directions, of total amplitude current_variation.
  double current_north = 0.0, current_east = 0.0;
  double current_variation = 0.0;  // [m/s]
  double current_period = 600.0;   // [s]
  std::uint64_t seed = 1;
  // Wind (USV only): mean speed [m/s] and the direction it comes FROM [rad, clockwise from north], plus a
  // slow gust amplitude [m/s] (seeded sinusoids, periods 30-90 s).
  double wind_speed = 0.0, wind_direction = 0.0, wind_gust = 0.0;
  double air_density = 1.225;  // [kg/m^3]
  // Wave-frequency motion: horizontal displacement amplitude [m] along the wave direction, heave amplitude
  // [m] (surface; decays as exp(-k depth), k = w^2/g), yaw amplitude [rad], frequency [rad/s] in [0.1, 0.4],
  // direction waves come FROM [rad]. Zero amplitudes = calm water.
  double wave_amplitude = 0.0, wave_heave_amplitude = 0.0, wave_yaw_amplitude = 0.0;
  double wave_frequency = 0.3, wave_direction = 0.0;
  double water_density = 1000.0;  // [kg/m^3] (fresh water: the thesis' lake trials)

  void validate() const;  // throws ConfigError naming the bad value
};

// Wave-frequency displacement and its rate, NED + yaw, to add to the low-frequency state.
struct WaveMotion {
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // [m] NED
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      // [m/s] NED
  double yaw = 0.0, yaw_rate = 0.0;                        // [rad], [rad/s]
};

// The reported state: low-frequency state plus wave-frequency motion (velocities rotated into body axes).
VehicleState withWave(const VehicleState& low_frequency, const WaveMotion& w);

class Environment {
 public:
  Environment();  // calm: no current, wind or waves
  explicit Environment(const EnvironmentParams& p);  // validates (ConfigError)
  Eigen::Vector3d current(double t) const;           // water velocity NED [m/s] (down component 0)
  Eigen::Vector2d wind(double t) const;              // air velocity NED [m/s] (where the air goes)
  WaveMotion wave(double t, double depth) const;     // WF motion at depth [m] (>= 0)
  const EnvironmentParams& params() const { return p_; }

 private:
  EnvironmentParams p_;
  double phase_[6] = {0, 0, 0, 0, 0, 0};
  double angle_[2] = {0, 0};
};

}  // namespace models
}  // namespace offshore_gnc
