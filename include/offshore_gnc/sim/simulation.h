#pragma once
// One vehicle's simulation: the models module's vehicle model + environment + the vehicle's sensors, each
// sensor sampled at its own rate on a fixed simulation step. Shared by the simulator nodelets and the
// benchmark (no ROS). Commands with NaN are rejected and counted by the models, never integrated.
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/faults.h"
#include "offshore_gnc/models/auv.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/state.h"
#include "offshore_gnc/models/usv.h"
#include "offshore_gnc/sim/scenario.h"
#include "offshore_gnc/sim/sensors.h"

namespace offshore_gnc {
namespace sim {

// The generalised command of a flight controller's RC inputs (normalised -1..1).
struct AuvCommand {
  double surge = 0, sway = 0, heave = 0, yaw = 0;
};
// aColor flight controller RC channels (1-based channel 3 throttle/heave, 4 yaw, 5 forward, 6 lateral),
// 1100..1900 us with 1500 neutral; nothing for fewer than 6 channels or a pulse outside that range.
std::optional<AuvCommand> fromRcChannels(const std::vector<std::uint16_t>& channels);
// ArduSub-style mixer: each thruster's factor per axis is its column of the thruster configuration matrix,
// normalised per axis; the sum is clamped to -1..1.
Eigen::VectorXd mixToThrusters(const Eigen::MatrixXd& tcm, const AuvCommand& c);
// Environment of a scenario: its current plus optional wind and waves.
models::EnvironmentParams environmentOf(const Scenario& sc);

class UsvSimulation {
 public:
  struct Config {
    double dt = 0.01;
    std::uint64_t seed = 1;
    bool lidar_on = true;
    GpsCompassConfig gps;
    LidarConfig lidar;
    models::UsvParams usv;
    FaultPlan faults;  // "gps" and "lidar" silence those sensors while active
  };
  struct Outputs {
    std::optional<GpsCompassReading> gps;
    bool lidar = false;  // scan() holds a new frame
  };
  UsvSimulation(const Scenario& sc, const Config& cfg);
  bool setCommand(const models::UsvCommand& c);  // false (and counted by the model) when rejected
  bool setJetCommands(const models::JetCommands& c);  // per-jet set-points (twin propulsion), as setCommand
  const Outputs& step();
  const VehicleState& state() const { return model_.state(); }
  const models::UsvModel& model() const { return model_; }
  const LidarScan& scan() const { return scan_; }
  const Counters& counters() const { return model_.counters(); }
  double dt() const { return cfg_.dt; }

 private:
  Config cfg_;
  models::Environment env_;
  models::UsvModel model_;
  GpsCompass gps_;
  Lidar lidar_;
  LidarScan scan_;
  Outputs out_;
  long step_ = 0, gps_every_, lidar_every_;
};

class AuvSimulation {
 public:
  struct Config {
    double dt = 0.01;
    std::uint64_t seed = 2;
    bool sonar_on = true;
    SonarConfig sonar;
    DepthConfig depth;
    AhrsConfig ahrs;
    DvlConfig dvl;  // used only by a Girona500 model (auv.type): the aColor has no DVL
    InsConfig ins;
    double odom_rate_hz = 20.0;
    models::AuvParams auv = models::AuvParams::girona500();
    FaultPlan faults;  // "sonar", "depth" and "dvl" silence those sensors while active
  };
  struct Outputs {
    std::optional<AhrsReading> ahrs;
    std::optional<DepthReading> depth;
    std::optional<DvlReading> dvl;     // Girona500 only (hasDvl())
    std::optional<VehicleState> odom;  // navigation estimate (INS stand-in)
    bool sonar = false;                // beam() holds a new beam
  };
  AuvSimulation(const Scenario& sc, const Config& cfg);
  // Per-thruster normalised commands (Girona500 ThrusterSetpoints.setpoint); rejected and counted by the
  // model when the size is wrong or a value is not finite.
  bool setThrusters(const std::vector<double>& setpoints);
  // RC channels through the mixer (aColor); rejected and counted ("rejected_commands") when invalid.
  bool setRcChannels(const std::vector<std::uint16_t>& channels);
  const Outputs& step();
  const VehicleState& state() const { return model_.state(); }
  const models::AuvModel& model() const { return model_; }
  const SonarBeamReading& beam() const { return beam_; }
  bool hasDvl() const { return has_dvl_; }  // the vehicle carries a DVL: Girona500 yes, aColor no
  const Counters& counters() const { return counters_; }             // command conversion
  const Counters& modelCounters() const { return model_.counters(); }  // NaN / clamped commands
  double dt() const { return cfg_.dt; }

 private:
  Config cfg_;
  models::Environment env_;
  models::AuvModel model_;
  Sonar sonar_;
  DepthSensor depth_;
  Ahrs ahrs_;
  Dvl dvl_;
  InsEstimate ins_;
  SonarBeamReading beam_;
  Outputs out_;
  long step_ = 0, sonar_every_, depth_every_, ahrs_every_, dvl_every_, odom_every_;
  bool has_dvl_;
  Counters counters_;
};

}  // namespace sim
}  // namespace offshore_gnc
