#pragma once
// One vehicle's whole stack as its launch file runs it in simulation (usv.launch / auv.launch, sim:=true), in
// one process and without ROS: the simulator (plant + sensors), navigation, perception, the guidance pipeline,
// the control loop and the mission, each the very class its nodelet runs, fed what the nodelet would be fed,
// at the rate its timer or its sensor gives. The configuration comes from the same files the launch files load,
// as the vehicle's manifest lists them (config/vehicles/<vehicle>.yaml, closed_loop/manifest.h), read through the
// same parameter tables. Both vehicles on one clock make the ROS-free mission
// (closed_loop/mission.h). Each stack runs its safety supervisor as the SafetySupervisor nodelet does (the same
// inputs, its decision overriding control), so a fault in the simulation's plan (sim config `faults`) is answered
// here as in the ROS mission.
#include <Eigen/Core>

#include <deque>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "offshore_gnc/closed_loop/manifest.h"
#include "offshore_gnc/closed_loop/usbl_navigation.h"
#include "offshore_gnc/control/control_loop.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/guidance/pipeline.h"
#include "offshore_gnc/mission/mission.h"
#include "offshore_gnc/navigation/gps_navigator.h"
#include "offshore_gnc/navigation/pose_history.h"
#include "offshore_gnc/perception/lidar_targets.h"
#include "offshore_gnc/perception/sonar_targets.h"
#include "offshore_gnc/perception/target_tracker.h"
#include "offshore_gnc/safety/collision.h"
#include "offshore_gnc/safety/supervisor.h"
#include "offshore_gnc/sim/contact.h"
#include "offshore_gnc/sim/simulation.h"

namespace offshore_gnc {
namespace closed_loop {

// Steps of the simulation between two runs of a component at `rate_hz` (at least one).
int stepsPer(double rate_hz, double dt);

// The simulator's LiDAR frame as the LiDAR targets extraction reads it (the layout the UsvSim nodelet publishes).
perception::CloudView viewOf(const sim::PackedCloud& c);

// One vehicle's supervisor as its nodelet runs it: fed by the stack, updated at its rate, its decision handed to
// control (as the Control nodelet takes the SafetyState), every transition kept.
class StackSupervisor {
 public:
  StackSupervisor(const safety::SupervisorConfig& cfg, double dt, double rate_hz = 10.0);
  safety::Supervisor& core() { return sup_; }
  // Every step: updates at the supervisor's rate and sets control's override.
  void tick(long step, double t, control::ControlLoop& control);
  const safety::Decision& decision() const { return decision_; }
  const std::vector<safety::Transition>& transitions() const { return transitions_; }

 private:
  safety::Supervisor sup_;
  int every_;
  safety::Decision decision_;
  std::vector<safety::Transition> transitions_;
};

// ------------------------------------------------------------------------------------------------- USV
struct UsvStackConfig {
  sim::UsvSimulation::Config sim;     // the manifest's sim: its seed's default, the simulator's defaults
  navigation::GpsNavigatorConfig navigation;  // config/usv.yaml
  sim::HullFootprint hull;            // config/usv.yaml: the outline that judges contact
  perception::LidarConfig lidar;      // config/perception/lidar_usv.yaml
  perception::TrackerParams tracker;  // its tracker/...: the LidarTargets nodelet's tracks, which guidance takes
  double pose_timeout = 0.1;          // tf_timeout: a frame waits this long for the pose at its stamp [s]
  guidance::GuidanceParams guidance;  // config/guidance/usv.yaml
  control::ControlLoopParams control; // config/control/usv.yaml
  mission::UsvMissionParams mission;  // config/mission/usv.yaml
  // config/safety/usv.yaml: the supervisor; its region is also the mission's target check
  safety::SupervisorConfig safety = safety::usvDefaults();
  double safety_rate = 10.0;          // the supervisor's steps (its node's `rate`) [Hz]
  double mission_period = 0.5;        // the mission nodelet's timer [s]
  bool mission_enabled = true;        // false: guidance follows setRoute()'s path (benchmarks, tests)
  bool use_truth = false;             // guidance and control on the true state (isolates the controller)
};
// Reads the files under `config_dir` (the package's config/) that config/vehicles/usv.yaml lists, as usv.launch loads
// them; ConfigError names the file and the key (or the manifest's entry).
UsvStackConfig loadUsvStack(const std::string& config_dir);

class UsvStack {
 public:
  UsvStack(const sim::Scenario& scenario, const UsvStackConfig& cfg);
  // One simulator step, then every component whose sensor output or period has come.
  void step();
  void onTarget(const Eigen::Vector2d& ned, double t);  // /target, relayed from the AUV
  void onPeerAlive(double t);                           // the relay's link is up
  // /auv/mission/status, relayed: the AUV's phase, position and whether it is stationary at the surface.
  void onAuvStatus(mission::AuvPhase phase, const Eigen::Vector3d& ned, bool stationary, double t);
  void setRoute(const std::vector<Eigen::Vector3d>& path) { guidance_.setPath(path); }  // without the mission

  double time() const { return sim_.state().t; }
  const VehicleState& truth() const { return sim_.state(); }
  const std::optional<VehicleState>& estimate() const { return estimate_; }
  const mission::UsvMission& mission() const { return mission_; }
  const guidance::GuidancePipeline& guidance() const { return guidance_; }
  // The guidance output of this step, if guidance ran in it.
  const guidance::GuidanceOutput* guidanceStep() const { return guided_ ? &last_ : nullptr; }
  const guidance::GuidanceOutput& lastGuidance() const { return last_; }  // the latest guidance step's
  const std::vector<guidance::SbbObstacle>& obstacles() const { return obstacles_; }
  const perception::TargetTracker& tracker() const { return tracker_; }
  const sim::UsvSimulation& simulation() const { return sim_; }
  const control::ActuatorCommand& command() const { return command_; }  // the last control step's
  const control::ControlLoop& control() const { return control_; }
  const StackSupervisor& supervisor() const { return safety_; }
  // The GPS-compass reading of this step, if one came (what goes out on /usv_gps and /usv_heading).
  const std::optional<sim::GpsCompassReading>& gpsNow() const { return gps_now_; }

 private:
  void perceive(double t);
  void checkCollision(double t);  // the time to collision and the safe side, as the nodelet computes them
  void pathToGuidance();          // the mission's path, when it asks for one

  UsvStackConfig cfg_;
  sim::UsvSimulation sim_;
  navigation::GpsNavigator nav_;
  navigation::PoseHistory poses_;
  perception::LidarTargetExtractor lidar_;
  perception::TargetTracker tracker_;
  guidance::GuidancePipeline guidance_;
  control::ControlLoop control_;
  mission::UsvMission mission_;
  std::deque<sim::LidarScan> scans_;  // frames waiting for the pose at their stamp
  sim::PackedCloud cloud_;
  std::vector<guidance::SbbObstacle> obstacles_;
  std::vector<safety::SeenObstacle> seen_;  // the same, as the supervisor takes them
  std::optional<VehicleState> estimate_;
  std::optional<sim::GpsCompassReading> gps_now_;
  guidance::GuidanceOutput last_;
  control::ActuatorCommand command_;
  StackSupervisor safety_;
  bool guided_ = false;
  long step_ = 0;
  int guidance_every_, control_every_, mission_every_;
};

// ------------------------------------------------------------------------------------------------- AUV
// The AUV's GPS, modelled here because the simulator has none: a fix of the true horizontal position with white
// noise, at its rate, while the antenna is out of the water; the navigation fuses it as a position fix (the
// Girona500's navigator fuses its GPS at the surface the same way). The ROS mission has no such sensor yet.
struct AuvStackConfig {
  std::string model = "girona500";    // girona500 | acolor (auv.launch vehicle_model)
  sim::AuvSimulation::Config sim;     // the manifest's sim: its seed's default, the simulator's defaults, the model's params
  perception::SonarConfig sonar;      // config/perception/sonar_auv.yaml
  double pose_timeout = 0.1;          // tf_timeout
  guidance::GuidanceParams guidance;  // config/guidance/<model>.yaml
  control::ControlLoopParams control; // config/control/<model>.yaml
  mission::AuvMissionParams mission;  // config/mission/auv.yaml, the coverage from the scenario when it has one
  safety::SupervisorConfig safety = safety::auvDefaults();  // config/safety/auv.yaml
  double safety_rate = 10.0;          // [Hz]
  // auv.launch navigation: usbl (the default: UsblNavigation, the USV's relayed GPS and heading placing the
  // fixes) or ins (the simulator's INS-like estimate, without USBL: the supervisor's USBL timeout is off)
  std::string navigation = "usbl";
  UsblNavigationConfig usbl;          // config/usbl/usbl.yaml, config/navigation/auv_<model>.yaml
  unsigned usbl_seed = 1;             // the beacon simulator's (the manifest's usbl_sim seed)
  Eigen::Vector3d usv_gps_antenna{0, 0, -2.5};  // where the USV's GPS reports from (its simulator's gps/antenna)
  double length = 1.5;                // the vehicle config's vehicle/length: its size in the recovery figures [m]
  double mission_period = 0.5;
  bool mission_enabled = true;
  bool use_truth = false;
};
// As loadUsvStack, from config/vehicles/auv.yaml for `model` (one of its models); the mission's coverage from
// `scenario_file` when it has one (as auv.launch loads the scenario into the mission).
AuvStackConfig loadAuvStack(const std::string& config_dir, const std::string& model,
                            const std::string& scenario_file = "");
// The AUV's length from its vehicle config (config/auv_<model>.yaml vehicle/length) [m].
double auvLength(const std::string& config_dir, const std::string& model);
double auvLength(const VehicleManifest& auv, const std::string& model);

class AuvStack {
 public:
  AuvStack(const sim::Scenario& scenario, const AuvStackConfig& cfg);
  void step();
  void onPeerAlive(double t) { safety_.core().heard(safety::Source::kLink, t); }  // the relay's link is up
  // /usv/mission/status, relayed: the USV's phase, position and the point it holds (its station).
  void onUsvStatus(mission::UsvPhase phase, const Eigen::Vector2d& ned, const Eigen::Vector2d& station, double t);
  // What reaches the AUV's master from the USV: its GPS fix and heading over the relay, and (simulation only, the
  // acoustic channel) its true pose for the beacon simulator; set before step().
  void onUsvGps(const sim::GpsCompassReading& g);
  void setUsvTruth(const VehicleState& s) { usv_truth_ = s; }
  const UsblNavigation* usblNavigation() const { return usbl_ ? &*usbl_ : nullptr; }
  void setRoute(const std::vector<Eigen::Vector3d>& path) { guidance_.setPath(path); }  // without the mission
  const sim::AuvSimulation& simulation() const { return sim_; }
  const StackSupervisor& supervisor() const { return safety_; }

  double time() const { return sim_.state().t; }
  const VehicleState& truth() const { return sim_.state(); }
  const std::optional<VehicleState>& estimate() const { return estimate_; }
  const mission::AuvMission& mission() const { return mission_; }
  const guidance::GuidancePipeline& guidance() const { return guidance_; }
  const guidance::GuidanceOutput* guidanceStep() const { return guided_ ? &last_ : nullptr; }
  const guidance::GuidanceOutput& lastGuidance() const { return last_; }
  const control::ActuatorCommand& command() const { return command_; }  // the last control step's
  // The confirmed target for the USV, once (what the mission publishes on /target).
  std::optional<Eigen::Vector3d> takeTarget() { auto t = target_; target_.reset(); return t; }
  // Sonar targets of the sweeps so far (map_ned).
  const std::vector<perception::SonarTarget>& sonarTargets() const { return sonar_targets_; }

 private:
  void perceive();
  void navigate(const VehicleState& s, double t);  // a new /auv/odom: to TF, guidance, control, the supervisor


  AuvStackConfig cfg_;
  sim::AuvSimulation sim_;
  std::optional<UsblNavigation> usbl_;
  VehicleState usv_truth_;
  navigation::PoseHistory poses_;
  perception::SonarTargetExtractor sonar_;
  guidance::GuidancePipeline guidance_;
  control::ControlLoop control_;
  mission::AuvMission mission_;
  std::deque<sim::SonarBeamReading> beams_;
  std::vector<perception::SonarTarget> sonar_targets_;
  std::optional<VehicleState> estimate_;
  std::optional<Eigen::Vector3d> target_;
  guidance::GuidanceOutput last_;
  control::ActuatorCommand command_;
  StackSupervisor safety_;
  bool guided_ = false;
  long step_ = 0;
  int guidance_every_, control_every_, mission_every_, navigation_every_;
};

}  // namespace closed_loop
}  // namespace offshore_gnc
