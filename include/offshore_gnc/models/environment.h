#pragma once
// Environment shared by both vehicle models (ROS-free): the sea state. Current (constant plus a slow seeded
// variation), wind with gusts (a Harris spectrum) acting on the USV, and a long-crested irregular sea (JONSWAP)
// that gives each hull its wave-frequency (WF) motion, superposed on the low-frequency motion as in Fossen's
// two-time-scale model, and its mean wave drift force. Named sea states (calm, the thesis' field day, a moderate
// sea) fill the parameters; docs/simulation.md, "Sea state", gives every figure and its source. Deterministic:
// the same params (seed included) give the same values for the same time and place.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/models/state.h"

namespace YAML {
class Node;
}

namespace offshore_gnc {
namespace models {

struct EnvironmentParams {
  // Current, NED [m/s]: constant part plus two slow sinusoids (periods current_period and 1.37x it) with
  // seeded phases and directions, of total amplitude current_variation.
  double current_north = 0.0, current_east = 0.0;
  double current_variation = 0.0;  // [m/s]
  double current_period = 600.0;   // [s]
  int seed = 1;                    // every random phase: current, gusts, waves, whitecaps
  // Wind (USV only): mean speed [m/s] at 10 m and the direction it comes FROM [rad, clockwise from north], plus
  // gusts: the 1-sigma of the turbulent speed along the mean wind [m/s] (Harris spectrum).
  double wind_speed = 0.0, wind_direction = 0.0, wind_gust = 0.0;
  double air_density = 1.225;  // [kg/m^3]
  // Waves: significant height Hs [m] (0 = calm), peak period Tp [s], the direction they come FROM [rad], JONSWAP
  // peak enhancement gamma (1 = Pierson-Moskowitz).
  double wave_height = 0.0, wave_period = 4.0, wave_direction = 0.0, wave_gamma = 3.3;
  // > 0: the waves are the wind's sea over this fetch [m] (fetchLimitedSea of wind_speed: height and period), from
  // the wind's direction unless a file gives waves/direction_deg; environmentFromYaml resolves it.
  double wave_fetch = 0.0;
  double water_density = 1000.0;  // [kg/m^3] (fresh water: the thesis' lake trials)

  static const ParamTable<EnvironmentParams>& table();
  void validate() const;  // throws ConfigError naming the bad value
};

// The named sea states: "calm", "field_day" (the thesis' USV field test at Pyhajarvi), "field_day_auv" (its AUV
// test), "moderate" (Beaufort 4). Throws ConfigError listing the names for an unknown one.
EnvironmentParams seaState(const std::string& name);
const std::vector<std::string>& seaStateNames();
// A sea state from YAML: `sea_state: NAME` (default calm) with the table's keys (current/..., wind/..., waves/...,
// air_density, water_density) overriding it. Unknown keys inside current, wind and waves are refused naming the
// key; `source` prefixes every error. With waves/fetch the height and period come from the wind (a file giving
// them as well is refused): ripples under 0.5 s peak period, a breath of wind's, are no waves.
EnvironmentParams environmentFromYaml(const YAML::Node& root, const std::string& source);

// Wind sea from the wind, deep water: Hs [m] and Tp [s].
struct WindSea {
  double height, period;
};
// Fetch-limited growth (US Army Corps of Engineers, Coastal Engineering Manual, 2002, II-2, eq. II-2-36/37),
// wind speed U10 [m/s], fetch [m].
WindSea fetchLimitedSea(double wind_speed, double fetch);
// Fully developed Pierson-Moskowitz sea (Hs = 0.21 U19.5^2 / g, w_p = 0.877 g / U19.5; U19.5 = 1.026 U10).
WindSea fullyDevelopedSea(double wind_speed);
// Fraction of the surface white with foam (Monahan and O'Muircheartaigh 1980: W = 3.84e-6 U10^3.41).
double whitecapFraction(double wind_speed);

// What the waves act on: a box hull (length along the heading, beam, draft) [m].
struct Hull {
  double length = 8.0, beam = 2.5, draft = 0.5;
};

// Wave-frequency displacement and its rate, NED + Euler angles, to add to the low-frequency state.
struct WaveMotion {
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // [m] NED
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      // [m/s] NED
  double roll = 0.0, pitch = 0.0, yaw = 0.0;               // [rad]
  Eigen::Vector3d rate = Eigen::Vector3d::Zero();          // roll, pitch, yaw rates [rad/s]
};

// The reported state: low-frequency state plus wave-frequency motion (velocities rotated into body axes).
VehicleState withWave(const VehicleState& low_frequency, const WaveMotion& w);

class Environment;
// The surface at one moment along the waves' travel: its elevation and slope sampled finely enough that cubic
// Hermite interpolation stays within 0.25 % of Hs of the exact sum. A LiDAR frame asks for the elevation at about
// a thousand points, and each exact query costs a cosine per wave component. Points off the section are exact.
class SurfaceSection {
 public:
  double operator()(const Eigen::Vector2d& ne) const;

 private:
  friend class Environment;
  const Environment* env_ = nullptr;
  double t_ = 0.0, x0_ = 0.0, step_ = 1.0;
  Eigen::Vector2d travel_ = Eigen::Vector2d::UnitX();
  std::vector<double> eta_, slope_;  // elevation and its slope at x0_ + i step_ along travel_
};

class Environment {
 public:
  Environment();  // calm: no current, wind or waves
  explicit Environment(const EnvironmentParams& p);  // validates (ConfigError)
  Eigen::Vector3d current(double t) const;           // water velocity NED [m/s] (down component 0)
  Eigen::Vector2d wind(double t) const;              // air velocity NED [m/s] (where the air goes)
  double windSpeed(double t) const { return wind(t).norm(); }
  // Surface elevation [m, up] at a point (north, east).
  double elevation(double t, const Eigen::Vector2d& ne) const;
  // The same within `radius` of `centre` at time t, for many queries (SurfaceSection).
  SurfaceSection section(double t, const Eigen::Vector2d& centre, double radius) const;
  // Wave-frequency motion of a hull whose low-frequency state is `lf` (position, heading, depth >= 0: decaying
  // as exp(-k depth) per component, k = w^2 / g). Kinematic: the hull follows the water surface averaged over its
  // length and beam (heave, pitch, roll, and the orbital surge/sway whose bow-to-stern difference is its yaw), so
  // waves shorter than the hull move it little. Encounter frequency from the hull's own speed.
  WaveMotion wave(double t, const VehicleState& lf, const Hull& hull) const;
  // Mean wave drift force, NED [N], on a surface-piercing hull: rho g sum(a_i^2 / 2) R_i^2 times its width facing
  // the waves, along their direction; R_i^2 = 1 - exp(-2 k_i draft), the energy flux the hull's draft stops
  // (long waves pass under it), times min(1, 3.08 (k_i w/2)^3) for a width w small against the wavelength (they
  // pass round it: Havelock's small-body limit). 0 for a calm sea.
  Eigen::Vector2d driftForce(double heading, const Hull& hull) const;
  // Whitecap foam at a point of the surface: cells of `patch` metres that whiten for `life` seconds at a time,
  // a `fraction` of them at any time (deterministic for the seed); whitecapFraction(windSpeed(t)) is the wind's.
  bool foam(double t, const Eigen::Vector2d& ne, double patch, double life, double fraction) const;
  double significantHeight() const { return p_.wave_height; }
  const EnvironmentParams& params() const { return p_; }

 private:
  struct Component {
    double a, w, k, phase;  // amplitude [m or m/s], [rad/s], wave number [1/m], [rad]
  };
  EnvironmentParams p_;
  double phase_[2] = {0, 0}, angle_[2] = {0, 0};  // the current's variation
  std::vector<Component> waves_, gusts_;
};

}  // namespace models
}  // namespace offshore_gnc
