// scenario_check FILE [--faults PLAN]: validates a scenario before anything starts (the simulator's strict loader
// plus the mission section). --faults checks a fault plan (offshore_gnc::FaultPlan) and lists its faults with their
// vehicles and the supervisor's rule that answers each. Prints a one-line JSON summary (with the scenario's origin,
// which is the site of every node in simulation), or the error and exits 2.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "offshore_gnc/common/faults.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/sim/scenario.h"

using namespace offshore_gnc;

namespace {
void checkMission(const std::string& path) {
  const YAML::Node m = YAML::LoadFile(path)["mission"];
  if (!m) return;
  if (!m.IsMap()) throw ConfigError("scenario '" + path + "': key 'mission' must be a mapping");
  const std::set<std::string> allowed{"expect", "max_sim_time", "hold_time"};
  for (const auto& kv : m) {
    const std::string k = kv.first.as<std::string>();
    if (!allowed.count(k)) throw ConfigError("scenario '" + path + "': key 'mission." + k + "' is not a known key (typo?)");
  }
  if (m["expect"]) {
    const std::string e = m["expect"].as<std::string>();
    if (e != "target_reached" && e != "no_target")
      throw ConfigError("scenario '" + path + "': key 'mission.expect' = '" + e + "' is not one of: target_reached no_target");
  }
  if (m["max_sim_time"]) requireRange("mission.max_sim_time", m["max_sim_time"].as<double>(), 10.0, 86400.0);
  if (m["hold_time"]) requireRange("mission.hold_time", m["hold_time"].as<double>(), 0.0, 3600.0);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: scenario_check FILE.yaml [--faults PLAN]\n");
    return 2;
  }
  try {
    const sim::Scenario s = sim::loadScenario(argv[1]);
    checkMission(argv[1]);
    FaultPlan faults;
    for (int i = 2; i < argc; ++i) {
      if (std::string(argv[i]) == "--faults") {
        if (i + 1 >= argc) throw ConfigError("--faults needs a plan, e.g. --faults 'usbl@150+60'");
        faults = FaultPlan::parse(argv[++i]);
      } else {
        throw ConfigError(std::string("unknown argument '") + argv[i] + "' (usage: scenario_check FILE.yaml [--faults PLAN])");
      }
    }
    std::string listed;
    for (const auto& f : faults.faults()) {
      char one[224];
      char end[32] = "null";  // no end: to the end of the run
      if (std::isfinite(f.end)) std::snprintf(end, sizeof end, "%g", f.end);
      std::snprintf(one, sizeof one,
                    "%s{\"name\": \"%s\", \"vehicle\": \"%s\", \"rule\": \"%s\", \"start_s\": %g, \"end_s\": %s}",
                    listed.empty() ? "" : ", ", f.name.c_str(), findFaultKind(f.name)->vehicle,
                    findFaultKind(f.name)->rule, f.start, end);
      listed += one;
    }
    std::printf("{\"scenario\": \"%s\", \"origin\": [%.9f, %.9f, %.3f], \"obstacles\": %zu, \"targets\": %zu, "
                "\"faults\": [%s], \"ok\": true}\n",
                s.name.c_str(), s.origin.lat_deg, s.origin.lon_deg, s.origin.alt_m,
                s.world.buoys.size() + s.world.vessels.size(), s.world.targets.size(), listed.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
