// The ROS-free stacks read the vehicles' shipped configuration files through the parameter tables, and the
// whole default mission runs ROS-free in one process (./scripts/bench mission compares it with the ROS run).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "offshore_gnc/closed_loop/mission.h"
#include "offshore_gnc/common/faults.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/control/vehicle_control.h"
#include "bounds.h"

using namespace offshore_gnc;
using namespace offshore_gnc::closed_loop;
using testing_bounds::lower;
using testing_bounds::upper;

TEST(StackConfig, ShippedFilesLoadWithTheVehiclesPresets) {
  const UsvStackConfig u = loadUsvStack("config");
  EXPECT_DOUBLE_EQ(u.guidance.los.acceptance_radius, 16.0);
  EXPECT_TRUE(u.guidance.sbb_enabled);
  EXPECT_EQ(u.control.vehicle, "usv");
  EXPECT_DOUBLE_EQ(u.lidar.max_range, 64.0);                  // config/perception/lidar_usv.yaml
  EXPECT_DOUBLE_EQ(u.lidar.hull_min_x, -6.0);
  for (const char* m : {"girona500", "acolor"}) {
    const AuvStackConfig a = loadAuvStack("config", m, "config/scenarios/pyhajarvi.yaml");
    EXPECT_EQ(a.guidance.vehicle, m);
    EXPECT_EQ(a.control.vehicle, m);
    EXPECT_TRUE(a.guidance.los.sphere);
    EXPECT_DOUBLE_EQ(a.mission.coverage.north_max, 60.0);      // the scenario's auv/coverage
  }
  EXPECT_THROW(loadAuvStack("config", "nautilus"), ConfigError);
  // as guidance_auv.launch with sim:=true: the aColor's simulation gains over Table 4.2, the Girona500's as is
  const AuvStackConfig ac = loadAuvStack("config", "acolor");
  EXPECT_DOUBLE_EQ(ac.control.acolor.yaw.kp, 0.2);              // config/control/acolor_sim.yaml
  EXPECT_DOUBLE_EQ(ac.control.acolor.heave.kp, 300.0);          // Table 4.2, untouched
  EXPECT_DOUBLE_EQ(control::AcolorControlParams().yaw.kd, 0.812);  // the reference (config/control/acolor.yaml)
  EXPECT_DOUBLE_EQ(ac.guidance.los.acceptance_radius, 1.4);      // R = 3 L_AUV
  EXPECT_DOUBLE_EQ(ac.guidance.los.kp, 0.333);                   // Table 4.2 LOS
  EXPECT_TRUE(ac.guidance.los.crab_ned);
  EXPECT_DOUBLE_EQ(loadAuvStack("config", "girona500").control.girona500.yaw.kp, 63.425);  // Table 4.3
}

TEST(StackConfig, ABadValueNamesTheFileAndTheKey) {
  const std::string dir = testing::TempDir() + "/stack_config";
  ASSERT_EQ(std::system(("rm -rf " + dir + " && cp -r config " + dir).c_str()), 0);
  std::ofstream(dir + "/guidance/usv.yaml") << "vehicle: usv\nlos: {kp: 50.0}\n";
  try {
    loadUsvStack(dir);
    FAIL() << "an out-of-range LOS gain was accepted";
  } catch (const ConfigError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("guidance/usv.yaml"), std::string::npos) << w;
    EXPECT_NE(w.find("los/kp"), std::string::npos) << w;
  }
  std::ofstream(dir + "/guidance/usv.yaml") << "vehicle: usv\nlos: {adaptive_crab: maybe}\n";
  EXPECT_THROW(loadUsvStack(dir), ConfigError);
}

TEST(RosFreeMission, TheDefaultMissionSucceedsInOneProcess) {
  const MissionConfig cfg = loadMission("config", "config/scenarios/pyhajarvi.yaml");
  const MissionResult r = runMission(cfg);
  EXPECT_TRUE(r.success) << r.reason;
  EXPECT_EQ(r.outcome, Outcome::kSuccess);
  EXPECT_TRUE(r.recovered);
  EXPECT_EQ(r.auv.final_phase, "SURFACED");  // RECOVERED once it hears the USV's status, after the run's end
  EXPECT_EQ(r.usv.final_phase, "RECOVERED");
  // Each figure's bound and the runs it was set from: test/bounds.yaml and test/bounds_measured.yaml (issue 30).
  const std::string c = "rosfree_default";
  EXPECT_LE(r.target_error_m, upper(c, "target_error_m"));
  // the hull's: the AUV comes up 2-3 m from the buoy and the recovery's hold keeps the hull clear of it (the hold
  // point moved off its box; passing it in the transit, more than 5 m)
  EXPECT_GE(r.min_clearance_m, lower(c, "min_clearance_m"));
  // the AUV navigated on USBL fixes placed by the USV's relayed GPS and heading (as the main job's), not on the
  // simulator's INS-like estimate
  EXPECT_GE(r.usbl.received, lower(c, "usbl_fixes_received"));
  EXPECT_LE(r.auv_nav_rmse_m, upper(c, "auv_nav_rmse_m"));
  // The simulated pair's reflected replies are the outliers, and the gates (fit error, depth, the filter's)
  // refuse them and hardly anything else (seed 1 in the field day: the gates refused 5, 4 of them outliers). The
  // gross ones (7-32 m off) are refused; one a few decimetres past the 3 m threshold may pass (seed 1 since the
  // Girona500's own-direction thrust limits, 2026-12-06: 3.2 and 3.7 m, the navigation's RMSE unchanged, 0.30 m).
  EXPECT_GT(r.usbl.multipath_replies, 0u);
  EXPECT_GT(r.usbl.outliers, 0u);
  EXPECT_LE(r.usbl.outliers_accepted, upper(c, "usbl_outliers_accepted"));
  EXPECT_GE(r.usbl.by_gates_outliers + 1, r.usbl.by_gates);
  EXPECT_EQ(r.usbl.rejected_by.count("gated"), 1u);  // the navigation filter's gate caught some the others let by
  EXPECT_GT(r.usbl.rejected, 0u);
  EXPECT_GT(r.usv.metrics.samples, 100u);
  EXPECT_GT(r.auv.metrics.samples, 100u);
  EXPECT_LE(r.usv_final_distance_to_target_m, upper(c, "usv_final_distance_to_target_m"));
  // Issue 15's goals on the same classes the nodelets run, in the field day's wind, current and chop (issue 32).
  // The hold counts at the target and at the recovery point, each from on station.
  EXPECT_LE(r.usv.metrics.rmse, upper(c, "usv_xte_est_rmse_m"));
  EXPECT_LE(r.usv_wait_drift_m, upper(c, "usv_wait_drift_m"));
  EXPECT_LE(r.usv_hold_p95_m, upper(c, "usv_hold_p95_m"));
  EXPECT_GE(r.sim_time_s, r.detection_time_s + cfg.scenario.mission.hold_time);  // held at the target before success
  // After the find (issue 36): the AUV holds near its point, comes up, the hull ends off it and never touches it.
  EXPECT_LE(r.auv_hold_excursion_m, upper(c, "auv_hold_excursion_m"));
  EXPECT_LE(r.auv_ascent_drift_m, upper(c, "auv_ascent_drift_m"));
  EXPECT_LE(r.recovery_distance_m, upper(c, "recovery_distance_m"));
  EXPECT_GE(r.usv_auv_min_clearance_m, lower(c, "usv_auv_min_clearance_m"));
  EXPECT_LE(r.find_to_recovery_s, upper(c, "find_to_recovery_s"));
  // the supervisors ran and never acted: no false alarm (the buoy on the path has a safe side)
  EXPECT_TRUE(r.usv_safety.empty()) << r.usv_safety.front().rule << ": " << r.usv_safety.front().reason;
  EXPECT_TRUE(r.auv_safety.empty()) << r.auv_safety.front().rule << ": " << r.auv_safety.front().reason;
}

// A poor radio: half a second late, a third of the USV's GPS and heading messages lost on the way to the AUV. The
// fixes still find the USV's pose at their time (interpolated between the messages that came), so the AUV still
// navigates within a metre and the target crosses (reliable: delayed, never lost).
TEST(RosFreeMission, ALateLossyRadioStillPlacesTheFixes) {
  MissionConfig cfg = loadMission("config", "config/scenarios/pyhajarvi.yaml");
  cfg.radio.latency = 0.5;
  cfg.radio.loss = 0.33;
  const MissionResult r = runMission(cfg);
  EXPECT_TRUE(r.success) << toString(r.outcome) << ": " << r.reason;
  const std::string c = "rosfree_poor_radio";
  EXPECT_GE(r.relay_lost, lower(c, "relay_lost"));
  EXPECT_GE(r.usbl.received, lower(c, "usbl_fixes_received"));
  EXPECT_LE(r.auv_nav_rmse_m, upper(c, "auv_nav_rmse_m"));
}

// The supervisors in the ROS-free stacks answer the simulators' faults as in the ROS mission (docs/safety.md):
// the rule at its detection time (plus one supervisor period), its action reaching control, and the release.
TEST(RosFreeStacks, TheSupervisorsAnswerTheSimulatorsFaults) {
  const sim::Scenario sc = sim::loadScenario("config/scenarios/pyhajarvi.yaml");
  auto activation = [](const std::vector<safety::Transition>& log, const std::string& rule, bool active) {
    for (const auto& tr : log)
      if (tr.rule == rule && tr.to_active == active) return tr.t;
    return -1.0;
  };
  UsvStackConfig u = loadUsvStack("config");
  u.sim.faults = FaultPlan::parse("gps@20+10 jet@40+5");
  UsvStack usv(sc, u);
  control::SafetyOverride at_25 = control::SafetyOverride::kNone, at_43 = at_25;
  while (usv.time() < 55.0) {
    usv.step();
    usv.onPeerAlive(usv.time());
    if (std::abs(usv.time() - 25.0) < 1e-6) at_25 = usv.control().safety();
    if (std::abs(usv.time() - 43.0) < 1e-6) at_43 = usv.control().safety();
  }
  const auto& log = usv.supervisor().transitions();
  // gps: 3 s after the last fix (10 Hz); navigation goes with it (its only source)
  EXPECT_NEAR(activation(log, "gps_timeout", true), 23.0, 0.11);
  EXPECT_NEAR(activation(log, "navigation_timeout", true), 23.0, 0.11);
  EXPECT_EQ(at_25, control::SafetyOverride::kNeutral);
  EXPECT_GT(activation(log, "gps_timeout", false), 32.0 - 0.01);  // released 2 s after the fixes are back
  // jet: the gateway's jet_timeout 0.5 s, then the rule's 1 s
  EXPECT_NEAR(activation(log, "jet", true), 41.5, 0.11);
  EXPECT_EQ(at_43, control::SafetyOverride::kNeutral);
  EXPECT_GT(activation(log, "jet", false), 47.0 - 0.01);

  AuvStackConfig a = loadAuvStack("config", "girona500", "config/scenarios/pyhajarvi.yaml");
  a.navigation = "ins";  // alone, without the USV whose GPS places the USBL fixes
  a.sim.faults = FaultPlan::parse("nav@20+10");
  AuvStack auv(sc, a);
  safety::Action auv_at_25 = safety::Action::kNone;
  double depth_at_23 = NAN, shallowest = INFINITY;
  while (auv.time() < 40.0) {
    auv.step();
    auv.onPeerAlive(auv.time());
    const double t = auv.time();
    if (std::abs(t - 25.0) < 1e-6) auv_at_25 = auv.supervisor().decision().action;
    if (std::abs(t - 23.0) < 1e-6) depth_at_23 = auv.truth().position.z();
    if (t > 23.0 && t < 35.0) shallowest = std::min(shallowest, auv.truth().position.z());
  }
  // navigation: 3 s after the last estimate (20 Hz)
  EXPECT_NEAR(activation(auv.supervisor().transitions(), "navigation_timeout", true), 23.0, 0.11);
  EXPECT_EQ(auv_at_25, safety::Action::kSurface);
  EXPECT_GT(activation(auv.supervisor().transitions(), "navigation_timeout", false), 35.0 - 0.01);
  EXPECT_LT(shallowest, depth_at_23 - 1.0) << depth_at_23;  // it rose while surfacing
}

TEST(RosFreeMission, TheAcolorFollowsItsLawnmowerFindsTheTargetAndIsRecovered) {
  // On its USBL navigation (as the ROS mission's); measured 2026-12-02: cross-track from the first waypoint on the
  // truth 0.52 m, target error 0.55 m. Before issue 16's aColor work its heading chattered and it ran 700 m north
  // without turning. Its hold (config/control/acolor_sim.yaml) is gentle: it has no DVL, its thrusters show only in
  // the next fixes. Until 2026-12-04 its navigation took a hold's desired surge of 0 for "still in the water" and
  // at the surface it ran off; then its proportional hold stood 1-3 m off its point, never the mission's 1 m, and
  // the USV waited at its run-in (auv_adrift). With the hold's slow integral (2026-12-05) it sits on its point and
  // is recovered (seed 4 auv_adrift: test/bounds_measured.yaml's left_out), the hull further off it at the end than
  // the Girona500's (the aColor's loose hold).
  const MissionConfig cfg = loadMission("config", "config/scenarios/pyhajarvi.yaml", "acolor");
  const MissionResult r = runMission(cfg);
  EXPECT_EQ(r.outcome, Outcome::kSuccess) << r.reason;
  EXPECT_EQ(r.usv.final_phase, "RECOVERED");
  const std::string c = "rosfree_acolor";
  EXPECT_LE(r.auv_surface_excursion_m, upper(c, "auv_surface_excursion_m"));
  EXPECT_LE(r.auv_hold_excursion_m, upper(c, "auv_hold_excursion_m"));
  EXPECT_GE(r.usv_auv_min_clearance_m, lower(c, "usv_auv_min_clearance_m"));
  EXPECT_LE(r.recovery_distance_m, upper(c, "recovery_distance_m"));
  EXPECT_GT(r.auv.tracking_truth.samples, 500u);
  EXPECT_LE(r.auv.tracking_truth.rmse, upper(c, "auv_xte_true_rmse_m"));
  EXPECT_LE(r.target_error_m, upper(c, "target_error_m"));
}

TEST(RosFreeMission, TheUsvWaitsAndHoldsInAStrongCurrent) {
  // strong_current.yaml, 0.5 m/s mostly across the transit: issue 15's goals. The Girona500 without its crab is carried off its lawnmower but finds the target.
  // It holds its point and the surface in 0.5 m/s with the stern turned into the current, backing (a hold crabbing
  // the bow the wrong way had left its sway thruster saturated 45 degrees off it: auv_adrift), and is recovered
  // (2026-12-04 seed 1: 1.7 m off its point at the surface, the hull 5.3 m off it at the end).
  const MissionConfig cfg = loadMission("config", "config/scenarios/strong_current.yaml");
  const MissionResult r = runMission(cfg);
  EXPECT_TRUE(r.success) << r.reason;
  EXPECT_EQ(r.usv.final_phase, "RECOVERED");
  EXPECT_EQ(r.target.has_value(), true);
  const std::string c = "rosfree_strong_current";
  EXPECT_LE(r.target_error_m, upper(c, "target_error_m"));
  // the way to the run-in rounds it on a leg beside it
  EXPECT_GE(r.usv_auv_min_clearance_m, lower(c, "usv_auv_min_clearance_m"));
  // issue 15's cross-track goal is the transit's, to the target, which r.usv.metrics counts (the whole run's, 3.7 m,
  // had the recovery's legs round the AUV in it, where the 16 m circle of acceptance cuts each corner across the
  // current: usv_recovery_xte_truth)
  ASSERT_GT(r.usv.metrics.samples, 100u);
  EXPECT_LE(r.usv.metrics.rmse, upper(c, "usv_xte_est_rmse_m"));
  EXPECT_LE(r.usv_wait_drift_m, upper(c, "usv_wait_drift_m"));
  EXPECT_LE(r.usv_hold_p95_m, upper(c, "usv_hold_p95_m"));
}

// no_target.yaml: the AUV covers its area, finds nothing, comes up at once and is recovered.
TEST(RosFreeMission, NoTargetScenarioEndsWithTheAuvRecovered) {
  const MissionConfig cfg = loadMission("config", "config/scenarios/no_target.yaml");
  const MissionResult r = runMission(cfg);
  EXPECT_TRUE(r.success) << r.reason;  // the scenario expects no target, and the AUV back
  EXPECT_EQ(r.usv.final_phase, "RECOVERED");
  EXPECT_FALSE(r.target.has_value());
  EXPECT_LT(r.ascent_at_s - r.found_at_s, 1.0);  // up at once
  EXPECT_GE(r.usv_auv_min_clearance_m, lower("rosfree_no_target", "usv_auv_min_clearance_m"));
  EXPECT_LE(r.recovery_distance_m, upper("rosfree_no_target", "recovery_distance_m"));
}

// Issue 32: the same in the moderate sea (Beaufort 4, Hs 1 m) with everything that echoes: the surface, a bottom 7 m
// down, the buoy's mooring line in the coverage area, volume clutter. None of it may become a target (one seed here;
// `./scripts/bench clutter` runs 20). At the surface the Girona500 holds: the waves' mean drift on its 1.5 m hull is
// a small body's (Havelock), not a wall's (as a full reflection it had exceeded its 420 N of backing thrust and it
// ended 244 m off). With the hold's integral it sits on its point (0.17 m off, 2026-12-05 seed 1; its proportional
// hold stood 1.2 m off), but the USV, in 1 m waves, wanders about its run-in (its hold point jumping as the way there
// is planned again) and on seed 1 never closes in: auv_adrift with the AUV held, never on top of it. The hull's least
// distance to the AUV is short of issue 36's 1 m in this sea (2026-12-05, seeds 1-4: 0.92, 1.55, 3.11, 3.20 m, seeds 3
// and 4 recovered; before the AUV was handed to guidance's planner, seeds 1-3: 4.34, 2.97, 0.71 m, none recovered).
// With the GPS noise drawn by the simulator (sim::SurfaceGps, the ROS simulator's too; 2026-12-05) seed 1 is
// recovered: hull 2.86 m off at the least, surface excursion 1.50 m.
TEST(RosFreeMission, NoTargetInTheModerateSeaFindsNoneAndTheAuvHolds) {
  std::ifstream in("config/scenarios/no_target.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("sea_state: field_day");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::string("sea_state: field_day").size(), "sea_state: moderate");
  const std::string path = ::testing::TempDir() + "no_target_moderate.yaml";
  std::ofstream(path) << text;
  const MissionConfig cfg = loadMission("config", path);
  ASSERT_NEAR(cfg.scenario.sea.wave_height, 1.0, 0.05);
  ASSERT_GT(cfg.auv.sim.sonar.water.clutter_density, 0.0);
  const MissionResult r = runMission(cfg);
  EXPECT_FALSE(r.target.has_value());
  EXPECT_LT(r.ascent_at_s - r.found_at_s, 1.0);
  // recovered, or the AUV held at the surface with the USV still closing in: safe either way, said so
  ASSERT_TRUE(r.outcome == Outcome::kSuccess || r.outcome == Outcome::kAuvAdrift) << r.reason;
  EXPECT_EQ(r.usv.final_phase, r.outcome == Outcome::kSuccess ? "RECOVERED" : "RECOVERY");
  EXPECT_LE(r.auv_surface_excursion_m, upper("rosfree_no_target_moderate", "auv_surface_excursion_m"));
  // never on top of it
  EXPECT_GE(r.usv_auv_min_clearance_m, lower("rosfree_no_target_moderate", "usv_auv_min_clearance_m"));
}
