// mission_outcome: the main job's report judges its run with the ROS-free mission's own code (closed_loop/outcome.h,
// sim/contact.h), given what its bags recorded: the USV's true track (CSV t,north,east,yaw) against the scenario's
// shapes with the hull of config/usv.yaml, the AUV's true track (CSV t,north,east,down) against the same hull (the
// AUV a disc of its config's length, counted within kAuvContactDepth of the surface), and the facts only the job
// knows.
//   mission_outcome --scenario FILE --usv-track CSV [--auv-track CSV --auv-model M] [--config DIR] [--held 0|1]
//                   [--recovered 0|1] [--auv-no-target 0|1] [--target-error M] [--final-distance M] [--died 0|1]
//                   [--safety-stop 0|1]
// Prints {"outcome": "...", "min_clearance_m": x, "usv_auv_min_clearance_m": x, "recovery_distance_m": x} (null when
// there is nothing to measure; the last at the end of the tracks); exit 2 on bad input.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "offshore_gnc/closed_loop/outcome.h"
#include "offshore_gnc/closed_loop/stacks.h"
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

// The rows of a CSV of four numbers per line after its header (non-finite rows skipped).
std::vector<std::array<double, 4>> readTrack(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError("cannot read the track '" + path + "'");
  std::vector<std::array<double, 4>> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::array<double, 4> r{};
    char c1, c2, c3;
    if ((ss >> r[0] >> c1 >> r[1] >> c2 >> r[2] >> c3 >> r[3]) && std::isfinite(r[1] + r[2] + r[3])) rows.push_back(r);
  }
  return rows;
}

std::string json(double v) {
  if (!std::isfinite(v)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.4f", v);
  return b;
}
}  // namespace

int main(int argc, char** argv) {
  try {
    std::string scenario, track, auv_track, auv_model = "girona500", config = OFFSHORE_GNC_CONFIG_DIR;
    closed_loop::OutcomeFacts f;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (i + 1 >= argc) throw ConfigError(a + " needs a value");
      const std::string v = argv[++i];
      if (a == "--scenario") scenario = v;
      else if (a == "--usv-track") track = v;
      else if (a == "--auv-track") auv_track = v;
      else if (a == "--auv-model") auv_model = v;
      else if (a == "--config") config = v;
      else if (a == "--held") f.held = number(a, v) != 0.0;
      else if (a == "--recovered") f.recovered = number(a, v) != 0.0;
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
    const auto usv = readTrack(track);
    for (const auto& r : usv)  // the scenario's vessels where they were at the sample's time
      f.min_clearance_m = std::min(f.min_clearance_m, sim::hullClearance(hull, {r[1], r[2]}, r[3], sc.world, r[0]));
    // the hull against the AUV: each USV sample with the AUV's nearest in time (both bags on the one simulated clock)
    double recovery_distance = NAN;
    if (!auv_track.empty()) {
      const double length = closed_loop::auvLength(config, auv_model);
      const auto auv = readTrack(auv_track);
      for (const auto& r : usv) {
        const auto it = std::lower_bound(auv.begin(), auv.end(), r[0],
                                         [](const std::array<double, 4>& x, double t) { return x[0] < t; });
        if (it == auv.end() || std::abs((*it)[0] - r[0]) > 0.25) continue;
        const double c = closed_loop::auvClearance(hull, {r[1], r[2]}, r[3], {(*it)[1], (*it)[2]}, length);
        if ((*it)[3] < closed_loop::kAuvContactDepth) f.auv_clearance_m = std::min(f.auv_clearance_m, c);
        recovery_distance = c;
      }
    }
    std::printf("{\"outcome\": \"%s\", \"min_clearance_m\": %s, \"usv_auv_min_clearance_m\": %s, \"recovery_distance_m\": %s}\n",
                closed_loop::toString(closed_loop::classify(f)), json(f.min_clearance_m).c_str(),
                json(f.auv_clearance_m).c_str(), json(recovery_distance).c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mission_outcome: %s\n", e.what());
    return 2;
  }
}
