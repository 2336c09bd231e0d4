#include "offshore_gnc/closed_loop/closed_loop.h"

#include <cmath>

namespace offshore_gnc {
namespace closed_loop {

namespace {

sim::Scenario scenarioOf(const ClosedLoopConfig& cfg) {
  sim::Scenario sc;
  sc.name = "closed_loop";
  sc.sea = models::seaState(cfg.sea_state);
  sc.sea.current_north = cfg.current.x();
  sc.sea.current_east = cfg.current.y();
  sc.usv = {cfg.start.x(), cfg.start.y(), cfg.start_yaw};
  sc.auv = {cfg.start.x(), cfg.start.y(), cfg.start.z(), cfg.start_yaw};
  sc.world.buoys = cfg.buoys;
  return sc;
}

// Runs a stack along the route and measures it the way the mission report does.
template <class Stack>
ClosedLoopResult follow(const ClosedLoopConfig& cfg, Stack& stack) {
  ClosedLoopResult res;
  stack.setRoute(cfg.path);
  std::vector<double> xte;
  double finished_at = -1.0;
  while (stack.time() < cfg.max_time) {
    stack.step();
    const guidance::GuidanceOutput* g = stack.guidanceStep();
    if (!g) continue;
    const double t = stack.time();
    const VehicleState& truth = stack.truth();
    if (g->los.mode == guidance::Mode::kFollowPath) xte.push_back(g->los.cross_track_error);
    if (g->planned_changed && (stack.guidance().plan().modified || res.planned_path.empty()))
      res.planned_path = stack.guidance().plannedPath();
    if (g->los.mode == guidance::Mode::kStationKeeping && finished_at < 0.0) finished_at = t;
    res.track.push_back(truth.position);
    for (const auto& b : cfg.buoys)
      res.min_clearance = std::min(res.min_clearance, (truth.position.head<2>() - b.centre).norm() - b.radius);
    for (const auto& b : stack.guidance().plan().boxes)
      if (b.cuts_path && b.contains(truth.position.head<2>())) ++res.inside_box_samples;
    if (finished_at >= 0.0 && t - finished_at >= 30.0) {
      const Eigen::Vector3d d = truth.position - stack.guidance().plannedPath().back();
      res.hold_error = std::max(res.hold_error, std::hypot(d.x(), d.y()));
    }
    if (finished_at >= 0.0 && t - finished_at >= cfg.hold_until) break;
  }
  res.finished = finished_at >= 0.0;
  res.time = finished_at;
  res.metrics = guidance::computeMetrics(xte);
  res.status = stack.guidance().plan().boxes.empty() ? (res.finished ? "finished" : "timeout")
                                                      : stack.guidance().plan().status;
  return res;
}

}  // namespace

ClosedLoopResult runUsv(const ClosedLoopConfig& cfg) {
  UsvStackConfig c = loadUsvStack(cfg.config_dir);
  c.sim.seed = cfg.seed;
  c.mission_enabled = false;
  c.use_truth = !cfg.navigation;
  if (cfg.usv) cfg.usv(c);
  UsvStack stack(scenarioOf(cfg), c);
  ClosedLoopResult r = follow(cfg, stack);
  r.rejected_commands = stack.simulation().counters().get("rejected_commands");
  return r;
}

ClosedLoopResult runAuv(const ClosedLoopConfig& cfg, const std::string& model) {
  AuvStackConfig c = loadAuvStack(cfg.config_dir, model);
  c.sim.seed = cfg.seed;
  c.sim.sonar_on = false;
  c.navigation = "ins";  // a route alone, no USV to place USBL fixes: the simulator's INS-like estimate
  c.mission_enabled = false;
  c.use_truth = !cfg.navigation;
  if (cfg.auv) cfg.auv(c);
  AuvStack stack(scenarioOf(cfg), c);
  ClosedLoopResult r = follow(cfg, stack);
  r.rejected_commands = stack.simulation().modelCounters().get("rejected_commands");
  return r;
}

}  // namespace closed_loop
}  // namespace offshore_gnc
