#include "offshore_gnc/closed_loop/mission.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace closed_loop {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The relayed messages' sizes on the radio: the relay's frame (32 bytes of header, a 32-byte HMAC, the topic's
// name) around the serialised message. /usv_gps (NavSatFix, 123 bytes) and /usv_heading (QuaternionStamped, 55)
// go as one here (one reading, so they are lost together); /target (Target, about 200 bytes).
// Each vehicle's /mission/status (MissionStatus, about 150 bytes with its phase and reason strings) crosses too.
constexpr std::size_t kUsvPoseBytes = (64 + 8 + 123) + (64 + 12 + 55), kTargetBytes = 64 + 7 + 200;
constexpr std::size_t kStatusBytes = 64 + 20 + 150;

// As report.split_tracking: the true position's distance from the leg guidance followed, the line through the
// estimate's projection on it along the leg's angle (e positive to starboard; NaN off a leg). Not
// plannedPath()[k-1..k]: LOS merges waypoints closer than min_leg_length, so its leg index need not count the planned
// path's waypoints.
double trueCrossTrack(const guidance::GuidanceOutput& g, const VehicleState& truth) {
  double e = kNaN;
  if (g.reference.mode == ReferenceMode::kFollow)
    guidance::legGeometry(g.reference.point.head<2>(),
                          g.reference.point.head<2>() + Eigen::Vector2d(std::cos(g.reference.path_angle),
                                                                        std::sin(g.reference.path_angle)),
                          truth.position.head<2>(), &e, nullptr);
  return e;
}

// g: guidance's step (nullptr: none); its cross-track counts only while tracking (the USV's transit, the AUV's search).
void record(VehicleRecord& r, const VehicleState& truth, long step, const guidance::GuidanceOutput* g,
            const guidance::GuidancePipeline& pipeline, bool tracking = true) {
  if (step % 5 == 0) r.truth.emplace_back(truth.t, truth.position.x(), truth.position.y(), truth.position.z());
  if (!g) return;
  if (tracking && g->los.mode == guidance::Mode::kFollowPath) {
    r.xte.emplace_back(truth.t, g->los.cross_track_error);
    const double e_truth = trueCrossTrack(*g, truth);
    r.xte_truth.emplace_back(truth.t, e_truth);
    if (g->los.active_leg >= 2) {
      r.xte_tracking.emplace_back(truth.t, g->los.cross_track_error);
      r.xte_tracking_truth.emplace_back(truth.t, e_truth);
    } else {
      r.xte_approach_truth.emplace_back(truth.t, e_truth);
    }
  }
  if (g->planned_changed && pipeline.plannedPath().size() > r.planned.size()) r.planned = pipeline.plannedPath();
  if (g->boxes_changed) r.boxes = pipeline.plan().boxes;
}

// Nearest-rank percentile (as python/offshore_gnc/report.py); NaN for no samples.
double percentile(std::vector<double> v, double q) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::clamp<std::size_t>(k, 1, v.size()) - 1];
}

guidance::TrackingMetrics metricsOf(const std::vector<Eigen::Vector2d>& samples) {
  std::vector<double> e;
  for (const auto& s : samples) e.push_back(s.y());
  guidance::TrackingMetrics m = guidance::computeMetrics(e);  // NaN samples (no leg) skipped
  if (m.samples == 0) m.rmse = m.sd = m.mae = m.max_abs = m.mean = kNaN;  // nothing measured: unknown, not zero
  return m;
}

// The truth (t, north, east, down) at t, linear between its samples; nothing outside their span.
std::optional<Eigen::Vector3d> truthAt(const std::vector<Eigen::Vector4d>& truth, double t) {
  if (truth.empty() || t < truth.front()(0) || t > truth.back()(0)) return std::nullopt;
  const auto b = std::lower_bound(truth.begin(), truth.end(), t,
                                  [](const Eigen::Vector4d& s, double v) { return s(0) < v; });
  if (b == truth.begin() || (*b)(0) == t) return b->tail<3>();
  const auto a = b - 1;
  const double w = (t - (*a)(0)) / ((*b)(0) - (*a)(0));
  return Eigen::Vector3d(a->tail<3>() + w * (b->tail<3>() - a->tail<3>()));
}

// As report.usbl_verdicts: each fix's verdict (fused, gated by the filter, or the positioning's rejection) and its
// distance from the truth at its stamp.
UsblFixScores scoreFixes(const std::vector<UsblFixRecord>& fixes, const std::vector<Eigen::Vector4d>& truth) {
  UsblFixScores s;
  s.received = fixes.size();
  for (const auto& f : fixes) {
    const std::string verdict = f.verdict();
    const std::optional<Eigen::Vector3d> p = truthAt(truth, f.t);
    const bool placed = p && f.ned.allFinite();
    const bool outlier = placed && (f.ned - *p).norm() > kUsblOutlierM;
    s.outliers += outlier;
    if (verdict == "fused") {
      s.outliers_accepted += outlier;
      continue;
    }
    ++s.rejected;
    ++s.rejected_by[verdict];
    s.rejected_outliers += outlier;
    if (verdict == "filter_error" || verdict == "fit_error" || verdict == "depth" || verdict == "gated") {
      ++s.by_gates;
      s.by_gates_outliers += outlier;
      s.by_gates_unplaced += !placed;
    }
  }
  return s;
}

void finish(VehicleRecord& r, const std::string& phase) {
  r.metrics = metricsOf(r.xte);
  r.metrics_truth = metricsOf(r.xte_truth);
  r.tracking = metricsOf(r.xte_tracking);
  r.tracking_truth = metricsOf(r.xte_tracking_truth);
  r.approach_truth = metricsOf(r.xte_approach_truth);
  r.final_phase = phase;
}
}  // namespace

MissionConfig loadMission(const std::string& config_dir, const std::string& scenario_file,
                          const std::string& auv_model) {
  MissionConfig c;
  c.scenario_file = scenario_file;
  c.scenario = sim::loadScenario(scenario_file);
  c.usv = loadUsvStack(config_dir);
  c.auv = loadAuvStack(config_dir, auv_model, scenario_file);
  c.auv.usv_gps_antenna = c.usv.sim.gps.antenna;  // the USBL's mounting is from the point /usv_gps reports
  c.radio = sim::loadRadioParams(config_dir + "/relay/radio.yaml");
  return c;
}

namespace {
// What each mission's status carries across the radio (MissionStatus on the relay).
struct UsvStatusMsg {
  mission::UsvPhase phase;
  Eigen::Vector2d position, station;
};
struct AuvStatusMsg {
  mission::AuvPhase phase;
  Eigen::Vector3d position;
  bool stationary;
};

// The ascent's drift counts once the AUV has risen this much from where it began: before, it may be moving clear
// of the USV at depth (AuvMission's surface_clearance) [m].
constexpr double kRisen = 0.3;

void keepMax(double& m, double v) { m = std::isnan(m) ? v : std::max(m, v); }

template <class Phase>
void notePhase(VehicleRecord& r, double t, Phase p) {
  const std::string name = mission::toString(p);
  if (r.phases.empty() || r.phases.back().second != name) r.phases.emplace_back(t, name);
}
}  // namespace

MissionResult runMission(const MissionConfig& cfg) {
  const auto w0 = std::chrono::steady_clock::now();
  MissionResult res;
  UsvStack usv(cfg.scenario, cfg.usv);
  AuvStack auv(cfg.scenario, cfg.auv);
  // the relay's topics over the radio: /usv_gps and /usv_heading to the AUV (best effort), /target back (reliable),
  // each mission's status to the other (best effort, every mission period)
  RadioLink<sim::GpsCompassReading> to_auv(cfg.radio, 4 * cfg.radio_seed - 3);
  RadioLink<Eigen::Vector3d> to_usv(cfg.radio, 4 * cfg.radio_seed - 2);
  RadioLink<UsvStatusMsg> usv_status(cfg.radio, 4 * cfg.radio_seed - 1);
  RadioLink<AuvStatusMsg> auv_status(cfg.radio, 4 * cfg.radio_seed);
  const int status_every = stepsPer(1.0 / cfg.usv.mission_period, cfg.usv.sim.dt);
  long step = 0;
  double t = 0.0;
  std::optional<Eigen::Vector2d> wait_start;  // where the USV started waiting for the target
  bool target_delivered = false, held = false;
  double ascent_depth = kNaN;  // the AUV's true depth when its ascent began
  res.auv_hold_point = Eigen::Vector3d::Constant(kNaN);
  std::vector<double> hold_error, recovery_hold_error, nav_error;  // the USV's at the target, and beside the AUV
  std::vector<Eigen::Vector2d> recovery_xte;                       // (t, e true) on the recovery's legs
  res.usv_wait_drift_m = kNaN;
  res.reason = "simulated time limit reached";
  res.min_clearance_m = res.usv_auv_min_clearance_m = std::numeric_limits<double>::infinity();
  res.auv_hold_excursion_m = res.auv_ascent_drift_m = res.auv_surface_excursion_m = kNaN;
  std::pair<double, std::string> closest;  // when the hull came closest to what
  sim::World traffic;                       // the vessels under way
  for (const auto& v : cfg.scenario.world.vessels)
    if (v.motion.kind != sim::VesselMotion::Kind::kMoored) traffic.vessels.push_back(v);
  double auv_closest_t = kNaN;              // and to the AUV near the surface
  // where the USV held at the target: its true position at the last step of ARRIVED (it then leaves for the AUV)
  std::optional<Eigen::Vector2d> usv_station_end;
  const sim::Scenario::Mission& judge = cfg.scenario.mission;
  const Fault* geofence = nullptr;
  for (const auto& f : cfg.link_faults.faults())
    if (f.name == "geofence") geofence = &f;
  bool geofence_sent = false;
  const bool kills = cfg.kill == "usv" || cfg.kill == "auv";
  double end = judge.max_sim_time;
  for (; t <= end; ++step) {
    if (kills && res.stack_died.empty() && t >= cfg.kill_at) {  // SIGKILL: the stack stops where it is
      res.stack_died = cfg.kill;
      end = std::min(end, t + cfg.after_kill);
    }
    const bool usv_alive = res.stack_died != "usv", auv_alive = res.stack_died != "auv";
    const bool link_up = !cfg.link_faults.active("link", t) && usv_alive && auv_alive;  // a dead relay: no link
    to_auv.setUp(link_up);
    to_usv.setUp(link_up);
    usv_status.setUp(link_up);
    auv_status.setUp(link_up);
    if (usv_alive) {
      usv.step();
      if (usv.gpsNow()) to_auv.send(usv.time(), *usv.gpsNow(), kUsvPoseBytes, false);
    }
    t = usv_alive ? usv.time() : t + cfg.usv.sim.dt;
    if (auv_alive) {
      for (const auto& g : to_auv.receive(t)) auv.onUsvGps(g);
      auv.setUsvTruth(usv.truth());  // the simulated acoustic channel
      auv.step();
    }
    if (link_up) {  // the relays' link status
      usv.onPeerAlive(t);
      auv.onPeerAlive(t);
    }
    if (geofence && !geofence_sent && t >= geofence->start) {  // the phantom arrives as a relayed /target would
      usv.onTarget(Eigen::Vector2d(kGeofenceTargetNorth, 0.0), t);
      geofence_sent = true;
    }
    if (auto tg = auv.takeTarget()) {
      res.target = *tg;  // the last one the AUV sent (refined while it holds)
      to_usv.send(t, *tg, kTargetBytes, true);
    }
    if (step % status_every == 0) {  // each mission's status, as its nodelet's timer publishes it
      const mission::UsvMission& um = usv.mission();
      const mission::AuvMission& am = auv.mission();
      if (usv_alive && um.pose())
        usv_status.send(t, {um.phase(), *um.pose(), um.stationPoint() ? *um.stationPoint() : mission::kNoPoint},
                        kStatusBytes, false);
      if (auv_alive && am.pose()) auv_status.send(t, {am.phase(), *am.pose(), am.stationary()}, kStatusBytes, false);
    }
    for (const auto& m : usv_status.receive(t)) auv.onUsvStatus(m.phase, m.position, m.station, t);
    for (const auto& m : auv_status.receive(t)) usv.onAuvStatus(m.phase, m.position, m.stationary, t);
    for (const auto& tg : to_usv.receive(t)) {
      usv.onTarget(tg.head<2>(), t);
      target_delivered = true;
    }
    if (!usv.mission().refusal().empty() && (res.target_refusals.empty() || res.target_refusals.back() != usv.mission().refusal()))
      res.target_refusals.push_back(usv.mission().refusal());
    const Eigen::Vector2d usv_ne = usv.truth().position.head<2>();
    if (!target_delivered && usv.mission().phase() == mission::UsvPhase::StationKeeping) {
      if (!wait_start) wait_start = usv_ne, res.usv_wait_drift_m = 0.0;
      res.usv_wait_drift_m = std::max(res.usv_wait_drift_m, (usv_ne - *wait_start).norm());
    }
    notePhase(res.usv, t, usv.mission().phase());
    notePhase(res.auv, t, auv.mission().phase());
    // the USV's path following is its transit to the target (Table 5.1's figure); the recovery's short legs round the
    // AUV, entered and cut by the 16 m circle of acceptance, are reported apart
    const auto usv_phase = usv.mission().phase();
    const guidance::GuidanceOutput* usv_g = usv_alive ? usv.guidanceStep() : nullptr;
    record(res.usv, usv.truth(), step, usv_g, usv.guidance(), usv_phase == mission::UsvPhase::Transit);
    if (usv_g && usv_g->planned_changed) {
      MissionResult::Plan plan{t, usv.guidance().plan().status, {}, usv.guidance().plannedRound()};
      for (const auto& w : usv.guidance().plannedPath()) plan.path.push_back(w.head<2>());
      res.usv_plans.push_back(std::move(plan));
    }
    if (usv_g && usv_phase == mission::UsvPhase::Recovery && usv_g->los.mode == guidance::Mode::kFollowPath)
      recovery_xte.emplace_back(t, trueCrossTrack(*usv_g, usv.truth()));
    const VehicleState& ax = auv.truth();
    if (step % 5 == 0) {  // the hull against every true shape, a fault's obstacle included, and the AUV, at 20 Hz
      const auto& fault = usv.simulation().faultObstacle();
      std::string what;
      const double c = sim::hullClearance(cfg.usv.hull, usv_ne, usv.truth().yaw, cfg.scenario.world, t,
                                          fault ? std::vector<sim::Vessel>{*fault} : std::vector<sim::Vessel>{}, &what);
      if (c < res.min_clearance_m) {
        res.min_clearance_m = c;
        closest = {t, what};
      }
      if (!traffic.vessels.empty()) {
        const double ct = sim::hullClearance(cfg.usv.hull, usv_ne, usv.truth().yaw, traffic, t);
        if (!(ct >= res.traffic_min_clearance_m)) res.traffic_min_clearance_m = ct;  // NaN at first
      }
      res.recovery_distance_m = auvClearance(cfg.usv.hull, usv_ne, usv.truth().yaw, ax.position.head<2>(), cfg.auv.length);
      if (ax.position.z() < kAuvContactDepth && res.recovery_distance_m < res.usv_auv_min_clearance_m) {
        res.usv_auv_min_clearance_m = res.recovery_distance_m;
        auv_closest_t = t;
      }
    }
    if (step % 5 == 0 && usv_alive) {
      const VehicleState& x = usv.truth();
      const MotionReference& ref = usv.lastGuidance().reference;
      const control::JoystickOut& j = usv.command().joystick;
      const auto& los = usv.lastGuidance().los;
      const control::DpOutput& dp = usv.control().usvController()->stationKeeping();
      res.usv_trace.push_back({x.t, x.position.x(), x.position.y(), x.yaw, x.velocity.x(), x.velocity.y(),
                               x.angular_rate.z(), static_cast<double>(ref.mode), ref.point.x(), ref.point.y(),
                               ref.heading, los.mode == guidance::Mode::kFollowPath ? los.cross_track_error : kNaN,
                               j.surge, j.sway, j.yaw, dp.heading, dp.steady_force.x(), dp.steady_force.y(),
                               dp.distance});
    }
    // the AUV's tracking counts in its search (the hold and ascent paths' lead-ins are no search legs), as the report's
    record(res.auv, ax, step, auv_alive && !auv.mission().searchOver() ? auv.guidanceStep() : nullptr, auv.guidance());
    if (step % 5 == 0 && auv_alive) {
      const Eigen::Vector3d e = auv.estimate() ? auv.estimate()->position : Eigen::Vector3d::Constant(kNaN);
      const MotionReference& ref = auv.lastGuidance().reference;
      const Eigen::Vector4d tau =
          cfg.auv.model == "girona500" ? auv.command().thrusters.tau : Eigen::Vector4d::Constant(kNaN);
      res.auv_trace.push_back({ax.t, ax.position.x(), ax.position.y(), ax.position.z(), ax.yaw, e.x(), e.y(), e.z(),
                               static_cast<double>(ref.mode), ref.point.x(), ref.point.y(), ref.depth, ref.heading,
                               tau(0), tau(1), tau(2), tau(3)});
    }
    const mission::AuvMission& am = auv.mission();
    if (auv.estimate() && auv.estimate()->t >= t - 1e-9 && !am.searchOver())  // a new /auv/odom, searching
      nav_error.push_back((auv.estimate()->position.head<2>() - ax.position.head<2>()).norm());
    // the AUV keeping the spot: its true position from the hold point, from on station there until the ascent
    if (am.phase() == mission::AuvPhase::TargetFound) {
      res.auv_hold_point = am.holdPoint();
      if (t >= am.onStationSince()) keepMax(res.auv_hold_excursion_m, (ax.position - am.holdPoint()).norm());
    }
    // coming up: from the surfacing point, once it has risen (a move clear of the USV at depth comes first)
    if (am.phase() == mission::AuvPhase::Ascent) {
      if (std::isnan(ascent_depth)) ascent_depth = ax.position.z();
      if (ax.position.z() < ascent_depth - kRisen)
        keepMax(res.auv_ascent_drift_m, (ax.position.head<2>() - am.holdPoint().head<2>()).norm());
    }
    // holding at the surface (waiting for the USV, or beside it): from the point it holds there
    if (am.phase() == mission::AuvPhase::Surfaced || am.phase() == mission::AuvPhase::Recovered)
      keepMax(res.auv_surface_excursion_m, (ax.position.head<2>() - am.holdPoint().head<2>()).norm());
    // the USV on station: at the target, and at its recovery point
    const mission::UsvMission& um = usv.mission();
    held = held || um.arrived();
    if (um.phase() == mission::UsvPhase::Arrived) usv_station_end = usv_ne;
    const auto ph = um.phase();
    if ((ph == mission::UsvPhase::Arrived || ph == mission::UsvPhase::Recovery || ph == mission::UsvPhase::Recovered) &&
        t >= um.onStationSince()) {
      const auto* g = usv.guidanceStep();
      if (g && g->reference.mode == ReferenceMode::kHold)
        (ph == mission::UsvPhase::Arrived ? hold_error : recovery_hold_error)
            .push_back((usv_ne - g->reference.point.head<2>()).norm());
    }
    if (um.phase() == mission::UsvPhase::Recovered) {
      res.recovered = true;
      res.reason = "the AUV is recovered: " + um.detail();
      break;
    }
  }
  const mission::AuvMission& am = auv.mission();
  const mission::UsvMission& um = usv.mission();
  if (!res.recovered) {
    if (!res.stack_died.empty())
      res.reason = "the " + res.stack_died + " stack was killed at " + std::to_string(cfg.kill_at) + " s; the " +
                   (res.stack_died == "usv" ? std::string("AUV: ") + mission::toString(am.phase()) + " (" + am.detail()
                                            : std::string("USV: ") + mission::toString(um.phase()) + " (" + um.detail()) +
                   ")";
    else if (am.searchOver())
      res.reason += ": the AUV is " + std::string(mission::toString(am.phase())) + " (" + am.detail() + "), the USV " +
                    mission::toString(um.phase());
  }
  finish(res.usv, mission::toString(um.phase()));
  finish(res.auv, mission::toString(am.phase()));
  res.sim_time_s = t;
  res.usv_safety = usv.supervisor().transitions();
  res.auv_safety = auv.supervisor().transitions();
  res.usv_hold_p95_m = percentile(hold_error, 0.95);
  res.usv_recovery_hold_p95_m = percentile(recovery_hold_error, 0.95);
  res.usv_recovery_xte_truth = metricsOf(recovery_xte);
  const guidance::TrackingMetrics nav = guidance::computeMetrics(nav_error);
  res.auv_nav_rmse_m = nav.rmse;
  res.auv_nav_max_m = nav_error.empty() ? kNaN : *std::max_element(nav_error.begin(), nav_error.end());
  if (const UsblNavigation* u = auv.usblNavigation()) {
    res.usbl = scoreFixes(u->fixes(), res.auv.truth);
    res.usbl_fixes = u->fixes();
    res.usbl.multipath_replies = u->beaconCounters().get("multipath");
  }
  res.relay_lost = to_auv.lost() + to_usv.lost() + usv_status.lost() + auv_status.lost();

  const auto& targets = cfg.scenario.world.targets;
  res.target_error_m = res.usv_final_distance_to_target_m = kNaN;
  if (res.target && !targets.empty()) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& tt : targets) best = std::min(best, (res.target->head<2>() - tt.position.head<2>()).norm());
    res.target_error_m = best;
  }
  if (!targets.empty()) {  // where it held at the target, else where it is now
    const Eigen::Vector2d at = usv_station_end ? *usv_station_end : Eigen::Vector2d(usv.truth().position.head<2>());
    double best = std::numeric_limits<double>::infinity();
    for (const auto& tt : targets) best = std::min(best, (at - tt.position.head<2>()).norm());
    res.usv_final_distance_to_target_m = best;
  }
  res.detection_time_s = am.detectionTime();
  if (std::isinf(res.min_clearance_m)) res.min_clearance_m = kNaN;  // nothing in the water
  if (std::isinf(res.usv_auv_min_clearance_m)) res.usv_auv_min_clearance_m = kNaN;
  res.found_at_s = am.searchEndedAt();
  res.ascent_at_s = am.ascentStart();
  res.surfaced_at_s = am.surfacedAt();
  res.recovered_at_s = um.recoveredAt();
  res.find_to_recovery_s = res.recovered_at_s - res.found_at_s;
  res.auv_surface_point = std::isnan(res.surfaced_at_s) ? Eigen::Vector2d(kNaN, kNaN) : Eigen::Vector2d(am.holdPoint().head<2>());
  res.recovery_point = um.recoveryPoint();

  OutcomeFacts f;
  f.expect_target = judge.expect_target;
  f.held = held;
  f.recovered = res.recovered;
  f.auv_no_target = am.noTarget();
  f.target_reported = res.target.has_value();
  f.target_error_m = res.target_error_m;
  f.target_tolerance_m = judge.target_tolerance;
  f.final_distance_m = res.usv_final_distance_to_target_m;
  f.station_tolerance_m = cfg.usv.mission.standoff + judge.target_tolerance;
  f.min_clearance_m = std::isnan(res.min_clearance_m) ? std::numeric_limits<double>::infinity() : res.min_clearance_m;
  f.auv_clearance_m = std::isnan(res.usv_auv_min_clearance_m) ? std::numeric_limits<double>::infinity()
                                                              : res.usv_auv_min_clearance_m;
  f.stack_died = !res.stack_died.empty();
  for (const auto* log : {&res.usv_safety, &res.auv_safety})
    for (const auto& tr : *log) f.safety_stop |= tr.to_active && tr.rule != "manual" && tr.action >= safety::Action::kHold;
  res.outcome = classify(f);
  if (res.outcome == Outcome::kCollision) {
    const bool auv_hit = !std::isnan(res.usv_auv_min_clearance_m) && !(res.min_clearance_m <= res.usv_auv_min_clearance_m);
    const auto hit = auv_hit ? std::make_pair(auv_closest_t, std::string("the AUV")) : closest;
    char b[160];
    std::snprintf(b, sizeof b, "the hull touched %s at %.1f s (clearance %.2f m); ", hit.second.c_str(), hit.first,
                  auv_hit ? res.usv_auv_min_clearance_m : res.min_clearance_m);
    res.reason = b + res.reason;
  }
  res.success = res.outcome == Outcome::kSuccess;
  res.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  return res;
}

}  // namespace closed_loop
}  // namespace offshore_gnc
