// Safety supervisor and operating region: detection / release times of every rule, no flapping, priorities,
// manual, latching and reset, bad input, configuration; region geometry and the origins check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/safety/region.h"
#include "offshore_gnc/safety/supervisor.h"

using namespace offshore_gnc;
using namespace offshore_gnc::safety;

namespace {

RuleConfig rule(double detection, double release, const char* action, bool recovery = true) {
  RuleConfig r;
  r.detection = detection, r.release = release, r.action = action, r.recovery = recovery;
  return r;
}

double stepTime(int k) { return k * 0.1; }  // a 10 Hz control period

// A "C" open towards +x: the notch 10 < x < 30, 10 < y < 20 is outside.
std::vector<Eigen::Vector2d> cShape() {
  return {{0, 0}, {30, 0}, {30, 10}, {10, 10}, {10, 20}, {30, 20}, {30, 30}, {0, 30}};
}

struct RuleCase {
  Rule rule;
  std::function<void(SupervisorConfig&)> enable;
  std::function<void(Supervisor&, double, bool)> feed;  // good = the condition is clear
  double onset;  // when the condition starts to hold
};

}  // namespace

// Each rule: the condition holds on [1, 5) s (a timeout: from last heard + timeout); the rule becomes active
// exactly its detection time later, not one period before, and is released its release time after 5 s.
TEST(Supervisor, EachRuleTriggersAfterDetectionAndReleasesAfterRelease) {
  const std::vector<RuleCase> cases = {
      {Rule::kGpsTimeout, [](SupervisorConfig& c) { c.gps_timeout = 0.5; },
       [](Supervisor& s, double t, bool good) { if (good) s.heard(Source::kGps, t); }, 0.9 + 0.5},
      {Rule::kCommandTimeout, [](SupervisorConfig& c) { c.command_timeout = 0.5; },
       [](Supervisor& s, double t, bool good) { if (good) s.heard(Source::kCommand, t); }, 0.9 + 0.5},
      {Rule::kMaxDepth, [](SupervisorConfig& c) { c.max_depth = 50; },
       [](Supervisor& s, double t, bool good) { s.depth(t, good ? 10 : 60); }, 1.0},
      {Rule::kMinAltitude, [](SupervisorConfig& c) { c.min_altitude = 2; },
       [](Supervisor& s, double t, bool good) { s.altitude(t, good ? 10 : 1); }, 1.0},
      {Rule::kRegion, [](SupervisorConfig& c) { c.region = {-100, -100, 100, -100, 100, 100, -100, 100}; },
       [](Supervisor& s, double t, bool good) { s.position(t, good ? 0 : 150, 0); }, 1.0},
      {Rule::kBusOff, [](SupervisorConfig& c) { c.bus_off_check = true; },
       [](Supervisor& s, double t, bool good) { s.busOff(t, !good); }, 1.0},
      {Rule::kJet, [](SupervisorConfig& c) { c.jet_check = true; },
       [](Supervisor& s, double t, bool good) { s.jetAnswering(t, 0, true), s.jetAnswering(t, 1, good); }, 1.0},
      {Rule::kCollision, [](SupervisorConfig& c) { c.allstop_ttc = 5; },
       [](Supervisor& s, double t, bool good) { s.timeToCollision(t, good ? 20 : 2, false); }, 1.0},
  };
  const double detection = 1.0, release = 2.0;
  for (const auto& c : cases) {
    SCOPED_TRACE(ruleName(c.rule));
    SupervisorConfig cfg;
    c.enable(cfg);
    cfg.rules[c.rule] = rule(detection, release, "hold");
    Supervisor s(cfg);
    std::vector<Transition> all;
    for (int k = 0; k <= 100; ++k) {
      const double t = stepTime(k);
      c.feed(s, t, t < 1.0 - 1e-9 || t >= 5.0 - 1e-9);
      const auto out = s.update(t);
      const bool expect_active = t >= c.onset + detection - 1e-6 && t < 5.0 + release - 1e-6;
      ASSERT_EQ(s.active(c.rule), expect_active) << "t = " << t;
      EXPECT_EQ(out.decision.action, expect_active ? Action::kHold : Action::kNone);
      all.insert(all.end(), out.transitions.begin(), out.transitions.end());
    }
    ASSERT_EQ(all.size(), 2u);
    EXPECT_NEAR(all[0].t, c.onset + detection, 0.05);
    EXPECT_TRUE(all[0].to_active && !all[0].from_active);
    EXPECT_EQ(all[0].rule, ruleName(c.rule));
    EXPECT_EQ(all[0].action, Action::kHold);
    EXPECT_NEAR(all[1].t, 5.0 + release, 1e-6);  // recovery is a transition too
    EXPECT_TRUE(all[1].from_active && !all[1].to_active);
    EXPECT_NE(all[1].reason.find("released"), std::string::npos) << all[1].reason;
    EXPECT_EQ(s.counters().get("transitions"), 2u);
  }
}

TEST(Supervisor, ReasonsNameTheValues) {
  SupervisorConfig cfg;
  cfg.gps_timeout = 1.0;
  cfg.max_depth = 50;
  cfg.rules.max_depth = rule(0.0, 2.0, "surface");
  Supervisor s(cfg);
  s.heard(Source::kGps, 0.0);
  s.depth(0.0, 50.5);
  auto out = s.update(2.1);
  ASSERT_EQ(out.transitions.size(), 2u);
  EXPECT_EQ(out.transitions[0].reason, "gps silent for 2.1 s (timeout 1.0 s)");
  EXPECT_EQ(out.transitions[1].reason, "depth 50.50 m beyond max 50.00 m");
  EXPECT_EQ(out.decision.active_rule, "max_depth");
  s.depth(3.0, 45.0);
  out = s.update(5.0);
  ASSERT_EQ(out.transitions.size(), 1u);
  EXPECT_EQ(out.transitions[0].reason, "depth 45.00 m within max 50.00 m, clear for 2.0 s: released");
  EXPECT_EQ(out.decision.active_rule, "gps_timeout");
  EXPECT_EQ(out.decision.reason, "gps silent for 5.0 s (timeout 1.0 s)");
}

TEST(Supervisor, NeverHeardTriggersAfterTimeoutFromStart) {
  SupervisorConfig cfg;
  cfg.navigation_timeout = 1.0;
  cfg.rules.navigation_timeout = rule(0.0, 2.0, "surface");
  Supervisor s(cfg);
  EXPECT_EQ(s.update(10.0).decision.action, Action::kNone);  // the start
  EXPECT_EQ(s.update(11.0).decision.action, Action::kNone);       // exactly the timeout: not yet silent
  const auto out = s.update(11.1);
  EXPECT_EQ(out.decision.action, Action::kSurface);
  ASSERT_EQ(out.transitions.size(), 1u);
  EXPECT_EQ(out.transitions[0].reason, "navigation never heard in 1.1 s since start (timeout 1.0 s)");
}

TEST(Supervisor, ToggleAtThresholdDoesNotFlap) {
  for (double detection : {0.0, 1.0}) {
    SCOPED_TRACE(detection);
    SupervisorConfig cfg;
    cfg.max_depth = 50;
    cfg.rules.max_depth = rule(detection, 2.0, "surface");
    Supervisor s(cfg);
    int on = 0, off = 0;
    for (int k = 0; k < 600; ++k) {
      s.depth(stepTime(k), k % 2 ? 50.01 : 49.99);
      for (const auto& tr : s.update(stepTime(k)).transitions) (tr.to_active ? on : off)++;
    }
    // never continuously over for 1 s: no activation; with no detection time one activation, never released
    EXPECT_EQ(on, detection > 0 ? 0 : 1);
    EXPECT_EQ(off, 0);
  }
}

TEST(Supervisor, HigherActionWinsAndItsRuleIsReported) {
  SupervisorConfig cfg;
  cfg.gps_timeout = 1.0;
  cfg.max_depth = 50;
  cfg.rules.gps_timeout = rule(0.0, 2.0, "hold");
  cfg.rules.max_depth = rule(0.0, 2.0, "surface");
  {
    Supervisor s(cfg);
    s.update(0.0);
    s.depth(0.0, 60.0);
    const auto d = s.update(2.0).decision;
    EXPECT_TRUE(s.active(Rule::kGpsTimeout) && s.active(Rule::kMaxDepth));
    EXPECT_EQ(d.action, Action::kSurface);  // surface beats hold
    EXPECT_EQ(d.active_rule, "max_depth");
    EXPECT_EQ(d.reason, "depth 60.00 m beyond max 50.00 m");
  }
  std::swap(cfg.rules.gps_timeout.action, cfg.rules.max_depth.action);  // the higher action earlier in the table
  Supervisor s(cfg);
  s.update(0.0);
  s.depth(0.0, 60.0);
  const auto d = s.update(2.0).decision;
  EXPECT_EQ(d.action, Action::kSurface);
  EXPECT_EQ(d.active_rule, "gps_timeout");
}

TEST(Supervisor, AbortLatchesEvenWithRecovery) {
  SupervisorConfig cfg;
  cfg.allstop_ttc = 5;
  cfg.max_depth = 50;
  cfg.rules.collision = rule(0.0, 1.0, "abort", true);
  cfg.rules.max_depth = rule(0.0, 1.0, "surface");
  Supervisor s(cfg);
  s.timeToCollision(0.0, 2.0, false);
  s.depth(0.0, 60.0);
  EXPECT_EQ(s.update(0.0).decision.action, Action::kAbort);
  s.timeToCollision(1.0, INFINITY, false);
  s.depth(1.0, 10.0);
  const auto out = s.update(100.0);
  ASSERT_EQ(out.transitions.size(), 1u);  // only the surface rule recovers
  EXPECT_EQ(out.transitions[0].rule, "max_depth");
  EXPECT_EQ(out.decision.action, Action::kAbort);
  EXPECT_EQ(out.decision.reason,
            "time to collision 2.0 s below allstop 5.0 s and no safe side (clear now, latched until reset)");
  for (const auto& r : ruleTable(cfg))
    if (r.name == "collision") {
      EXPECT_FALSE(r.recovery);
    }
  s.reset(101.0);
  const auto after = s.update(101.0);
  ASSERT_EQ(after.transitions.size(), 1u);
  EXPECT_EQ(after.transitions[0].rule, "collision");
  EXPECT_EQ(after.transitions[0].reason, "time to collision inf s (allstop 5.0 s): released by reset");
  EXPECT_EQ(after.decision.action, Action::kNone);
}

TEST(Supervisor, ManualWinsOverEverything) {
  SupervisorConfig cfg;
  cfg.allstop_ttc = 5;
  cfg.rules.collision = rule(0.0, 1.0, "abort");
  Supervisor s(cfg);
  s.timeToCollision(0.0, 1.0, false);
  EXPECT_EQ(s.update(0.0).decision.action, Action::kAbort);
  s.setManual(true);
  auto out = s.update(0.1);
  EXPECT_TRUE(out.decision.manual);
  EXPECT_EQ(out.decision.action, Action::kNone);  // nothing automatic reaches the actuators
  EXPECT_EQ(out.decision.active_rule, "collision");  // but the operator sees what is active
  ASSERT_EQ(out.transitions.size(), 1u);
  EXPECT_EQ(out.transitions[0].rule, "manual");
  EXPECT_TRUE(out.transitions[0].to_active);
  EXPECT_TRUE(s.update(0.2).transitions.empty());  // reported once
  s.setManual(false);
  out = s.update(0.3);
  EXPECT_FALSE(out.decision.manual);
  EXPECT_EQ(out.decision.action, Action::kAbort);  // still latched underneath
  ASSERT_EQ(out.transitions.size(), 1u);
  EXPECT_FALSE(out.transitions[0].to_active);
}

TEST(Supervisor, NonRecoverableLatchesUntilReset) {
  SupervisorConfig cfg;
  cfg.max_depth = 50;
  cfg.rules.max_depth = rule(0.5, 1.0, "surface", false);
  Supervisor s(cfg);
  s.depth(0.0, 55.0);
  EXPECT_EQ(s.update(0.5).transitions.size(), 1u);
  s.depth(1.0, 30.0);
  for (int k = 10; k < 1000; ++k) EXPECT_TRUE(s.update(stepTime(k)).transitions.empty());
  auto d = s.update(100.0).decision;
  EXPECT_EQ(d.action, Action::kSurface);
  EXPECT_EQ(d.reason, "depth 55.00 m beyond max 50.00 m (clear now, latched until reset)");
  s.depth(100.0, 52.0);  // a reset while the condition holds keeps the rule
  s.reset(100.0);
  EXPECT_TRUE(s.update(100.0).transitions.empty());
  EXPECT_TRUE(s.active(Rule::kMaxDepth));
  s.depth(101.0, 30.0);
  s.reset(101.0);
  const auto out = s.update(101.1);
  ASSERT_EQ(out.transitions.size(), 1u);
  EXPECT_EQ(out.transitions[0].reason, "depth 30.00 m within max 50.00 m: released by reset");
  EXPECT_EQ(out.transitions[0].t, 101.0);
  EXPECT_EQ(out.decision.action, Action::kNone);
  EXPECT_EQ(s.counters().get("transitions"), 2u);
}

TEST(Supervisor, NonFiniteInputsAreCountedAndNotActedOn) {
  SupervisorConfig cfg;
  cfg.max_depth = 50, cfg.min_altitude = 2, cfg.allstop_ttc = 5, cfg.gps_timeout = 1.0;
  cfg.region = {-100, -100, 100, -100, 100, 100, -100, 100};
  for (Rule r : {Rule::kMaxDepth, Rule::kMinAltitude, Rule::kRegion, Rule::kCollision, Rule::kGpsTimeout})
    cfg.rules[r] = rule(0.0, 0.5, "surface");
  Supervisor s(cfg);
  s.heard(Source::kGps, 0.0);
  s.depth(0.0, 10.0);
  s.altitude(0.0, 10.0);
  s.update(0.0);
  s.depth(0.1, NAN);
  s.depth(NAN, 60.0);
  s.altitude(0.1, INFINITY);
  s.position(0.1, NAN, 0.0);
  s.timeToCollision(0.1, NAN, false);
  s.timeToCollision(0.1, -1.0, false);
  s.heard(Source::kGps, NAN);
  s.busOff(NAN, true);
  s.update(NAN);
  EXPECT_EQ(s.counters().get("bad_input"), 9u);
  EXPECT_EQ(s.update(0.5).decision.action, Action::kNone);
  s.altitude(0.5, NAN);  // unknown altitude: not bad input
  EXPECT_EQ(s.counters().get("bad_input"), 9u);
  // nor does bad input clear an active rule
  s.heard(Source::kGps, 0.6);
  s.depth(0.6, 60.0);
  s.altitude(0.6, 1.0);
  EXPECT_EQ(s.update(0.6).transitions.size(), 2u);
  for (int k = 7; k < 100; ++k) {
    s.heard(Source::kGps, stepTime(k));
    s.depth(stepTime(k), NAN);
    s.altitude(stepTime(k), NAN);
    EXPECT_TRUE(s.update(stepTime(k)).transitions.empty());
  }
  EXPECT_TRUE(s.active(Rule::kMaxDepth) && s.active(Rule::kMinAltitude));
  EXPECT_EQ(s.counters().get("bad_input"), 9u + 93u);
}

TEST(Supervisor, ConfigValidationRefusesOutOfRange) {
  auto refuses = [](const std::function<void(SupervisorConfig&)>& change, const std::string& name) {
    SupervisorConfig c = usvDefaults();
    change(c);
    try {
      Supervisor s(c);
      ADD_FAILURE() << name << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  refuses([](SupervisorConfig& c) { c.max_depth = 20000; }, "'max_depth'");
  refuses([](SupervisorConfig& c) { c.gps_timeout = NAN; }, "'gps_timeout'");
  refuses([](SupervisorConfig& c) { c.rules.collision.detection = -1; }, "'rules/collision/detection'");
  refuses([](SupervisorConfig& c) { c.rules.jet.action = "explode"; }, "'rules/jet/action'");
  refuses([](SupervisorConfig& c) { c.region = {0, 0, 10, 0, 10}; }, "'region'");
  refuses([](SupervisorConfig& c) { c.region = {0, 0, 10, 0, 20, 0}; }, "no area");
  EXPECT_NO_THROW(Supervisor{usvDefaults()});
  EXPECT_NO_THROW(Supervisor{auvDefaults()});
  EXPECT_NE(SupervisorConfig::table().find("rules/max_depth/recovery"), nullptr);
  EXPECT_THROW(parseAction("stop"), ConfigError);
}

TEST(Supervisor, RuleTablesOfThePresets) {
  std::vector<std::string> usv, auv;
  for (const auto& r : ruleTable(usvDefaults())) usv.push_back(r.name);
  EXPECT_EQ(usv, (std::vector<std::string>{"gps_timeout", "navigation_timeout", "lidar_timeout", "link_timeout",
                                           "command_timeout", "region", "bus_off", "jet", "collision"}));
  const auto rows = ruleTable(auvDefaults());
  for (const auto& r : rows) auv.push_back(r.name);
  EXPECT_EQ(auv, (std::vector<std::string>{"navigation_timeout", "sonar_timeout", "usbl_timeout", "depth_timeout",
                                           "link_timeout", "command_timeout", "max_depth", "min_altitude"}));
  EXPECT_EQ(rows[6].condition, "depth > 50 m");
  EXPECT_EQ(rows[6].action, Action::kSurface);
  EXPECT_FALSE(rows[6].recovery);
  EXPECT_EQ(rows[7].condition, "altitude < 2 m (unknown altitude never triggers)");
  EXPECT_EQ(rows[7].action, Action::kSurface);
  EXPECT_EQ(rows[0].condition, "navigation not heard for more than 3 s");
}

TEST(Region, ConcavePolygonPoints) {
  for (bool reversed : {false, true}) {
    auto v = cShape();
    if (reversed) std::reverse(v.begin(), v.end());
    const Region r(v);
    EXPECT_TRUE(r.contains(5, 15));
    EXPECT_TRUE(r.contains(20, 5));
    EXPECT_TRUE(r.contains(20, 25));
    EXPECT_FALSE(r.contains(20, 15));  // in the notch
    EXPECT_FALSE(r.contains(-1, 5));
    EXPECT_FALSE(r.contains(35, 25));
    EXPECT_TRUE(r.contains(0, 15));  // on an edge
    EXPECT_TRUE(r.contains(10, 15));
    EXPECT_FALSE(r.contains(NAN, 5));
    EXPECT_DOUBLE_EQ(r.distanceToEdge(20, 15), 5.0);
    EXPECT_DOUBLE_EQ(r.distanceToEdge(5, 15), 5.0);
    EXPECT_DOUBLE_EQ(r.distanceToEdge(-3, -4), 5.0);
  }
  EXPECT_THROW(Region({{0, 0}, {1, 1}}), ConfigError);
  EXPECT_THROW(Region({{0, 0}, {1, 1}, {2, 2}}), ConfigError);
  EXPECT_THROW(Region::fromList({0, 0, 1, 0, 1}), ConfigError);
}

TEST(Region, TargetFarAwayIsRefusedNamingTheDistance) {
  const Region r = Region::fromList({-500, -500, 500, -500, 500, 500, -500, 500});
  EXPECT_EQ(r.checkTarget(2520300.0, 0.0),
            "target 2520.3 km from the origin is outside the operating region (nearest edge 2519.8 km)");
  EXPECT_EQ(r.checkTarget(0.0, 700.0), "target 700.0 m from the origin is outside the operating region (nearest edge 200.0 m)");
  EXPECT_EQ(r.checkTarget(100.0, -100.0), "");
  EXPECT_NE(r.checkTarget(NAN, 0.0), "");
}

TEST(Region, PathWithAPointOutsideIsReportedByIndex) {
  const Region r(cShape());
  EXPECT_EQ(r.checkPath(std::vector<Eigen::Vector2d>{{5, 5}, {20, 5}, {40, 5}, {20, 25}}), std::optional<std::size_t>(2));
  EXPECT_EQ(r.checkPath(std::vector<Eigen::Vector2d>{{5, 5}, {5, 25}, {20, 25}}), std::nullopt);
  // both ends inside, the leg crosses the notch
  EXPECT_EQ(r.checkPath(std::vector<Eigen::Vector2d>{{5, 5}, {20, 5}, {20, 25}}), std::optional<std::size_t>(2));
  EXPECT_EQ(r.checkPath(std::vector<Eigen::Vector3d>{{5, 5, 3}, {20, 15, 3}}), std::optional<std::size_t>(1));
  EXPECT_EQ(r.checkPath(std::vector<Eigen::Vector2d>{}), std::nullopt);
}

TEST(Region, SupervisorRegionRuleUsesThePolygon) {
  SupervisorConfig cfg;
  for (const auto& p : cShape()) cfg.region.insert(cfg.region.end(), {p.x(), p.y()});
  cfg.rules.region = rule(0.0, 1.0, "hold", false);
  Supervisor s(cfg);
  s.position(0.0, 20, 25);
  EXPECT_EQ(s.update(0.0).decision.action, Action::kNone);
  s.position(0.1, 20, 15);
  const auto d = s.update(0.1).decision;
  EXPECT_EQ(d.action, Action::kHold);
  EXPECT_EQ(d.reason, "position (20.0, 15.0) outside the operating region (nearest edge 5.0 m)");
}

