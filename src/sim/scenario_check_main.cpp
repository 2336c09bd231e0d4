// scenario_check FILE [--faults PLAN]: validates a scenario before anything starts (the simulator's strict loader,
// its mission section included). --faults checks a fault plan (offshore_gnc::FaultPlan) and lists its faults with their
// vehicles and the supervisor's rule that answers each. Prints a one-line JSON summary (with the scenario's origin,
// which is the site of every node in simulation), or the error and exits 2.
#include <cmath>
#include <cstdio>
#include <string>

#include "offshore_gnc/common/faults.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/sim/scenario.h"

using namespace offshore_gnc;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: scenario_check FILE.yaml [--faults PLAN]\n");
    return 2;
  }
  try {
    const sim::Scenario s = sim::loadScenario(argv[1]);
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
                "\"mission\": {\"expect\": \"%s\", \"max_sim_time\": %g, \"hold_time\": %g, \"target_tolerance\": %g}, "
                "\"faults\": [%s], \"ok\": true}\n",
                s.name.c_str(), s.origin.lat_deg, s.origin.lon_deg, s.origin.alt_m,
                s.world.buoys.size() + s.world.vessels.size(), s.world.targets.size(),
                s.mission.expect_target ? "target_reached" : "no_target", s.mission.max_sim_time, s.mission.hold_time,
                s.mission.target_tolerance, listed.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
