// Current, wind and wave-frequency motion; all randomness drawn once from the seed at construction.
#include "offshore_gnc/models/environment.h"

#include <cmath>
#include <random>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace models {

void EnvironmentParams::validate() const {
  requireRange("current_north", current_north, -5.0, 5.0);
  requireRange("current_east", current_east, -5.0, 5.0);
  requireRange("current_variation", current_variation, 0.0, 5.0);
  requireRange("current_period", current_period, 10.0, 1e6);
  requireRange("wind_speed", wind_speed, 0.0, 60.0);
  requireRange("wind_direction", wind_direction, -2 * kPi, 2 * kPi);
  requireRange("wind_gust", wind_gust, 0.0, 30.0);
  requireRange("air_density", air_density, 0.5, 2.0);
  requireRange("wave_amplitude", wave_amplitude, 0.0, 10.0);
  requireRange("wave_heave_amplitude", wave_heave_amplitude, 0.0, 10.0);
  requireRange("wave_yaw_amplitude", wave_yaw_amplitude, 0.0, 0.5);
  requireRange("wave_frequency", wave_frequency, 0.1, 0.4);
  requireRange("wave_direction", wave_direction, -2 * kPi, 2 * kPi);
  requireRange("water_density", water_density, 990.0, 1050.0);
}

Environment::Environment() { p_.validate(); }

Environment::Environment(const EnvironmentParams& p) : p_(p) {
  p_.validate();
  std::mt19937_64 rng(p_.seed);
  std::uniform_real_distribution<double> u(0.0, 2 * kPi);
  for (double& ph : phase_) ph = u(rng);
  for (double& a : angle_) a = u(rng);
}

Eigen::Vector3d Environment::current(double t) const {
  // Two slow components in seeded directions; half the amplitude each so the sum stays within it.
  const double w1 = 2 * kPi / p_.current_period, w2 = w1 / 1.37;
  const double a1 = 0.5 * p_.current_variation * std::sin(w1 * t + phase_[0]);
  const double a2 = 0.5 * p_.current_variation * std::sin(w2 * t + phase_[1]);
  return {p_.current_north + a1 * std::cos(angle_[0]) + a2 * std::cos(angle_[1]),
          p_.current_east + a1 * std::sin(angle_[0]) + a2 * std::sin(angle_[1]), 0.0};
}

Eigen::Vector2d Environment::wind(double t) const {
  const double speed = std::max(0.0, p_.wind_speed + 0.6 * p_.wind_gust * std::sin(2 * kPi * t / 37.0 + phase_[2]) +
                                         0.4 * p_.wind_gust * std::sin(2 * kPi * t / 89.0 + phase_[3]));
  // Meteorological direction: where the wind comes from; the air moves the opposite way.
  return {-speed * std::cos(p_.wind_direction), -speed * std::sin(p_.wind_direction)};
}

VehicleState withWave(const VehicleState& lf, const WaveMotion& w) {
  VehicleState out = lf;
  out.position += w.displacement;
  out.yaw = wrapAngle(lf.yaw + w.yaw);
  const double c = std::cos(out.yaw), s = std::sin(out.yaw);
  out.velocity += Eigen::Vector3d(c * w.velocity.x() + s * w.velocity.y(), -s * w.velocity.x() + c * w.velocity.y(),
                                  w.velocity.z());
  out.angular_rate.z() += w.yaw_rate;
  return out;
}

WaveMotion Environment::wave(double t, double depth) const {
  WaveMotion m;
  const double w = p_.wave_frequency;
  const double decay = std::exp(-w * w / 9.81 * std::max(0.0, depth));  // deep-water wave number k = w^2/g
  const double ph = w * t + phase_[4];
  const double s = std::sin(ph), c = std::cos(ph);
  // Waves travel opposite to where they come from.
  const Eigen::Vector3d along(-std::cos(p_.wave_direction), -std::sin(p_.wave_direction), 0.0);
  m.displacement = decay * (p_.wave_amplitude * s * along + Eigen::Vector3d(0, 0, p_.wave_heave_amplitude * c));
  m.velocity = decay * w * (p_.wave_amplitude * c * along - Eigen::Vector3d(0, 0, p_.wave_heave_amplitude * s));
  const double phy = ph + phase_[5];
  m.yaw = decay * p_.wave_yaw_amplitude * std::sin(phy);
  m.yaw_rate = decay * p_.wave_yaw_amplitude * w * std::cos(phy);
  return m;
}

}  // namespace models
}  // namespace offshore_gnc
