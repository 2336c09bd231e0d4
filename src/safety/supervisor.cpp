// Safety supervisor: conditions from time-stamped inputs, detection / release hysteresis, latching, priorities.
#include "offshore_gnc/safety/supervisor.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace safety {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = 1e-9;  // detection / release compare times: sums of 0.1 s steps must not miss by an ulp

const char* const kActions[] = {"none", "warn", "hold", "neutral", "surface", "abort"};
const char* const kSources[] = {"gps", "navigation", "lidar", "sonar", "usbl", "depth", "link", "command"};
const char* const kRules[] = {"gps_timeout", "navigation_timeout", "lidar_timeout", "sonar_timeout",
                              "usbl_timeout", "depth_timeout", "link_timeout", "command_timeout",
                              "max_depth", "min_altitude", "region", "bus_off", "jet", "collision"};
const char* const kSourceDocs[] = {"GPS-compass fixes", "the navigation estimate", "LiDAR scans", "sonar scans",
                                   "USBL fixes", "the depth sensor", "the relay link to the other vehicle",
                                   "the control command stream"};
RuleConfig RuleConfigs::* const kRuleMembers[] = {
    &RuleConfigs::gps_timeout, &RuleConfigs::navigation_timeout, &RuleConfigs::lidar_timeout,
    &RuleConfigs::sonar_timeout, &RuleConfigs::usbl_timeout, &RuleConfigs::depth_timeout,
    &RuleConfigs::link_timeout, &RuleConfigs::command_timeout, &RuleConfigs::max_depth,
    &RuleConfigs::min_altitude, &RuleConfigs::region, &RuleConfigs::bus_off, &RuleConfigs::jet,
    &RuleConfigs::collision};
double SupervisorConfig::* const kTimeouts[] = {
    &SupervisorConfig::gps_timeout, &SupervisorConfig::navigation_timeout, &SupervisorConfig::lidar_timeout,
    &SupervisorConfig::sonar_timeout, &SupervisorConfig::usbl_timeout, &SupervisorConfig::depth_timeout,
    &SupervisorConfig::link_timeout, &SupervisorConfig::command_timeout};
static_assert(sizeof kRules / sizeof *kRules == kRuleCount && sizeof kRuleMembers / sizeof *kRuleMembers == kRuleCount);
static_assert(sizeof kSources / sizeof *kSources == kSourceCount && sizeof kTimeouts / sizeof *kTimeouts == kSourceCount);

std::string fmt(const char* f, ...) __attribute__((format(printf, 1, 2)));
std::string fmt(const char* f, ...) {
  char b[256];
  va_list ap;
  va_start(ap, f);
  std::vsnprintf(b, sizeof b, f, ap);
  va_end(ap);
  return b;
}

std::size_t idx(Rule r) { return static_cast<std::size_t>(r); }
bool isTimeout(Rule r) { return idx(r) < kSourceCount; }

bool enabled(const SupervisorConfig& c, Rule r) {
  if (isTimeout(r)) return c.timeout(static_cast<Source>(idx(r))) > 0.0;
  switch (r) {
    case Rule::kMaxDepth: return c.max_depth > 0.0;
    case Rule::kMinAltitude: return c.min_altitude > 0.0;
    case Rule::kRegion: return !c.region.empty();
    case Rule::kBusOff: return c.bus_off_check;
    case Rule::kJet: return c.jet_check;
    case Rule::kCollision: return c.allstop_ttc > 0.0;
    default: return false;
  }
}

RuleConfig rule(double detection, double release, const char* action, bool recovery) {
  RuleConfig r;
  r.detection = detection, r.release = release, r.action = action, r.recovery = recovery;
  return r;
}

}  // namespace

const char* actionName(Action a) { return kActions[static_cast<int>(a)]; }
const char* sourceName(Source s) { return kSources[static_cast<int>(s)]; }
const char* ruleName(Rule r) { return kRules[idx(r)]; }

Action parseAction(const std::string& name) {
  for (int i = 0; i < 6; ++i)
    if (name == kActions[i]) return static_cast<Action>(i);
  throw ConfigError("unknown safety action '" + name + "' (none, warn, hold, neutral, surface, abort)");
}

RuleConfig& RuleConfigs::operator[](Rule r) { return this->*kRuleMembers[idx(r)]; }
const RuleConfig& RuleConfigs::operator[](Rule r) const { return this->*kRuleMembers[idx(r)]; }
double& SupervisorConfig::timeout(Source s) { return this->*kTimeouts[static_cast<int>(s)]; }
double SupervisorConfig::timeout(Source s) const { return this->*kTimeouts[static_cast<int>(s)]; }

const ParamTable<RuleConfig>& RuleConfig::table() {
  using P = RuleConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("detection", &P::detection, 0.0, 600.0, "s", "the condition must hold this long before the rule is active")
      .number("release", &P::release, 0.0, 600.0, "s", "the condition must be clear this long before release")
      .choice("action", &P::action, std::vector<std::string>(kActions, kActions + 6), "what the rule commands while active")
      .flag("recovery", &P::recovery, "released once clear (false: latched until reset; abort always latches)");
  return t;
}

const ParamTable<RuleConfigs>& RuleConfigs::table() {
  static const ParamTable<RuleConfigs> t = [] {
    ParamTable<RuleConfigs> tb;
    for (std::size_t i = 0; i < kRuleCount; ++i) tb.nest(std::string(kRules[i]) + "/", kRuleMembers[i], RuleConfig::table());
    return tb;
  }();
  return t;
}

const ParamTable<SupervisorConfig>& SupervisorConfig::table() {
  using P = SupervisorConfig;
  static const ParamTable<P> t = [] {
    ParamTable<P> tb;
    for (std::size_t i = 0; i < kSourceCount; ++i)
      tb.number(std::string(kSources[i]) + "_timeout", kTimeouts[i], -1.0, 3600.0, "s",
               ("silence of " + std::string(kSourceDocs[i]) + " before its rule's condition holds (<= 0 disables)").c_str());
    tb.number("max_depth", &P::max_depth, -1.0, 11000.0, "m", "deeper than this is a fault (<= 0 disables)")
        .number("min_altitude", &P::min_altitude, -1.0, 1000.0, "m", "closer to the bottom is a fault (<= 0 disables)")
        .number("allstop_ttc", &P::allstop_ttc, -1.0, 600.0, "s",
                "all-stop below this time to collision when no side is safe (<= 0 disables)")
        .number("collision_radius", &P::collision_radius, 0.0, 1000.0, "m",
                "the vehicle's footprint about its position for the time to collision (half its length)")
        .numbers("region", &P::region, 0, -1e7, 1e7, "m", "operating region x0, y0, x1, y1, ... in local NED (empty disables)")
        .flag("bus_off_check", &P::bus_off_check, "CAN bus off is a fault")
        .flag("jet_check", &P::jet_check, "a waterjet not answering is a fault")
        .nest("rules/", &P::rules, RuleConfigs::table());
    return tb;
  }();
  return t;
}

const ParamTable<SupervisorNodeParams>& SupervisorNodeParams::table() {
  using P = SupervisorNodeParams;
  static const ParamTable<P> t = ParamTable<P>()
      .choice("vehicle", &P::vehicle, {"usv", "auv"}, "the vehicle whose preset the rules start from (required)")
      .number("rate", &P::rate, 0.1, 1000.0, "Hz", "supervisor steps per second")
      .number("manual_timeout", &P::manual_timeout, 0.05, 60.0, "s",
              "USV: a manual command this old no longer holds autonomy off");
  return t;
}

SupervisorConfig usvDefaults() {
  SupervisorConfig c;
  // A few samples' worth (GPS 10 Hz, LiDAR 10 Hz): long enough not to act on one late message, short enough
  // that the boat has moved a few metres at most.
  c.gps_timeout = 3.0, c.navigation_timeout = 3.0, c.lidar_timeout = 3.0, c.link_timeout = 10.0, c.command_timeout = 3.0;
  // From cruise (1.6 m/s) the model stops in 6.3 m on full astern (4 s of cruise) and coasts 56 m and more on
  // neutral jets (docs/safety.md): all-stop is a hold (DP brakes on the reversing buckets), 8 s before contact (the
  // 4 s of a full-astern stop doubled for the DP's gentler braking and the LiDAR -> supervisor latency).
  c.allstop_ttc = 8.0;
  c.collision_radius = 4.0;  // half the 8 m hull: head on, the bow touches first
  c.region = {-1000, -1000, 1000, -1000, 1000, 1000, -1000, 1000};
  c.bus_off_check = c.jet_check = true;
  auto& r = c.rules;
  r.gps_timeout = r.navigation_timeout = rule(0.0, 2.0, "neutral", true);  // no position: DP impossible
  r.lidar_timeout = rule(0.0, 2.0, "hold", true);                          // blind to obstacles: stop
  r.link_timeout = rule(0.0, 5.0, "warn", true);  // the USV mission itself holds when its peer is lost
  r.command_timeout = rule(0.0, 2.0, "neutral", true);
  r.region = rule(1.0, 5.0, "hold", false);  // OpRegion: a breach latches until the operator resets
  r.collision = rule(0.0, 3.0, "hold", true);
  r.bus_off = rule(0.5, 2.0, "neutral", true);
  r.jet = rule(1.0, 2.0, "neutral", true);
  return c;
}

SupervisorConfig auvDefaults() {
  SupervisorConfig c;
  c.navigation_timeout = 3.0, c.sonar_timeout = 5.0, c.usbl_timeout = 30.0, c.depth_timeout = 3.0;
  c.link_timeout = 60.0, c.command_timeout = 3.0;
  c.max_depth = 50.0, c.min_altitude = 2.0;
  auto& r = c.rules;
  // COLA2 surfaces without navigation; recoverable, since the USBL navigation has no estimate until its first
  // fix (the AUV waits at the surface) and comes back after a gap. The depth sensor likewise.
  r.navigation_timeout = rule(0.0, 5.0, "surface", true);
  r.depth_timeout = rule(0.0, 2.0, "surface", true);
  r.sonar_timeout = r.usbl_timeout = rule(0.0, 2.0, "warn", true);
  // The AUV searches on its own (thesis ch. 5): a lost link is the USV's concern (it holds); here only a warning.
  r.link_timeout = rule(0.0, 5.0, "warn", true);
  r.command_timeout = rule(0.0, 2.0, "neutral", true);
  r.max_depth = rule(1.0, 5.0, "surface", false);
  r.min_altitude = rule(1.0, 5.0, "surface", true);
  return c;
}

std::vector<RuleInfo> ruleTable(const SupervisorConfig& c) {
  std::vector<RuleInfo> rows;
  for (std::size_t i = 0; i < kRuleCount; ++i) {
    const Rule r = static_cast<Rule>(i);
    if (!enabled(c, r)) continue;
    RuleInfo row;
    row.name = kRules[i];
    if (isTimeout(r)) row.condition = fmt("%s not heard for more than %g s", kSources[i], c.timeout(Source(i)));
    if (r == Rule::kMaxDepth) row.condition = fmt("depth > %g m", c.max_depth);
    if (r == Rule::kMinAltitude) row.condition = fmt("altitude < %g m (unknown altitude never triggers)", c.min_altitude);
    if (r == Rule::kRegion) row.condition = fmt("position outside the operating region (%zu vertices)", c.region.size() / 2);
    if (r == Rule::kBusOff) row.condition = "CAN bus off";
    if (r == Rule::kJet) row.condition = "a waterjet not answering";
    if (r == Rule::kCollision) row.condition = fmt("time to collision < %g s and no safe side", c.allstop_ttc);
    row.detection = c.rules[r].detection, row.release = c.rules[r].release;
    row.action = parseAction(c.rules[r].action);
    row.recovery = c.rules[r].recovery && row.action != Action::kAbort;
    rows.push_back(row);
  }
  return rows;
}

Supervisor::Supervisor(const SupervisorConfig& cfg) : cfg_(cfg) {
  SupervisorConfig::table().validate(cfg);
  if (!cfg.region.empty()) region_ = Region::fromList(cfg.region);
  for (std::size_t i = 0; i < kRuleCount; ++i) {
    rules_[i].enabled = enabled(cfg, Rule(i));
    rules_[i].since = -kInf;  // clear forever: nothing to release
    action_[i] = parseAction(cfg.rules[Rule(i)].action);
  }
}

bool Supervisor::refuse(double t, bool ok) {
  if (!std::isfinite(t) || !ok) {
    counters_.increment("bad_input");
    return true;
  }
  if (!start_) {  // the supervisor's start: sources never heard count from here
    start_ = t;
    for (double& h : last_heard_) h = t;
  }
  return false;
}

void Supervisor::set(Rule r, bool cond, double t) {
  State& s = rules_[idx(r)];
  if (!s.enabled || s.cond == cond) return;
  s.cond = cond;
  s.since = std::max(t, s.since);  // an out-of-order sample must not back-date a change
}

void Supervisor::checkSilence(std::size_t i, double t) {
  const double to = cfg_.timeout(Source(i));
  if (to > 0.0 && t - last_heard_[i] > to) set(Rule(i), true, last_heard_[i] + to);
}

void Supervisor::heard(Source s, double t) {
  if (refuse(t)) return;
  const auto i = static_cast<std::size_t>(s);
  checkSilence(i, t);  // a silence that ended before any update() still counts as one
  set(Rule(i), false, t);
  last_heard_[i] = std::max(last_heard_[i], t);
  ever_heard_[i] = true;
}

void Supervisor::depth(double t, double z) {
  if (refuse(t, std::isfinite(z))) return;
  depth_ = z;
  set(Rule::kMaxDepth, z > cfg_.max_depth, t);
}

void Supervisor::altitude(double t, double a) {
  if (std::isnan(a)) {  // unknown, e.g. no bottom lock: not bad input, and no evidence either way
    refuse(t);
    return;
  }
  if (refuse(t, std::isfinite(a))) return;
  altitude_ = a;
  set(Rule::kMinAltitude, a < cfg_.min_altitude, t);
}

void Supervisor::position(double t, double x, double y) {
  if (refuse(t, std::isfinite(x) && std::isfinite(y))) return;
  x_ = x, y_ = y;
  if (region_) set(Rule::kRegion, !region_->contains(x, y), t);
}

void Supervisor::busOff(double t, bool off) {
  if (!refuse(t)) set(Rule::kBusOff, off, t);
}

void Supervisor::jetAnswering(double t, int jet, bool answering) {
  if (refuse(t)) return;
  jets_[jet] = answering;
  bool silent = false;
  for (const auto& j : jets_) silent = silent || !j.second;
  set(Rule::kJet, silent, t);
}

void Supervisor::timeToCollision(double t, double ttc, bool safe_side_exists) {
  if (refuse(t, !std::isnan(ttc) && ttc >= 0.0)) return;  // +inf: no collision course
  ttc_ = ttc, safe_side_ = safe_side_exists;
  set(Rule::kCollision, ttc < cfg_.allstop_ttc && !safe_side_exists, t);
}

void Supervisor::setManual(bool manual) { manual_ = manual; }

bool Supervisor::recoverable(Rule r) const { return cfg_.rules[r].recovery && action_[idx(r)] != Action::kAbort; }

std::string Supervisor::describe(Rule r, double t) const {
  const bool on = rules_[idx(r)].cond;
  if (isTimeout(r)) {
    const std::size_t i = idx(r);
    const double to = cfg_.timeout(Source(i)), dt = t - last_heard_[i];
    if (!ever_heard_[i]) return fmt("%s never heard in %.1f s since start (timeout %.1f s)", kSources[i], dt, to);
    return fmt(on ? "%s silent for %.1f s (timeout %.1f s)" : "%s heard %.1f s ago (timeout %.1f s)", kSources[i], dt, to);
  }
  switch (r) {
    case Rule::kMaxDepth:
      return fmt(on ? "depth %.2f m beyond max %.2f m" : "depth %.2f m within max %.2f m", depth_, cfg_.max_depth);
    case Rule::kMinAltitude:
      return fmt(on ? "altitude %.2f m below min %.2f m" : "altitude %.2f m above min %.2f m", altitude_,
                 cfg_.min_altitude);
    case Rule::kRegion:
      return fmt("position (%.1f, %.1f) %s the operating region (nearest edge %s)", x_, y_, on ? "outside" : "inside",
                 region_ ? formatDistance(region_->distanceToEdge(x_, y_)).c_str() : "-");
    case Rule::kBusOff: return on ? "CAN bus off" : "CAN bus on";
    case Rule::kJet: {
      std::string s;
      for (const auto& j : jets_)
        if (!j.second) s += (s.empty() ? "" : ", ") + std::to_string(j.first);
      return on ? "waterjet " + s + " not answering" : "all waterjets answering";
    }
    case Rule::kCollision:
      return fmt(on ? "time to collision %.1f s below allstop %.1f s and no safe side"
                    : "time to collision %.1f s (allstop %.1f s)%s",
                 ttc_, cfg_.allstop_ttc, on ? "" : (safe_side_ ? ", a safe side exists" : ""));
    default: return "";
  }
}

void Supervisor::transition(Rule r, double t, bool to_active, const std::string& reason) {
  rules_[idx(r)].active = to_active;
  pending_.push_back({t, kRules[idx(r)], !to_active, to_active, action_[idx(r)], reason});
  counters_.increment("transitions");
}

void Supervisor::reset(double t) {
  if (refuse(t)) return;
  for (std::size_t i = 0; i < kSourceCount; ++i) checkSilence(i, t);
  for (std::size_t i = 0; i < kRuleCount; ++i)
    if (rules_[i].active && !rules_[i].cond) transition(Rule(i), t, false, describe(Rule(i), t) + ": released by reset");
}

SupervisorOutput Supervisor::update(double t) {
  if (refuse(t)) t = last_t_;  // a bad clock neither advances nor resets the timers
  last_t_ = t;
  for (std::size_t i = 0; i < kSourceCount; ++i) checkSilence(i, t);
  for (std::size_t i = 0; i < kRuleCount; ++i) {
    State& s = rules_[i];
    const Rule r = Rule(i);
    const RuleConfig& rc = cfg_.rules[r];
    if (!s.enabled) continue;
    if (!s.active && s.cond && t - s.since + kEps >= rc.detection) {
      s.reason = describe(r, t);
      transition(r, t, true, s.reason);
    } else if (s.active && !s.cond && recoverable(r) && t - s.since + kEps >= rc.release) {
      transition(r, t, false, describe(r, t) + fmt(", clear for %.1f s: released", t - s.since));
    }
  }
  if (manual_ != manual_reported_) {
    manual_reported_ = manual_;
    pending_.push_back({t, "manual", !manual_, manual_, Action::kNone,
                        manual_ ? "manual control engaged: no automatic action commanded"
                                : "manual control released: automatic supervision resumed"});
    counters_.increment("transitions");
  }
  SupervisorOutput out;
  int best = -1;
  for (std::size_t i = 0; i < kRuleCount; ++i)  // strictly higher: the first rule of equal actions is reported
    if (rules_[i].active && (best < 0 || action_[i] > action_[best])) best = static_cast<int>(i);
  if (best >= 0) {
    const Rule r = Rule(best);
    const State& s = rules_[best];
    out.decision.action = action_[best];
    out.decision.active_rule = kRules[best];
    out.decision.reason = s.cond ? describe(r, t)
                                 : s.reason + (recoverable(r) ? fmt(" (clear now, released after %.1f s clear)",
                                                                    cfg_.rules[r].release)
                                                              : std::string(" (clear now, latched until reset)"));
  }
  out.decision.manual = manual_;
  if (manual_) out.decision.action = Action::kNone;  // the operator has the actuators
  out.transitions.swap(pending_);
  return out;
}

}  // namespace safety
}  // namespace offshore_gnc
