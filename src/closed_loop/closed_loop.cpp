#include "offshore_gnc/closed_loop/closed_loop.h"

#include <cmath>

#include "offshore_gnc/navigation/gps_navigator.h"
#include "offshore_gnc/sim/simulation.h"

namespace offshore_gnc {
namespace closed_loop {

namespace {

sim::Scenario scenarioOf(const ClosedLoopConfig& cfg) {
  sim::Scenario sc;
  sc.name = "closed_loop";
  sc.current.north = cfg.current.x();
  sc.current.east = cfg.current.y();
  sc.current.variation = 0.0;
  sc.usv = {cfg.start.x(), cfg.start.y(), cfg.start_yaw};
  sc.auv = {cfg.start.x(), cfg.start.y(), cfg.start.z(), cfg.start_yaw};
  for (const auto& o : cfg.obstacles) {
    sim::Buoy b;
    b.centre = o.origin;
    b.radius = std::max(o.length, o.width) / 2.0;
    sc.world.buoys.push_back(b);
  }
  return sc;
}

// Shared loop: `apply(state, ref)` applies the controller; `navigate(outputs)` turns the plant's sensor outputs of
// one simulation step into a new navigation estimate (or nothing).
template <typename Plant, typename Apply, typename Navigate>
ClosedLoopResult run(const ClosedLoopConfig& cfg, Plant& plant, Apply apply, Navigate navigate) {
  ClosedLoopResult res;
  guidance::LosGuidance los(cfg.los);
  std::vector<Eigen::Vector3d> path = cfg.path;
  std::vector<bool> detour;
  std::vector<guidance::SbbBox> boxes;
  if (!cfg.obstacles.empty()) {
    const auto plan = guidance::planSbb(cfg.path, cfg.start.head<2>(), cfg.obstacles, cfg.sbb);
    path = plan.path;
    detour = plan.detour;
    boxes = plan.boxes;
    res.status = plan.status;
  }
  res.planned_path = path;
  los.setPath(path, false, detour);
  const int sub = std::max(1, static_cast<int>(std::lround(cfg.control_dt / plant.dt())));
  std::vector<double> xte;
  double finished_at = -1.0;
  VehicleState estimate = plant.state();  // until the first navigation output (the vehicle starts at rest)
  for (double t = 0.0; t < cfg.max_time; t += cfg.control_dt) {
    const VehicleState truth = plant.state();  // velocity over ground, as GPS / DVL navigation reports it
    const VehicleState s = cfg.navigation ? estimate : truth;
    const guidance::LosOutput o = los.update(s, cfg.control_dt);
    if (o.mode == guidance::Mode::kFollowPath) xte.push_back(o.cross_track_error);
    if (o.mode == guidance::Mode::kStationKeeping && finished_at < 0.0) finished_at = t;
    res.track.push_back(truth.position);
    for (const auto& ob : cfg.obstacles)
      res.min_clearance = std::min(
          res.min_clearance, (truth.position.head<2>() - ob.origin).norm() - std::max(ob.length, ob.width) / 2.0);
    for (const auto& b : boxes)
      if (b.cuts_path && b.contains(truth.position.head<2>())) ++res.inside_box_samples;
    if (!apply(s, guidance::referenceOf(o))) ++res.nan_outputs;
    for (int i = 0; i < sub; ++i)
      if (auto e = navigate(plant.step())) estimate = *e;
    // Station keeping: the largest distance from the last waypoint once settled (30 s to hold_until after the end).
    if (finished_at >= 0.0 && t - finished_at >= 30.0) {
      const Eigen::Vector3d d = plant.state().position - path.back();
      res.hold_error = std::max(res.hold_error, std::hypot(d.x(), d.y()));
    }
    if (finished_at >= 0.0 && t - finished_at >= cfg.hold_until) break;
  }
  res.finished = finished_at >= 0.0;
  res.time = finished_at;
  res.metrics = guidance::computeMetrics(xte);
  if (res.status.empty()) res.status = res.finished ? "finished" : "timeout";
  return res;
}

}  // namespace

ClosedLoopResult runUsv(const ClosedLoopConfig& cfg, const control::UsvControlParams& ctrl_p) {
  sim::UsvSimulation::Config sc;
  sc.seed = cfg.seed;
  sc.lidar_on = false;
  const sim::Scenario scenario = scenarioOf(cfg);
  sim::UsvSimulation plant(scenario, sc);
  control::UsvControlParams p = ctrl_p;
  p.dt = cfg.control_dt;
  control::UsvController ctrl(p);
  navigation::GpsNavigatorConfig nc;  // as the GpsNavigation nodelet: the antenna's lever arm removed
  nc.antenna = sc.gps.antenna;
  navigation::GpsNavigator nav(scenario.origin, nc);
  return run(
      cfg, plant,
      [&](const VehicleState& s, const MotionReference& r) {
        const control::JoystickOut j = ctrl.update(s, r);
        const bool finite = std::isfinite(j.surge) && std::isfinite(j.sway) && std::isfinite(j.yaw);
        plant.setCommand(models::UsvCommand{j.surge, j.sway, j.yaw});
        return finite;
      },
      [&](const sim::UsvSimulation::Outputs& out) -> std::optional<VehicleState> {
        if (!out.gps) return std::nullopt;
        nav.heading(out.gps->t, out.gps->heading);
        nav.velocity(out.gps->t, out.gps->velocity_ned, out.gps->rate_of_turn);
        return nav.fix(out.gps->t, out.gps->fix);
      });
}

ClosedLoopResult runGirona500(const ClosedLoopConfig& cfg, const control::Girona500ControlParams& ctrl_p) {
  sim::AuvSimulation::Config sc;
  sc.seed = cfg.seed;
  sc.sonar_on = false;
  sim::AuvSimulation plant(scenarioOf(cfg), sc);
  control::Girona500ControlParams p = ctrl_p;
  p.dt = cfg.control_dt;
  control::Girona500Controller ctrl(p);
  return run(
      cfg, plant,
      [&](const VehicleState& s, const MotionReference& r) {
        const control::Girona500Out out = ctrl.update(s, r);
        const auto& sp = out.alloc.setpoint;
        const bool finite = sp.allFinite();
        plant.setThrusters(std::vector<double>(sp.data(), sp.data() + sp.size()));
        return finite;
      },
      [](const sim::AuvSimulation::Outputs& out) { return out.odom; });
}

}  // namespace closed_loop
}  // namespace offshore_gnc
