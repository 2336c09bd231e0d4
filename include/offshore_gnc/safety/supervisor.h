#pragma once
// Per-vehicle safety supervisor (after COLA2's safety supervisor, DUNE's supervisors and MOOS-IvP's allstop):
// a fixed set of rules evaluated each control period from time-stamped inputs. A rule becomes active when its
// condition has held continuously for its detection time and is released when the condition has been clear
// continuously for its release time (time hysteresis: a signal toggling at a threshold never flaps the output).
// A rule without recovery, and every kAbort rule, latches until reset(). The decision is the highest action of
// the active rules.
//
// Manual control is not an action: setManual(true) wins over everything. The decision then says manual = true
// and action = kNone, i.e. no automatic action is commanded to the actuators (the operator has them); rules keep
// being evaluated and latching underneath, and active_rule / reason still name what the supervisor would do.
//
// Conditions change at the inputs' own times (sample-and-hold between samples), timeouts at last heard +
// timeout; update(t) only compares those times with t, so detection and release do not depend on the update
// rate. A source never heard counts as heard at the supervisor's start: the first time any method is given.
// Non-finite inputs are refused and counted ("bad_input"): they never trigger or clear a rule. ROS-free.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/safety/region.h"

namespace offshore_gnc {
namespace safety {

// Priority order: a higher value wins.
enum class Action { kNone, kWarn, kHold, kNeutral, kSurface, kAbort };
const char* actionName(Action a);  // "none", "warn", "hold", "neutral", "surface", "abort"
Action parseAction(const std::string& name);  // throws ConfigError on an unknown name

enum class Source { kGps, kNavigation, kLidar, kSonar, kUsbl, kDepth, kLink, kCommand };
constexpr std::size_t kSourceCount = 8;
const char* sourceName(Source s);  // "gps", "navigation", ...

// The rules, in table order (the first of equal actions is reported). A source's timeout rule is Rule(source).
enum class Rule {
  kGpsTimeout, kNavigationTimeout, kLidarTimeout, kSonarTimeout, kUsblTimeout, kDepthTimeout, kLinkTimeout,
  kCommandTimeout, kMaxDepth, kMinAltitude, kRegion, kBusOff, kJet, kCollision
};
constexpr std::size_t kRuleCount = 14;
const char* ruleName(Rule r);  // "gps_timeout", ..., "max_depth", "min_altitude", "region", "bus_off", "jet", "collision"

struct RuleConfig {
  double detection = 0.0;      // the condition must hold this long before the rule is active [s]
  double release = 2.0;        // and be clear this long before it is released [s]
  std::string action = "warn";  // actionName()s
  bool recovery = true;        // false: latched until reset() (kAbort always latches)
  static const ParamTable<RuleConfig>& table();
};

// One RuleConfig per Rule, as named members so that parameter files name them ("rules/max_depth/action").
struct RuleConfigs {
  RuleConfig gps_timeout, navigation_timeout, lidar_timeout, sonar_timeout, usbl_timeout, depth_timeout,
      link_timeout, command_timeout, max_depth, min_altitude, region, bus_off, jet, collision;
  RuleConfig& operator[](Rule r);
  const RuleConfig& operator[](Rule r) const;
  static const ParamTable<RuleConfigs>& table();
};

struct SupervisorConfig {
  // Thresholds; a value <= 0 disables its rule.
  double gps_timeout = 0.0, navigation_timeout = 0.0, lidar_timeout = 0.0, sonar_timeout = 0.0,
         usbl_timeout = 0.0, depth_timeout = 0.0, link_timeout = 0.0, command_timeout = 0.0;  // [s]
  double max_depth = 0.0;     // [m], positive down
  double min_altitude = 0.0;  // [m] above the bottom
  double allstop_ttc = 0.0;   // [s] all-stop when the time to collision is below this and no side is safe
  double collision_radius = 4.0;  // [m] the vehicle's footprint about its position for the time to collision
  std::vector<double> region;  // operating region x0, y0, x1, y1, ... in local NED [m]; empty disables
  bool bus_off_check = false;  // the CAN bus-off rule
  bool jet_check = false;      // the waterjets-answering rule
  RuleConfigs rules;
  double& timeout(Source s);
  double timeout(Source s) const;
  static const ParamTable<SupervisorConfig>& table();
};

// The SafetySupervisor nodelet's own parameters: `vehicle` (required: the preset is never guessed) picks the rules'
// preset, `rate` the supervisor's steps; `manual_timeout` is the USV's (a manual command this old is released).
struct SupervisorNodeParams {
  std::string vehicle = "usv";
  double rate = 10.0;            // [Hz]
  double manual_timeout = 1.0;   // [s]
  static const ParamTable<SupervisorNodeParams>& table();
};

// USV: gps, navigation, lidar, link, command timeouts, region (a 2 km square around the origin), collision,
// bus off, jets. AUV: navigation, sonar, usbl, depth, link, command timeouts, max depth 50 m and min altitude
// 2 m (both -> surface).
SupervisorConfig usvDefaults();
SupervisorConfig auvDefaults();

// One row per enabled rule, for generated docs and diagnostics.
struct RuleInfo {
  std::string name, condition;  // condition: "depth > 50 m", "gps not heard for more than 1 s", ...
  double detection = 0.0, release = 0.0;
  Action action = Action::kNone;
  bool recovery = true;
};
std::vector<RuleInfo> ruleTable(const SupervisorConfig& cfg);

struct Decision {
  Action action = Action::kNone;  // kNone when manual
  std::string active_rule;        // the rule behind the highest action ("" when none is active)
  std::string reason;             // one sentence: "gps silent for 2.1 s (timeout 1.0 s)"
  bool manual = false;
};

// A rule becoming active or released (or "manual" engaged / released): the nodelet logs each and publishes it
// latched. Recovery is never silent: a release is a transition too.
struct Transition {
  double t = 0.0;
  std::string rule;
  bool from_active = false, to_active = false;
  Action action = Action::kNone;  // the rule's action
  std::string reason;
};

struct SupervisorOutput {
  Decision decision;
  std::vector<Transition> transitions;  // since the previous update(), in order
};

class Supervisor {
 public:
  explicit Supervisor(const SupervisorConfig& cfg);  // throws ConfigError (table, region)

  void heard(Source s, double t);
  void depth(double t, double z);
  void altitude(double t, double a);  // NaN: unknown (no bottom lock): neither starts nor clears the condition
  void position(double t, double x, double y);
  void busOff(double t, bool off);
  void jetAnswering(double t, int jet, bool answering);
  void timeToCollision(double t, double ttc, bool safe_side_exists);  // ttc = +inf: not on a collision course
  void setManual(bool manual);  // reported (with a transition) at the next update()

  SupervisorOutput update(double t);
  // Releases every active rule whose condition is clear at t, latched ones included (transitions are reported
  // by the next update()); a rule whose condition still holds stays active.
  void reset(double t);

  bool active(Rule r) const { return rules_[static_cast<std::size_t>(r)].active; }
  const std::optional<Region>& region() const { return region_; }
  const SupervisorConfig& config() const { return cfg_; }
  const Counters& counters() const { return counters_; }

 private:
  struct State {
    bool enabled = false, cond = false, active = false;
    double since = 0.0;  // when cond last changed
    std::string reason;  // at activation
  };
  bool refuse(double t, bool ok = true);  // counts and returns true when t or the value is not usable
  void set(Rule r, bool cond, double t);
  void checkSilence(std::size_t i, double t);
  bool recoverable(Rule r) const;
  std::string describe(Rule r, double t) const;
  void transition(Rule r, double t, bool to_active, const std::string& reason);

  SupervisorConfig cfg_;
  std::optional<Region> region_;
  State rules_[kRuleCount];
  Action action_[kRuleCount];
  double last_heard_[kSourceCount] = {};
  bool ever_heard_[kSourceCount] = {};
  std::optional<double> start_;
  double last_t_ = 0.0;  // of the last good update()
  double depth_ = 0.0, altitude_ = 0.0, x_ = 0.0, y_ = 0.0, ttc_ = 0.0;
  bool safe_side_ = false;
  std::map<int, bool> jets_;
  bool manual_ = false, manual_reported_ = false;
  std::vector<Transition> pending_;
  Counters counters_;
};

}  // namespace safety
}  // namespace offshore_gnc
