// Every fault of docs/safety.md's table answered by the vehicles' supervisors in the ROS-free mission, the logic the
// main job's fault missions showed over ROS (test/py/test_mission_faults.py keeps only the wiring): the documented
// rule and action, detected at its timeout plus at most one supervisor period, raised once, released after the
// fault; the LiDAR's and the barge's while the USV is under way, where they act.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "offshore_gnc/closed_loop/mission.h"
#include "offshore_gnc/common/faults.h"

using namespace offshore_gnc;
using namespace offshore_gnc::closed_loop;

namespace {
constexpr double kPeriod = 0.1;  // the supervisors' update (config/safety)
constexpr double kSlack = 0.02;

struct Case {
  const char* fault;
  const char* vehicle;
  const char* rule;
  safety::Action action;
  double lo, hi;  // detection delay after the fault's start [s], before the supervisor's next update
};

// The simulators' rates and the presets' timeouts (safety::usvDefaults(), auvDefaults()).
const Case kCases[] = {
    {"gps", "usv", "gps_timeout", safety::Action::kNeutral, 3.0 - 0.1, 3.0},      // 10 Hz fixes, 3 s
    {"jet", "usv", "jet", safety::Action::kNeutral, 1.5, 1.5},                    // jet_timeout 0.5 s + 1 s
    {"bus_off", "usv", "bus_off", safety::Action::kNeutral, 0.5, 0.5},             // at once + 0.5 s
    {"sonar", "auv", "sonar_timeout", safety::Action::kWarn, 5.0 - 0.05, 5.0},      // 20 Hz beams, 5 s
    {"depth", "auv", "depth_timeout", safety::Action::kSurface, 3.0 - 0.1, 3.0},    // 10 Hz, 3 s
    // the navigation's heading_timeout 1 s after the last AHRS sample, then the navigation timeout 3 s
    {"nav", "auv", "navigation_timeout", safety::Action::kSurface, 4.0 - 0.1, 4.0},
    {"usbl", "auv", "usbl_timeout", safety::Action::kWarn, 30.0 - 2.0, 30.0},      // 0.5 Hz pings, 30 s
    {"link", "both", "link_timeout", safety::Action::kWarn, 10.0, 10.0},           // the USV's 10 s
};

MissionConfig defaultMission() { return loadMission("config", "config/scenarios/pyhajarvi.yaml"); }

MissionResult withFault(MissionConfig cfg, const std::string& plan, double until) {
  const FaultPlan p = FaultPlan::parse(plan);
  cfg.usv.sim.faults = p.of("usv");
  cfg.auv.sim.faults = p.of("auv");
  cfg.link_faults = p.of("both");
  cfg.scenario.mission.max_sim_time = until;
  return runMission(cfg);
}

// The rule's activations in a supervisor's log (the USV's for "both").
std::vector<safety::Transition> activations(const MissionResult& r, const std::string& vehicle, const std::string& rule,
                                            bool active) {
  std::vector<safety::Transition> out;
  for (const auto& tr : vehicle == "auv" ? r.auv_safety : r.usv_safety)
    if (tr.rule == rule && tr.to_active == active) out.push_back(tr);
  return out;
}

// The default mission with the AUV's search on the target's own lane: it finds the target early and the USV is
// under way from about 100 s (the USV transits only after the find).
MissionConfig shortSearch() {
  MissionConfig cfg = defaultMission();
  const double east = cfg.scenario.world.targets.at(0).position.y();
  cfg.auv.mission.coverage.east_min = east;
  cfg.auv.mission.coverage.east_max = east + 6.0;
  cfg.auv.mission.coverage.spacing = 6.0;
  return cfg;
}

// When the USV first makes `speed` over ground after `from` (its trace, 20 Hz), NaN if never.
double underWay(const MissionResult& r, double from, double speed) {
  for (const auto& row : r.usv_trace)
    if (row[0] >= from && std::hypot(row[4], row[5]) >= speed) return row[0];
  return NAN;
}
}  // namespace

class Faults : public ::testing::TestWithParam<Case> {};

TEST_P(Faults, AnsweredByTheDocumentedRuleInTime) {
  const Case& c = GetParam();
  const double start = c.vehicle == std::string("auv") || c.fault == std::string("link") ? 120.0 : 80.0;
  const double duration = c.fault == std::string("usbl") ? 60.0 : 20.0;
  char plan[64];
  std::snprintf(plan, sizeof plan, "%s@%g+%g", c.fault, start, duration);
  const MissionResult r = withFault(defaultMission(), plan, start + duration + 25.0);
  const auto on = activations(r, c.vehicle, c.rule, true);
  ASSERT_EQ(on.size(), 1u) << plan << ": raised " << on.size() << " times";  // once, no flapping
  const double delay = on[0].t - start;
  EXPECT_GE(delay, c.lo - kSlack) << plan;
  EXPECT_LE(delay, c.hi + kPeriod + kSlack) << plan;
  EXPECT_EQ(on[0].action, c.action) << plan << ": " << safety::actionName(on[0].action);
  const auto off = activations(r, c.vehicle, c.rule, false);
  ASSERT_EQ(off.size(), 1u) << plan << ": never released";
  EXPECT_GT(off[0].t, start + duration) << plan << ": released during the fault";
}

INSTANTIATE_TEST_SUITE_P(SafetyTable, Faults, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& i) { return std::string(i.param.fault); });

// The LiDAR goes silent while the USV transits to the target: it holds where it is (no eyes ahead), stopping
// within a few seconds, and goes on once the LiDAR is back.
TEST(FaultsUnderWay, ALidarOutageInTheTransitStopsTheUsv) {
  const MissionResult base = withFault(shortSearch(), "", 300.0);
  const double t0 = underWay(base, 0.0, 0.8);
  ASSERT_FALSE(std::isnan(t0)) << "the USV never got under way";
  const double start = std::ceil(t0) + 2.0;
  char plan[64];
  std::snprintf(plan, sizeof plan, "lidar@%g+20", start);
  const MissionResult r = withFault(shortSearch(), plan, 600.0);  // to the recovery
  const auto on = activations(r, "usv", "lidar_timeout", true);
  ASSERT_EQ(on.size(), 1u);
  EXPECT_NEAR(on[0].t - start, 3.0, 0.08 + kPeriod + kSlack);
  EXPECT_EQ(on[0].action, safety::Action::kHold);
  double stopped = NAN;  // under 0.5 m/s over ground after the detection
  for (const auto& row : r.usv_trace)
    if (row[0] >= on[0].t && std::hypot(row[4], row[5]) < 0.5) {
      stopped = row[0];
      break;
    }
  EXPECT_LE(stopped - on[0].t, 8.0) << "still under way " << stopped - on[0].t << " s after the hold";
  EXPECT_EQ(activations(r, "usv", "lidar_timeout", false).size(), 1u);
  EXPECT_EQ(r.outcome, Outcome::kSuccess) << r.reason;  // and the mission goes on to the target
}

// The barge broadside across the transit, 6 s ahead at the USV's speed: no side to go round, time to collision under
// allstop_ttc: the collision rule holds the USV before it touches, and lets it go once nothing closes any more.
TEST(FaultsUnderWay, ABargeAheadStopsTheUsvShortOfIt) {
  const MissionResult r = withFault(shortSearch(), "collision@60+150", 220.0);
  const auto on = activations(r, "usv", "collision", true);
  ASSERT_FALSE(on.empty());
  EXPECT_EQ(on[0].action, safety::Action::kHold);
  EXPECT_NE(on[0].reason.find("no safe side"), std::string::npos) << on[0].reason;
  EXPECT_GT(r.min_clearance_m, 0.0) << "the hull touched the barge";
  EXPECT_FALSE(activations(r, "usv", "collision", false).empty());
}

TEST(FaultsBetweenTheVehicles, ATargetOutsideTheRegionIsRefusedSayingWhy) {
  const MissionResult r = withFault(defaultMission(), "geofence@40", 60.0);
  ASSERT_EQ(r.target_refusals.size(), 1u);
  EXPECT_NE(r.target_refusals[0].find("outside the operating region"), std::string::npos) << r.target_refusals[0];
  EXPECT_NE(r.usv.final_phase, "TRANSIT");
  EXPECT_NE(r.usv.final_phase, "ARRIVED");
}

// Issue 16's case: no USBL reply for 60 s while the AUV searches. The navigation dead-reckons (DVL), the supervisor
// only warns, and the mission still ends at the right target.
TEST(FaultsUnderWay, ASixtySecondUsblOutageInTheSearchIsSurvived) {
  MissionConfig cfg = defaultMission();
  const MissionResult r = withFault(cfg, "usbl@120+60", cfg.scenario.mission.max_sim_time);
  EXPECT_EQ(r.outcome, Outcome::kSuccess) << r.reason;
  EXPECT_LT(r.auv_nav_max_m, 1.5);
  EXPECT_LT(r.target_error_m, 1.5);
  EXPECT_EQ(activations(r, "auv", "usbl_timeout", true).size(), 1u);
}
