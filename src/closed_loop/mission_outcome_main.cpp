// mission_outcome: the main job's report judges its run with the ROS-free mission's own code (closed_loop/outcome.h,
// sim/contact.h), given what its bags recorded: the USV's true track (CSV t,north,east,yaw) against the scenario's
// shapes with the hull of config/usv.yaml, and the facts only the job knows.
//   mission_outcome --scenario FILE --usv-track CSV [--config DIR] [--held 0|1] [--auv-no-target 0|1]
//                   [--target-error M] [--final-distance M] [--died 0|1] [--safety-stop 0|1]
// Prints {"outcome": "...", "min_clearance_m": x} (null without obstacles); exit 2 on bad input.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "offshore_gnc/closed_loop/outcome.h"
#include "offshore_gnc/common/param_yaml.h"
#include "offshore_gnc/mission/mission.h"
#include "offshore_gnc/sim/contact.h"
#include "offshore_gnc/sim/scenario.h"

using namespace offshore_gnc;

namespace {
double number(const std::string& option, const std::string& text) {
  if (text == "nan") return std::nan("");
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') throw ConfigError(option + " '" + text + "' is not a number");
  return v;
}
}  // namespace

int main(int argc, char** argv) {
  try {
    std::string scenario, track, config = OFFSHORE_GNC_CONFIG_DIR;
    closed_loop::OutcomeFacts f;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (i + 1 >= argc) throw ConfigError(a + " needs a value");
      const std::string v = argv[++i];
      if (a == "--scenario") scenario = v;
      else if (a == "--usv-track") track = v;
      else if (a == "--config") config = v;
      else if (a == "--held") f.held = number(a, v) != 0.0;
      else if (a == "--auv-no-target") f.auv_no_target = number(a, v) != 0.0;
      else if (a == "--target-error") f.target_error_m = number(a, v), f.target_reported = !std::isnan(f.target_error_m);
      else if (a == "--final-distance") f.final_distance_m = number(a, v);
      else if (a == "--died") f.stack_died = number(a, v) != 0.0;
      else if (a == "--safety-stop") f.safety_stop = number(a, v) != 0.0;
      else throw ConfigError("unknown option " + a);
    }
    if (scenario.empty() || track.empty()) throw ConfigError("--scenario FILE and --usv-track CSV are required");
    const sim::Scenario sc = sim::loadScenario(scenario);
    f.expect_target = sc.mission.expect_target;
    f.target_tolerance_m = sc.mission.target_tolerance;
    mission::UsvMissionParams usv_mission;  // its stand-off: how far short of the target the USV holds
    const std::string mission_file = config + "/mission/usv.yaml";
    readParamsYaml(loadYamlFile(mission_file), mission::UsvMissionParams::table(), usv_mission, mission_file);
    f.station_tolerance_m = usv_mission.standoff + sc.mission.target_tolerance;
    sim::HullFootprint hull;
    const std::string vehicle = config + "/usv.yaml";
    readParamsYaml(loadYamlFile(vehicle), sim::HullFootprint::table(), hull, vehicle);
    hull.validate();
    std::ifstream in(track);
    if (!in) throw ConfigError("cannot read the track '" + track + "'");
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      std::stringstream ss(line);
      double t, n, e, yaw;
      char c1, c2, c3;
      if (!(ss >> t >> c1 >> n >> c2 >> e >> c3 >> yaw) || !std::isfinite(n + e + yaw)) continue;
      f.min_clearance_m = std::min(f.min_clearance_m, sim::hullClearance(hull, {n, e}, yaw, sc.world));
    }
    char clearance[32] = "null";
    if (std::isfinite(f.min_clearance_m)) std::snprintf(clearance, sizeof clearance, "%.4f", f.min_clearance_m);
    std::printf("{\"outcome\": \"%s\", \"min_clearance_m\": %s}\n", closed_loop::toString(closed_loop::classify(f)),
                clearance);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mission_outcome: %s\n", e.what());
    return 2;
  }
}
