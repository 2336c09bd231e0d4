// scenario_check FILE: validates a scenario before anything starts (the simulator's strict loader plus the
// mission section); prints a one-line JSON summary, or the error naming the key and exits 2.
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <set>
#include <string>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/sim/scenario.h"

using namespace offshore_gnc;

namespace {
void checkMission(const std::string& path) {
  const YAML::Node m = YAML::LoadFile(path)["mission"];
  if (!m) return;
  if (!m.IsMap()) throw ConfigError("scenario '" + path + "': key 'mission' must be a mapping");
  const std::set<std::string> allowed{"expect", "max_sim_time"};
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
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: scenario_check FILE.yaml\n");
    return 2;
  }
  try {
    const sim::Scenario s = sim::loadScenario(argv[1]);
    checkMission(argv[1]);
    std::printf("{\"scenario\": \"%s\", \"obstacles\": %zu, \"targets\": %zu, \"ok\": true}\n", s.name.c_str(),
                s.world.buoys.size() + s.world.vessels.size(), s.world.targets.size());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
