#pragma once
// One vehicle's simulation: the models module's vehicle model + environment + the vehicle's sensors, each
// sensor sampled at its own rate on a fixed simulation step. Shared by the simulator nodelets and the
// benchmark (no ROS). Commands with NaN are rejected and counted by the models, never integrated.
#include <array>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/faults.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/models/auv.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/joystick_allocation.h"
#include "offshore_gnc/models/state.h"
#include "offshore_gnc/models/usv.h"
#include "offshore_gnc/sim/scenario.h"
#include "offshore_gnc/sim/sensors.h"
#include "offshore_gnc/sim/world.h"

namespace offshore_gnc {
namespace sim {

// The generalised command of a flight controller's RC inputs (normalised -1..1).
struct AuvCommand {
  double surge = 0, sway = 0, heave = 0, yaw = 0;
};
// aColor flight controller RC channels (1-based channel 3 throttle/heave, 4 yaw, 5 forward, 6 lateral),
// 1100..1900 us with 1500 neutral; nothing for fewer than 6 channels or a pulse outside that range.
std::optional<AuvCommand> fromRcChannels(const std::vector<std::uint16_t>& channels);
// The RC command through the flight controller's mixer (models::mixAxes).
Eigen::VectorXd mixToThrusters(const Eigen::MatrixXd& tcm, const AuvCommand& c);
// Environment of a scenario: its sea state (preset, current, wind, waves).
models::EnvironmentParams environmentOf(const Scenario& sc);

// The obstacle of the `collision` fault: a barge broadside across the USV's course, appearing the first time the
// USV moves at `min_speed` or more within the fault's window where its bow (half its length ahead) reaches it in
// `time_ahead` at that speed, and gone at the window's end. Its face is wider than the LiDAR sees at that distance
// (its returns grow sparse towards the ends: perception made it 70 m long from 10 m), and the safety box of that
// extent reaches past the USV: no side is left to go round it.
struct CollisionFault {
  double time_ahead = 6.0;  // [s] under the supervisor's allstop_ttc (8 s)
  double length = 150.0, width = 10.0, height = 3.0;  // [m]
  double min_speed = 0.8;   // under way: speed over ground [m/s]
};

// What the CAN gateway reports of the bus (on the vessel; simulated here, where there is no bus): the bus state
// and whether each waterjet's control unit answers (a status frame within the gateway's jet_timeout).
struct GatewayReport {
  bool bus_off = false;
  std::array<bool, 2> answering{true, true};  // port, starboard
  bool operator!=(const GatewayReport& o) const { return bus_off != o.bus_off || answering != o.answering; }
};

class UsvSimulation {
 public:
  struct Config {
    double dt = 0.01;
    std::uint64_t seed = 1;
    bool lidar_on = true;
    GpsCompassConfig gps;
    LidarConfig lidar;
    models::UsvParams usv;
    // "gps" and "lidar" silence those sensors while active; "jet" stops the port jet's unit, "bus_off" the bus
    // (both units then run idle with the bucket neutral, the GPS-compass on the bus is silent); "collision" shows
    // the CollisionFault obstacle to the LiDAR.
    FaultPlan faults;
    double jet_status_rate_hz = 10.0;  // the units' status frames
    double jet_timeout = 0.5;          // the gateway's (config/can/usv.yaml): a unit silent this long is not answering
    CollisionFault collision;
    static const ParamTable<Config>& table();  // the UsvSim nodelet's lidar/... (gps/...: GpsCompassConfig's)
  };
  struct Outputs {
    std::optional<GpsCompassReading> gps;
    bool lidar = false;  // scan() holds a new frame
    std::array<bool, 2> jet_status{false, false};  // unit i sent its status (jet(i)) this step
    bool gateway_changed = false;  // gateway() changed this step (and on the first step)
  };
  UsvSimulation(const Scenario& sc, const Config& cfg);
  // Both validate (NaN: false, counted by the model) and reach the jets unless a fault stops them.
  bool setCommand(const models::UsvCommand& c);
  bool setJetCommands(const models::JetCommands& c);  // per-jet set-points (twin propulsion), as setCommand
  const Outputs& step();
  const VehicleState& state() const { return model_.state(); }
  const models::UsvModel& model() const { return model_; }
  const LidarScan& scan() const { return scan_; }
  const GatewayReport& gateway() const { return gateway_; }
  // The collision fault's obstacle while it is in the world.
  const std::optional<Vessel>& faultObstacle() const { return obstacle_; }
  const Counters& counters() const { return model_.counters(); }
  double dt() const { return cfg_.dt; }

 private:
  void updateFaults(double t);
  void applyStops();  // the stopped units' set-points over the last command

  Config cfg_;
  World world_;
  models::Environment env_;
  models::UsvModel model_;
  GpsCompass gps_;
  Lidar lidar_;
  LidarScan scan_;
  Outputs out_;
  long step_ = 0, gps_every_, lidar_every_, status_every_;
  // faults on the propulsion: units stopped (port, starboard) and since when [s]
  std::array<bool, 2> stopped_{false, false};
  std::array<double, 2> stopped_since_{0.0, 0.0};
  std::optional<models::JoystickAllocation> allocation_;  // twin propulsion: the model's own, for stopped units
  bool from_joystick_ = true;                              // the last command was a joystick one (else per jet)
  models::UsvCommand last_command_;
  models::JetCommands last_jets_{};
  GatewayReport gateway_;
  bool gateway_reported_ = false;
  std::optional<Vessel> obstacle_;
  double obstacle_window_ = -1.0;  // start of the collision window it appeared in (once per window)
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
    SurfaceGpsConfig surface_gps;  // the same: the Girona500's GPS at the surface
    InsConfig ins;
    double odom_rate_hz = 20.0;
    models::AuvParams auv = models::AuvParams::girona500();
    // "sonar", "depth" and "dvl" silence those sensors while active; "nav" the AHRS, the DVL and the INS-like
    // estimate (the navigation's own inputs: without a heading it has no estimate either)
    FaultPlan faults;
    static const ParamTable<Config>& table();  // the AuvSim nodelet's sonar/... and odom/... (the sensors' own beside)
  };
  struct Outputs {
    std::optional<AhrsReading> ahrs;
    std::optional<DepthReading> depth;
    std::optional<DvlReading> dvl;     // Girona500 only (hasDvl())
    std::optional<SurfaceGpsReading> gps;  // Girona500 only, at the surface
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
  SurfaceGps gps_;
  InsEstimate ins_;
  SonarBeamReading beam_;
  Outputs out_;
  long step_ = 0, sonar_every_, depth_every_, ahrs_every_, dvl_every_, gps_every_, odom_every_;
  bool has_dvl_;
  Counters counters_;
};

}  // namespace sim
}  // namespace offshore_gnc
