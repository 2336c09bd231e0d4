// Real-time factor of the simulations with all sensors at their real rates (ROS-free: the simulation cores the
// simulator nodelets run). Prints one line per case and, last, one JSON object.
//   sim_bench [scenario.yaml] [simulated_seconds]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "offshore_gnc/sim/simulation.h"

using namespace offshore_gnc::sim;

namespace {
template <class F>
double rtf(double sim_seconds, F&& step) {
  const auto t0 = std::chrono::steady_clock::now();
  const double simulated = step(sim_seconds);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return simulated / wall;
}
}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "config/scenarios/pyhajarvi_map.yaml";
  const double seconds = argc > 2 ? std::atof(argv[2]) : 120.0;
  const Scenario sc = loadScenario(path);
  std::size_t returns = 0, bins = 0;  // consumed so that nothing is optimised away
  auto runUsv = [&](double secs) {
    UsvSimulation usv(sc, UsvSimulation::Config{});
    usv.setCommand({0.6, 0.0, 0.3});
    const long n = static_cast<long>(secs / usv.dt());
    for (long i = 0; i < n; ++i)
      if (usv.step().lidar)
        for (float r : usv.scan().ranges) returns += r == r;
    return usv.state().t;
  };
  auto runAuv = [&](double secs) {
    AuvSimulation auv(sc, AuvSimulation::Config{});
    auv.setThrusters({0.5, 0.4, 0.1, 0.1, 0.0});
    const long n = static_cast<long>(secs / auv.dt());
    for (long i = 0; i < n; ++i)
      if (auv.step().sonar) bins += auv.beam().intensities[10];
    return auv.state().t;
  };
  const double usv = rtf(seconds, runUsv);
  const double auv = rtf(seconds, runAuv);
  const double all = rtf(seconds, [&](double secs) {
    UsvSimulation u(sc, UsvSimulation::Config{});
    AuvSimulation a(sc, AuvSimulation::Config{});
    u.setCommand({0.6, 0.0, 0.3});
    a.setThrusters({0.5, 0.4, 0.1, 0.1, 0.0});
    const long n = static_cast<long>(secs / u.dt());
    for (long i = 0; i < n; ++i) {
      if (u.step().lidar) returns += u.scan().ranges.size();
      if (a.step().sonar) bins += a.beam().intensities.size();
    }
    return u.state().t;
  });
  std::printf("scenario %s, %.0f s simulated per case, step 10 ms, LiDAR 12.5 Hz x 4 x 1101 beams, sonar 20 Hz\n",
              path.c_str(), seconds);
  std::printf("USV alone (GPS-compass + LiDAR): %.0fx real time\n", usv);
  std::printf("AUV alone (AHRS + depth + sonar + INS estimate): %.0fx real time\n", auv);
  std::printf("both vehicles, all sensors, one core: %.0fx real time (checksum %zu)\n", all, (returns + bins) % 7);
  std::printf("{\"rtf_usv\": %.1f, \"rtf_auv\": %.1f, \"rtf_all\": %.1f, \"sim_seconds\": %.0f}\n", usv, auv, all,
              seconds);
  return 0;
}
