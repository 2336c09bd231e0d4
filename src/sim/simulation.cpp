// Vehicle simulations: plant integration on a fixed step and sensor sampling at each sensor's own rate.
#include "offshore_gnc/sim/simulation.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace sim {

namespace {
long everySteps(const char* name, double rate_hz, double dt) {
  requireRange(name, rate_hz, 1e-3, 0.5 / dt);  // at most one sample per step
  return std::max(1L, std::lround(1.0 / (rate_hz * dt)));
}
}  // namespace

models::EnvironmentParams environmentOf(const Scenario& sc) { return sc.sea; }

Eigen::VectorXd mixToThrusters(const Eigen::MatrixXd& tcm, const AuvCommand& c) {
  return models::mixAxes(tcm, Eigen::Vector4d(c.surge, c.sway, c.heave, c.yaw));
}

std::optional<AuvCommand> fromRcChannels(const std::vector<std::uint16_t>& ch) {
  if (ch.size() < 6) return std::nullopt;
  for (std::size_t i = 2; i < 6; ++i)
    if (ch[i] < 1100 || ch[i] > 1900) return std::nullopt;
  auto n = [&](int c) { return (ch[c - 1] - 1500.0) / 400.0; };
  return AuvCommand{n(5), n(6), n(3), n(4)};
}

// ---------------------------------------------------------------- USV
UsvSimulation::UsvSimulation(const Scenario& sc, const Config& cfg)
    : cfg_(cfg),
      world_(sc.world),
      env_(environmentOf(sc)),
      model_(cfg.usv),
      gps_(cfg.gps, geo::LocalNed(sc.origin), cfg.seed * 7919 + 1),
      lidar_(cfg.lidar, sc.world, cfg.seed * 7919 + 2, &env_) {
  requireRange("dt", cfg.dt, 1e-4, 0.1);
  requireRange("jet_timeout", cfg.jet_timeout, 0.0, 10.0);
  requireRange("collision/time_ahead", cfg.collision.time_ahead, 0.1, 600.0);
  requireRange("collision/length", cfg.collision.length, 0.1, 10000.0);
  requireRange("collision/width", cfg.collision.width, 0.1, 1000.0);
  requireRange("collision/height", cfg.collision.height, 0.1, 100.0);
  requireRange("collision/min_speed", cfg.collision.min_speed, 0.0, 20.0);
  gps_every_ = everySteps("gps/rate", cfg.gps.rate_hz, cfg.dt);
  lidar_every_ = everySteps("lidar/rate", cfg.lidar.rate_hz, cfg.dt);
  status_every_ = everySteps("jet_status_rate", cfg.jet_status_rate_hz, cfg.dt);
  if (cfg.usv.type == models::UsvModelType::Dynamic3Dof && cfg.usv.propulsion == models::UsvPropulsion::Twin)
    allocation_.emplace(cfg.usv);
  VehicleState s;
  s.position = {sc.usv.north, sc.usv.east, 0.0};
  s.yaw = wrapAngle(sc.usv.yaw);
  model_.reset(s);
}

const ParamTable<UsvSimulation::Config>& UsvSimulation::Config::table() {
  using P = UsvSimulation::Config;
  static const ParamTable<P> t = ParamTable<P>()
      .flag("lidar/enabled", &P::lidar_on, "simulate the LiDAR")
      .nest("lidar/", &P::lidar, LidarConfig::table());
  return t;
}

bool UsvSimulation::setCommand(const models::UsvCommand& c) {
  if (!model_.setCommand(c)) return false;
  from_joystick_ = true;
  last_command_ = model_.command();  // as the model took it (clamped)
  applyStops();
  return true;
}

bool UsvSimulation::setJetCommands(const models::JetCommands& c) {
  if (!model_.setJetCommands(c)) return false;
  from_joystick_ = false;
  last_jets_ = c;
  applyStops();
  return true;
}

// A stopped unit (its own fault, or no command over a bus that is off: the units' watchdog) idles with its bucket
// neutral: no force. The other jet keeps what the last command gave it.
void UsvSimulation::applyStops() {
  if (!stopped_[0] && !stopped_[1]) return;
  if (!allocation_) {  // lumped jets: only both can stop
    if (stopped_[0] && stopped_[1]) model_.setCommand({});
    return;
  }
  models::JetCommands c = from_joystick_ ? allocation_->allocate(last_command_) : last_jets_;
  for (int i = 0; i < 2; ++i)
    if (stopped_[i]) c[i] = {cfg_.usv.rpm_min, 0.0, 0.0};
  model_.setJetCommands(c);
}

void UsvSimulation::updateFaults(double t) {
  const bool bus_off = cfg_.faults.active("bus_off", t);
  const std::array<bool, 2> stopped{bus_off || cfg_.faults.active("jet", t), bus_off};
  if (stopped != stopped_) {
    for (int i = 0; i < 2; ++i)
      if (stopped[i] && !stopped_[i]) stopped_since_[i] = t;
    const bool resumed = (stopped_[0] && !stopped[0]) || (stopped_[1] && !stopped[1]);
    stopped_ = stopped;
    if (resumed) {  // the last command reaches the units again
      if (from_joystick_) model_.setCommand(last_command_);
      else model_.setJetCommands(last_jets_);
    }
    applyStops();
  }
  GatewayReport g;
  g.bus_off = bus_off;
  for (int i = 0; i < 2; ++i) g.answering[i] = !(stopped_[i] && t - stopped_since_[i] >= cfg_.jet_timeout - 1e-9);
  out_.gateway_changed = !gateway_reported_ || g != gateway_;
  gateway_ = g;
  gateway_reported_ = true;

  const Fault* window = cfg_.faults.activeFault("collision", t);
  if (!window && obstacle_) {
    obstacle_.reset();
    lidar_.setWorld(world_);
  }
  const VehicleState& s = model_.state();
  const Eigen::Rotation2Dd to_ned(s.yaw);
  const Eigen::Vector2d v = to_ned * s.velocity.head<2>();  // over ground
  if (window && !obstacle_ && window->start != obstacle_window_ && v.norm() >= cfg_.collision.min_speed) {
    const Eigen::Vector2d ahead = v.norm() > 1e-6 ? Eigen::Vector2d(v.normalized())  // the course, else the bow
                                                  : Eigen::Vector2d(std::cos(s.yaw), std::sin(s.yaw));
    const double face = cfg_.usv.length / 2 + v.norm() * cfg_.collision.time_ahead;  // from the USV's position
    Vessel barge;
    barge.centre = s.position.head<2>() + (face + cfg_.collision.width / 2) * ahead;
    barge.yaw = std::atan2(ahead.y(), ahead.x()) + kPi / 2;  // its long axis across the course
    barge.length = cfg_.collision.length;
    barge.width = cfg_.collision.width;
    barge.height = cfg_.collision.height;
    obstacle_ = barge;
    obstacle_window_ = window->start;
    World w = world_;
    w.vessels.push_back(barge);
    lidar_.setWorld(w);
  }
}

const UsvSimulation::Outputs& UsvSimulation::step() {
  model_.step(cfg_.dt, env_);
  ++step_;
  out_.gps.reset();
  out_.lidar = false;
  const double t = model_.state().t;
  updateFaults(t);
  // a silenced GPS-compass is still sampled: its errors are correlated in time and go on while it is silent; on
  // the vessel it reaches the computer over the CAN bus (NMEA 2000), silent too while the bus is off
  if (step_ % gps_every_ == 0) {
    out_.gps = gps_.measure(model_.state());
    if (!out_.gps->valid || cfg_.faults.active("gps", t) || gateway_.bus_off) out_.gps.reset();  // valid: no outage
  }
  if (cfg_.lidar_on && step_ % lidar_every_ == 0 && !cfg_.faults.active("lidar", t)) {
    lidar_.scan(model_.state(), scan_);
    out_.lidar = true;
  }
  for (int i = 0; i < 2; ++i) out_.jet_status[i] = step_ % status_every_ == 0 && !stopped_[i];
  return out_;
}

// ---------------------------------------------------------------- AUV
AuvSimulation::AuvSimulation(const Scenario& sc, const Config& cfg)
    : cfg_(cfg),
      env_(environmentOf(sc)),
      model_(cfg.auv),
      sonar_(cfg.sonar, sc.world, cfg.seed * 7919 + 3, &env_),
      depth_(cfg.depth, cfg.seed * 7919 + 4),
      ahrs_(cfg.ahrs, cfg.seed * 7919 + 5),
      dvl_(cfg.dvl, cfg.seed * 7919 + 7),
      gps_(cfg.surface_gps, geo::LocalNed(sc.origin), cfg.seed * 7919 + 8),
      ins_(cfg.ins, cfg.seed * 7919 + 6),
      has_dvl_(cfg.auv.type == models::AuvType::Girona500) {
  requireRange("dt", cfg.dt, 1e-4, 0.1);
  sonar_every_ = everySteps("sonar/ping_rate", cfg.sonar.ping_rate_hz, cfg.dt);
  depth_every_ = everySteps("depth/rate", cfg.depth.rate_hz, cfg.dt);
  ahrs_every_ = everySteps("ahrs/rate", cfg.ahrs.rate_hz, cfg.dt);
  dvl_every_ = everySteps("dvl/rate", cfg.dvl.rate_hz, cfg.dt);
  gps_every_ = everySteps("surface_gps/rate", cfg.surface_gps.rate_hz, cfg.dt);
  odom_every_ = everySteps("odom_rate", cfg.odom_rate_hz, cfg.dt);
  counters_.increment("rejected_commands", 0);  // listed in diagnostics from the start
  VehicleState s;
  s.position = {sc.auv.north, sc.auv.east, sc.auv.depth};
  s.yaw = wrapAngle(sc.auv.yaw);
  model_.reset(s);
}

const ParamTable<AuvSimulation::Config>& AuvSimulation::Config::table() {
  using P = AuvSimulation::Config;
  static const ParamTable<P> t = ParamTable<P>()
      .flag("sonar/enabled", &P::sonar_on, "simulate the imaging sonar")
      .nest("sonar/", &P::sonar, SonarConfig::table())
      .number("odom/rate", &P::odom_rate_hz, 0.1, 100.0, "Hz", "the INS-like navigation estimate's rate")
      .number("odom/position_sigma", &P::ins, &InsConfig::position_sigma, 0.0, 100.0, "m",
              "its white position noise")
      .number("odom/drift", &P::ins, &InsConfig::drift_per_sqrt_s, 0.0, 10.0, "m/sqrt(s)",
              "its horizontal random walk");
  return t;
}

bool AuvSimulation::setThrusters(const std::vector<double>& sp) {
  return model_.setCommand(Eigen::Map<const Eigen::VectorXd>(sp.data(), static_cast<Eigen::Index>(sp.size())));
}

bool AuvSimulation::setRcChannels(const std::vector<std::uint16_t>& ch) {
  const auto c = fromRcChannels(ch);
  if (!c) {
    counters_.increment("rejected_commands");
    return false;
  }
  return model_.setCommand(mixToThrusters(model_.tcm(), *c));
}

const AuvSimulation::Outputs& AuvSimulation::step() {
  const VehicleState before = model_.state();
  model_.step(cfg_.dt, env_);
  const VehicleState& s = model_.state();
  ++step_;
  out_.ahrs.reset();
  out_.depth.reset();
  out_.dvl.reset();
  out_.gps.reset();
  out_.odom.reset();
  out_.sonar = false;
  const bool nav_fault = cfg_.faults.active("nav", s.t);  // the navigation's own inputs are silent
  if (step_ % ahrs_every_ == 0 && !nav_fault) out_.ahrs = ahrs_.measure(s, (s.velocity - before.velocity) / cfg_.dt);
  if (step_ % depth_every_ == 0) {
    out_.depth = depth_.measure(s);
    if (cfg_.faults.active("depth", s.t)) out_.depth.reset();
  }
  if (has_dvl_ && step_ % dvl_every_ == 0) {
    out_.dvl = dvl_.measure(s);
    if (nav_fault || cfg_.faults.active("dvl", s.t)) out_.dvl.reset();
  }
  if (has_dvl_ && step_ % gps_every_ == 0) out_.gps = gps_.measure(s);  // the Girona500's, as its DVL
  if (step_ % odom_every_ == 0) {
    out_.odom = ins_.estimate(s);  // sampled all the same: its drift goes on
    if (nav_fault) out_.odom.reset();
  }
  if (cfg_.sonar_on && step_ % sonar_every_ == 0 && !cfg_.faults.active("sonar", s.t)) {
    sonar_.ping(s, beam_);
    out_.sonar = true;
  }
  return out_;
}

}  // namespace sim
}  // namespace offshore_gnc
