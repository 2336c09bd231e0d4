#include "offshore_gnc/closed_loop/stacks.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "offshore_gnc/common/param_yaml.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/perception/sensor_frame.h"
#include "offshore_gnc/sim/simulator_params.h"

namespace offshore_gnc {
namespace closed_loop {

int stepsPer(double rate_hz, double dt) { return std::max(1, static_cast<int>(std::lround(1.0 / (rate_hz * dt)))); }

perception::CloudView viewOf(const sim::PackedCloud& c) {
  using P = sim::PackedCloud;
  perception::CloudView v;
  v.data = c.data.data();
  v.size = c.data.size();
  v.width = c.width;
  v.height = c.height;
  v.point_step = P::kPointStep;
  v.row_step = c.width * P::kPointStep;
  const auto f32 = static_cast<std::uint8_t>(perception::FieldType::Float32);
  v.x = {true, P::kX, f32, 1};
  v.y = {true, P::kY, f32, 1};
  v.z = {true, P::kZ, f32, 1};
  v.ring = {true, P::kRing, static_cast<std::uint8_t>(perception::FieldType::UInt16), 1};
  return v;
}

namespace {

perception::SonarBeamView viewOf(const sim::SonarBeamReading& b) {
  perception::SonarBeamView v;
  v.stamp = b.t;
  v.bearing = b.bearing;
  v.beam_width = b.beam_width;
  v.range_resolution = b.range_resolution;
  v.range_offset = b.range_offset;
  v.status = b.head_status;
  v.bins = b.intensities.data();
  v.num_bins = b.intensities.size();
  return v;
}

// A component's sources read in order through `t` (each over the one before, as its rosparam loads are).
template <class P>
void readSources(const std::vector<ParamSource>& sources, const ParamTable<P>& t, P& p) {
  for (const auto& s : sources) readParamsYaml(s.yaml, t, p, s.name);
}

// The preset is the one the loaded `vehicle` names (the last source that sets it, as on the parameter server).
guidance::GuidanceParams readGuidance(const std::vector<ParamSource>& sources) {
  std::string vehicle = "usv";
  for (const auto& s : sources)
    if (s.yaml["vehicle"]) vehicle = s.yaml["vehicle"].as<std::string>();
  guidance::GuidanceParams g = guidance::GuidanceParams::preset(vehicle);
  readSources(sources, guidance::GuidanceParams::table(), g);
  return g;
}

control::ControlLoopParams readControl(const std::vector<ParamSource>& sources) {
  control::ControlLoopParams c;
  for (const auto& s : sources) {
    readParamsYaml(s.yaml, control::ControlLoopParams::table(), c, s.name);
    if (c.vehicle == "usv") readParamsYaml(s.yaml, control::UsvControlParams::table(), c.usv, s.name);
    else if (c.vehicle == "girona500") readParamsYaml(s.yaml, control::Girona500ControlParams::table(), c.girona500, s.name);
    else readParamsYaml(s.yaml, control::AcolorControlParams::table(), c.acolor, s.name);
  }
  return c;
}

// The supervisor's rules over the vehicle's preset, and its node's rate (as the SafetySupervisor nodelet reads them).
void readSafety(const std::vector<ParamSource>& sources, safety::SupervisorConfig& cfg, double& rate) {
  readSources(sources, safety::SupervisorConfig::table(), cfg);
  safety::SupervisorNodeParams node;
  readSources(sources, safety::SupervisorNodeParams::table(), node);
  rate = node.rate;
}

// The simulator nodelet's seed and step.
template <class Config>
void readRun(const std::vector<ParamSource>& sources, Config& c) {
  sim::RunParams run;
  readSources(sources, sim::RunParams::table(), run);
  c.seed = static_cast<std::uint64_t>(run.seed);
  c.dt = run.dt;
}

// The decision reaches control as control::SupervisorAction (control does not depend on safety).
constexpr bool sameAction(safety::Action a, control::SupervisorAction c) {
  return static_cast<int>(a) == static_cast<int>(c);
}
static_assert(sameAction(safety::Action::kNone, control::SupervisorAction::kNone) &&
              sameAction(safety::Action::kWarn, control::SupervisorAction::kWarn) &&
              sameAction(safety::Action::kHold, control::SupervisorAction::kHold) &&
              sameAction(safety::Action::kNeutral, control::SupervisorAction::kNeutral) &&
              sameAction(safety::Action::kSurface, control::SupervisorAction::kSurface) &&
              sameAction(safety::Action::kAbort, control::SupervisorAction::kAbort),
              "safety::Action must match control::SupervisorAction");

// The supervisor surfaces the vehicle (surface, or abort, which surfaces): the AUV mission ascends as well.
bool surfaces(const safety::Decision& d) { return !d.manual && d.action >= safety::Action::kSurface; }

// The AUV's supervisor as auv.launch configures it: without USBL (navigation:=ins) its USBL timeout is off.
safety::SupervisorConfig auvSafety(const AuvStackConfig& c) {
  if (c.navigation != "usbl" && c.navigation != "ins")
    throw ConfigError("navigation '" + c.navigation + "' is not one of: usbl, ins");
  safety::SupervisorConfig s = c.safety;
  if (c.navigation == "ins") s.usbl_timeout = 0.0;
  return s;
}

}  // namespace

StackSupervisor::StackSupervisor(const safety::SupervisorConfig& cfg, double dt, double rate_hz)
    : sup_(cfg), every_(stepsPer(rate_hz, dt)) {}

void StackSupervisor::tick(long step, double t, control::ControlLoop& control) {
  if (step % every_ != 0) return;
  safety::SupervisorOutput out = sup_.update(t);
  transitions_.insert(transitions_.end(), out.transitions.begin(), out.transitions.end());
  decision_ = out.decision;
  const auto action = static_cast<control::SupervisorAction>(decision_.action);  // as the Control nodelet reads it
  control.setSafety(control::safetyOverrideOf(action, decision_.manual),
                    decision_.active_rule + ": " + decision_.reason);
}

// ------------------------------------------------------------------------------------------------- USV
UsvStackConfig loadUsvStack(const std::string& dir) {
  const VehicleManifest m = VehicleManifest::load(dir, "usv");  // what usv.launch starts, with its files
  UsvStackConfig c;
  readRun(m.sources("sim"), c.sim);
  readSources(m.sources("navigation"), navigation::GpsNavigatorConfig::table(), c.navigation);
  const std::string vehicle = m.vehicleConfigPath();
  readParamsYaml(loadYamlFile(vehicle), sim::HullFootprint::table(), c.hull, vehicle);
  c.hull.validate();
  const std::vector<ParamSource> lidar = m.sources("lidar_targets");
  readSources(lidar, perception::LidarConfig::table(), c.lidar);
  for (const auto& s : lidar) readParamsYaml(s.yaml, perception::TrackerParams::table(), c.tracker, s.name, "tracker/");
  perception::SensorFrameParams f;
  readSources(lidar, perception::SensorFrameParams::table(), f);
  c.pose_timeout = f.tf_timeout;
  c.guidance = readGuidance(m.sources("guidance"));
  c.control = readControl(m.sources("control"));
  readSources(m.sources("mission"), mission::UsvMissionParams::table(), c.mission);
  readSafety(m.sources("safety"), c.safety, c.safety_rate);
  return c;
}

UsvStack::UsvStack(const sim::Scenario& scenario, const UsvStackConfig& cfg)
    : cfg_(cfg),
      sim_(scenario, cfg.sim),
      nav_(scenario.origin, cfg.navigation),  // in simulation the scenario is the site
      lidar_(cfg.lidar),
      tracker_(cfg.tracker),
      guidance_(cfg.guidance),
      control_(cfg.control),
      mission_(cfg.mission),
      safety_(cfg.safety, cfg.sim.dt, cfg.safety_rate),
      guidance_every_(stepsPer(cfg.guidance.rate, cfg.sim.dt)),
      control_every_(stepsPer(cfg.control.rate, cfg.sim.dt)),
      mission_every_(stepsPer(1.0 / cfg.mission_period, cfg.sim.dt)) {
  if (!cfg.safety.region.empty()) mission_.setRegion(safety::Region::fromList(cfg.safety.region));
  // the recovery distance is the bow's, a hold keeps the hull clear (as the nodelets read the outline)
  const guidance::HullReach reach{cfg.hull.ahead(), cfg.hull.astern(), cfg.hull.abeam()};
  mission_.setHullReach(reach);
  guidance_.setHullReach(reach);
}

void UsvStack::pathToGuidance() {
  if (auto p = mission_.takePath()) {
    std::vector<Eigen::Vector3d> path;
    for (const auto& w : *p) path.emplace_back(w.x(), w.y(), 0.0);
    guidance_.setPath(path);
    guidance_.setKnownObstacles(mission_.keepClear());
  }
}

void UsvStack::onTarget(const Eigen::Vector2d& ned, double t) {
  mission_.onTarget(ned, t);
  pathToGuidance();
}

void UsvStack::onAuvStatus(mission::AuvPhase phase, const Eigen::Vector3d& ned, bool stationary, double t) {
  mission_.onAuvStatus(phase, ned, stationary, t);
  safety_.core().heard(safety::Source::kLink, t);
  pathToGuidance();
}

void UsvStack::onPeerAlive(double t) {
  mission_.onPeerAlive(t);
  safety_.core().heard(safety::Source::kLink, t);
}

void UsvStack::perceive(double t) {
  // LidarTargets: each frame positioned with the navigation pose at its stamp (tf2's wait, then drop).
  while (!scans_.empty()) {
    const sim::LidarScan& scan = scans_.front();
    Eigen::Isometry3d body;
    if (!poses_.at(scan.t, body)) {
      if (t - scan.t > cfg_.pose_timeout) scans_.pop_front();  // dropped, as the nodelet does
      else break;
      continue;
    }
    sim::packCloud(scan, cloud_);
    // levelled with the sensor's IMU, as the nodelet does with its sensor_msgs/Imu (FLU: the FRD pitch negated)
    const perception::LidarResult r = lidar_.extract(viewOf(cloud_), perception::levelling(scan.roll, -scan.pitch));
    const Eigen::Isometry3d to_world = body * sim::sensorMount(cfg_.sim.lidar.mount, cfg_.sim.lidar.mount_yaw, false);
    obstacles_.clear();
    seen_.clear();
    std::vector<perception::Detection> detections;
    for (const auto& g : r.targets) {
      const perception::TargetGeometry w = perception::transformed(g, to_world);
      guidance::SbbObstacle o;
      o.origin = w.origin.head<2>();
      o.length = w.length;
      o.width = w.width;
      obstacles_.push_back(o);
      safety::SeenObstacle so;
      so.origin = o.origin;
      so.axis = w.axis.head<2>();
      so.length = w.length;
      so.width = w.width;
      seen_.push_back(so);
      detections.push_back({w.centroid.head<2>(), w.length, w.width});  // the nodelet's: the centroid
    }
    if (r.error == perception::CloudError::None) {
      // the LidarTargets nodelet's tracker on the frame's targets at its stamp; the tracks to guidance before the
      // targets, so that a vessel under way is not also boxed where it stands (as the Guidance nodelet takes them)
      if (tracker_.update(scan.t, detections) && cfg_.guidance.sbb_enabled) {
        std::vector<guidance::Contact> contacts;
        for (const perception::Track& tr : tracker_.tracks()) {
          guidance::Contact c;
          c.id = tr.id;
          c.position = tr.position();
          c.velocity = tr.velocity();
          c.covariance = tr.P;
          c.length = tr.length;
          c.width = tr.width;
          c.confirmed = tr.confirmed;
          contacts.push_back(c);
        }
        guidance_.setTracks(contacts, scan.t);
      }
      if (cfg_.guidance.sbb_enabled) guidance_.setObstacles(obstacles_, t);
    }
    scans_.pop_front();
  }
}

void UsvStack::checkCollision(double t) {
  if (!estimate_) return;
  const VehicleState& s = cfg_.use_truth ? sim_.state() : *estimate_;
  std::vector<safety::SafetyBoxView> boxes;
  for (const auto& b : guidance_.plan().boxes) {
    safety::SafetyBoxView v;
    for (int i = 0; i < 4; ++i) v.corners[i] = b.corners[i];
    v.cuts_path = b.cuts_path;
    v.blocked = b.side == guidance::SbbSide::kBlocked;
    boxes.push_back(v);
  }
  const Eigen::Vector2d p = s.position.head<2>(), v = Eigen::Rotation2Dd(s.yaw) * s.velocity.head<2>();
  const safety::Collision c = safety::timeToCollision(p, v, seen_, cfg_.safety.collision_radius);
  safety_.core().timeToCollision(t, c.ttc, safety::safeSideExists(boxes, p));
}

void UsvStack::step() {
  const sim::UsvSimulation::Outputs& out = sim_.step();
  const double t = sim_.state().t;
  ++step_;
  guided_ = false;
  gps_now_ = out.gps;
  safety::Supervisor& sup = safety_.core();  // fed as the SafetySupervisor nodelet is
  bool course = false;                       // the time to collision's inputs changed
  if (out.gps) {  // GpsNavigation: heading and velocity first, then the fix
    sup.heard(safety::Source::kGps, out.gps->t);
    nav_.heading(out.gps->t, out.gps->heading);
    nav_.velocity(out.gps->t, out.gps->velocity_ned, out.gps->rate_of_turn);
    if (auto e = nav_.fix(out.gps->t, out.gps->fix)) {
      estimate_ = e;
      const VehicleState& s = cfg_.use_truth ? sim_.state() : *e;
      poses_.add(s);
      guidance_.setState(s, t);
      control_.onState(s, t);
      if (cfg_.mission_enabled) mission_.onPose(s.position.head<2>(), s.yaw, s.t);
      sup.heard(safety::Source::kNavigation, t);
      sup.position(t, s.position.x(), s.position.y());
      course = true;
    }
  }
  if (out.gateway_changed) {  // what the CAN gateway would report (the simulator's stand-in)
    for (int i = 0; i < 2; ++i) sup.jetAnswering(t, i, sim_.gateway().answering[i]);
    sup.busOff(t, sim_.gateway().bus_off);
  }
  if (out.lidar) {
    scans_.push_back(sim_.scan());
    sup.heard(safety::Source::kLidar, t);
  }
  const std::size_t queued = scans_.size();
  perceive(t);
  course = course || scans_.size() < queued;
  if (cfg_.mission_enabled) {
    if (step_ % mission_every_ == 0) mission_.tick(t);
    pathToGuidance();
  }
  if (step_ % guidance_every_ == 0 && guidance_.update(t, guidance_every_ * cfg_.sim.dt, last_)) {
    guided_ = true;
    course = course || last_.boxes_changed;
    control_.onReference(last_.reference, t);
    // what guidance plans round, at each replan (the nodelet's guidance/obstacles)
    if (cfg_.mission_enabled && last_.boxes_changed) mission_.setObstacles(guidance_.plannedRound());
    if (cfg_.mission_enabled)
      mission_.onGuidance(last_.los.mode, last_.los.distance_to_go, t,
                          last_.reference.mode == ReferenceMode::kHold ? Eigen::Vector2d(last_.reference.point.head<2>())
                                                                       : mission::kNoPoint);
  }
  if (course) checkCollision(t);
  safety_.tick(step_, t, control_);
  if (step_ % control_every_ == 0) {
    command_ = control_.update(t);
    const auto& j = command_.joystick;
    sim_.setCommand(models::UsvCommand{j.surge, j.sway, j.yaw});
    sup.heard(safety::Source::kCommand, t);
  }
}

// ------------------------------------------------------------------------------------------------- AUV
AuvStackConfig loadAuvStack(const std::string& dir, const std::string& model, const std::string& scenario_file) {
  const VehicleManifest m = VehicleManifest::load(dir, "auv");  // what auv.launch starts, with its files
  m.requireModel(model);
  AuvStackConfig c;
  c.model = model;
  readRun(m.sources("sim", model), c.sim);
  const std::vector<ParamSource> sonar = m.sources("sonar_targets", model);
  readSources(sonar, perception::SonarConfig::table(), c.sonar);
  perception::SensorFrameParams f;
  readSources(sonar, perception::SensorFrameParams::table(), f);
  c.pose_timeout = f.tf_timeout;
  c.guidance = readGuidance(m.sources("guidance", model));
  c.control = readControl(m.sources("control", model));
  c.mission.coverage = mission::CoverageArea();
  const std::vector<ParamSource> mission = m.sources("mission", model);
  readSources(mission, mission::AuvMissionParams::table(), c.mission);
  // as auv.launch: the scenario's auv/coverage when it has one, else the mission config's
  const YAML::Node sc = scenario_file.empty() ? YAML::Node() : loadYamlFile(scenario_file);
  if (sc && yamlAt(sc, "auv/coverage").IsDefined()) {
    readParamsYaml(sc, mission::CoverageArea::table(), c.mission.coverage, scenario_file, "auv/coverage/");
  } else {
    for (const auto& s : mission) readParamsYaml(s.yaml, mission::CoverageArea::table(), c.mission.coverage, s.name, "coverage/");
  }
  c.mission.validate();
  readSafety(m.sources("safety", model), c.safety, c.safety_rate);
  c.usbl = loadUsblNavigation(m, model);
  c.usbl_seed = static_cast<unsigned>(c.usbl.beacon.seed);
  c.length = auvLength(m, model);
  c.sim.auv = model == "acolor" ? models::AuvParams::aColor() : models::AuvParams::girona500();
  return c;
}

double auvLength(const std::string& dir, const std::string& model) {
  const VehicleManifest m = VehicleManifest::load(dir, "auv");
  return auvLength(m, model);
}

double auvLength(const VehicleManifest& m, const std::string& model) {
  struct Vehicle {
    double length = 1.5;
  } v;
  static const ParamTable<Vehicle> table =
      ParamTable<Vehicle>().number("vehicle/length", &Vehicle::length, 0.1, 50.0, "m", "L_AUV");
  const std::string file = m.vehicleConfigPath(model);
  readParamsYaml(loadYamlFile(file), table, v, file);
  return v.length;
}

AuvStack::AuvStack(const sim::Scenario& scenario, const AuvStackConfig& cfg)
    : cfg_(cfg),
      sim_(scenario, cfg.sim),
      sonar_(cfg.sonar),
      guidance_(cfg.guidance),
      control_(cfg.control),
      mission_(cfg.mission),
      safety_(auvSafety(cfg), cfg.sim.dt, cfg.safety_rate),
      guidance_every_(stepsPer(cfg.guidance.rate, cfg.sim.dt)),
      control_every_(stepsPer(cfg.control.rate, cfg.sim.dt)),
      mission_every_(stepsPer(1.0 / cfg.mission_period, cfg.sim.dt)),
      navigation_every_(stepsPer(cfg.usbl.params.rate, cfg.sim.dt)) {
  if (cfg.navigation == "usbl")
    usbl_.emplace(cfg.usbl, geo::LocalNed(scenario.origin), cfg.usv_gps_antenna, cfg.usbl_seed, cfg.sim.faults);
}

void AuvStack::onUsvStatus(mission::UsvPhase phase, const Eigen::Vector2d& ned, const Eigen::Vector2d& station,
                           double t) {
  if (!cfg_.mission_enabled) return;
  mission_.onUsvStatus(phase, ned, station, t);
  if (auto p = mission_.takePath()) guidance_.setPath(*p);
}

void AuvStack::onUsvGps(const sim::GpsCompassReading& g) {
  if (!usbl_) return;
  usbl_->usvGps(g.t, g.fix);
  usbl_->usvHeading(g.t, g.heading);
}

void AuvStack::navigate(const VehicleState& est, double t) {
  estimate_ = est;
  const VehicleState& s = cfg_.use_truth ? sim_.state() : est;
  poses_.add(s);
  guidance_.setState(s, t);
  control_.onState(s, t);
  if (cfg_.mission_enabled) mission_.onPose(s.position, s.yaw, t);
  safety::Supervisor& sup = safety_.core();
  sup.heard(safety::Source::kNavigation, t);
  sup.position(t, s.position.x(), s.position.y());
  sup.depth(t, s.position.z());
}

void AuvStack::perceive() {
  // SonarTargets: each beam positioned with the navigation pose at its stamp; a sweep's targets to the mission.
  const double t = sim_.state().t;
  while (!beams_.empty()) {
    const sim::SonarBeamReading& b = beams_.front();
    const perception::SonarBeamView view = viewOf(b);
    Eigen::Isometry3d body;
    if (!sonar_.check(view)) {
      beams_.pop_front();
      continue;
    }
    if (!(b.head_status & (sim::kFault | sim::kCentring))) safety_.core().heard(safety::Source::kSonar, b.t);
    if (!poses_.at(b.t, body)) {
      if (t - b.t <= cfg_.pose_timeout) break;
      sonar_.counters().increment("no_transform");
      sonar_.breakRun();
      beams_.pop_front();
      continue;
    }
    const Eigen::Isometry3d head = body * sim::sensorMount(cfg_.sim.sonar.mount, 0.0, true, -cfg_.sim.sonar.tilt);
    sonar_.addBeam(view, head, head.translation().z());  // map_ned: z is the depth
    beams_.pop_front();
    if (!sonar_.sweepReady()) continue;
    const perception::SonarSweep sweep = sonar_.takeSweep();
    for (const auto& st : sweep.targets) {
      sonar_targets_.push_back(st);
      if (mission_.onDetection(st.geometry.origin, sweep.end_stamp)) break;
    }
  }
}

void AuvStack::step() {
  const sim::AuvSimulation::Outputs& out = sim_.step();
  const double t = sim_.state().t;
  ++step_;
  guided_ = false;
  safety::Supervisor& sup = safety_.core();  // fed as the SafetySupervisor nodelet is
  if (usbl_) {  // the Usbl and AuvNavigation nodelets
    if (out.depth) usbl_->depth(out.depth->t, out.depth->pressure_pa);
    if (out.ahrs) usbl_->ahrs(out.ahrs->t, out.ahrs->roll, out.ahrs->pitch, out.ahrs->yaw, out.ahrs->angular_rate);
    if (out.dvl) usbl_->dvl(out.dvl->t, out.dvl->velocity);
    usbl_->step(t, usv_truth_, sim_.state());
    if (out.gps) {  // /auv/gps/fix (sim::SurfaceGps): the AuvNavigation and AuvMission nodelets both take it
      usbl_->gpsFix(out.gps->t, out.gps->fix, out.gps->sigma);
      if (cfg_.mission_enabled) mission_.onSurfaceFix(out.gps->t);
    }
    for (double s : usbl_->acceptedNow()) sup.heard(safety::Source::kUsbl, s);
    if (step_ % navigation_every_ == 0) {
      const bool fix_lost = usbl_->status(t) == navigation::NavStatus::kFixLost;  // /auv/navigation/status
      control_.onFixLost(fix_lost);
      if (cfg_.mission_enabled) mission_.onFixLost(fix_lost);
      if (auto e = usbl_->estimate(t)) navigate(*e, t);
    }
  } else if (out.odom) {  // the simulator's INS estimate: /auv/odom and its TF
    navigate(*out.odom, t);
  }
  if (out.depth) sup.heard(safety::Source::kDepth, t);
  if (out.sonar) beams_.push_back(sim_.beam());
  perceive();
  if (cfg_.mission_enabled) {
    if (step_ % mission_every_ == 0) mission_.tick(t);
    if (auto p = mission_.takePath()) guidance_.setPath(*p);
    if (auto tg = mission_.takeTarget()) target_ = tg;
  }
  if (step_ % guidance_every_ == 0 && guidance_.update(t, guidance_every_ * cfg_.sim.dt, last_)) {
    guided_ = true;
    control_.onReference(last_.reference, t);
    if (cfg_.mission_enabled) {
      mission_.onGuidance(last_.los.mode, t);
      if (auto p = mission_.takePath()) guidance_.setPath(*p);
    }
  }
  safety_.tick(step_, t, control_);
  if (cfg_.mission_enabled && surfaces(safety_.decision())) {
    mission_.onSafetySurface(t);
    if (auto p = mission_.takePath()) guidance_.setPath(*p);
  }
  if (step_ % control_every_ == 0) {
    sup.heard(safety::Source::kCommand, t);
    command_ = control_.update(t);
    if (usbl_) usbl_->commandedVelocity(t, command_.water_velocity);  // /auv/commanded_velocity
    if (cfg_.model == "girona500") {
      const auto& sp = command_.thrusters.alloc.setpoint;
      sim_.setThrusters(std::vector<double>(sp.data(), sp.data() + sp.size()));
    } else {
      sim_.setRcChannels(command_.rc);
    }
  }
}

}  // namespace closed_loop
}  // namespace offshore_gnc
