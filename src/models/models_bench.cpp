// Model-only speed: steps per second and real-time factor of each vehicle model at the simulators' step
// (dt = 0.01 s) with a time-varying command and the lake environment (current, wind, waves), on one core.
// Prints one JSON object. Usage: models_bench [simulated_seconds=600]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

#include "offshore_gnc/models/auv.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/models/usv.h"

using namespace offshore_gnc::models;

namespace {
// Runs `step(k)` for the simulated duration; returns steps per wall-clock second.
double rate(long steps, const std::function<void(long)>& step) {
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) step(k);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return steps / s;
}
}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 600.0, dt = 0.01;
  const long steps = std::lround(seconds / dt);
  const Environment env(loadEnvironmentParams("config/models/environment_lake.yaml"));
  UsvParams up = loadUsvParams("config/models/usv.yaml");
  UsvModel usv(up);
  up.type = UsvModelType::Nomoto;
  UsvModel nomoto(up);
  AuvModel girona(loadAuvParams("config/models/girona500.yaml"));
  AuvModel acolor(loadAuvParams("config/models/acolor.yaml"));
  auto joy = [&](long k) { return UsvCommand{0.8, 0.0, std::sin(k * dt * 0.2)}; };
  const double r_usv = rate(steps, [&](long k) { usv.step(dt, joy(k), env); });
  const double r_nomoto = rate(steps, [&](long k) { nomoto.step(dt, joy(k), env); });
  Eigen::VectorXd c5(5), c6(6);
  const double r_g500 = rate(steps, [&](long k) {
    const double s = std::sin(k * dt * 0.3);
    c5 << -0.6 + 0.2 * s, -0.6 - 0.2 * s, 0.1 * s, 0.1 * s, 0.2 * s;
    girona.step(dt, c5, env);
  });
  const double r_acolor = rate(steps, [&](long k) {
    const double s = std::sin(k * dt * 0.3);
    c6 << 0.5, 0.5 + 0.2 * s, 0.5 - 0.2 * s, 0.5, 0.1 * s, 0.1 * s;
    acolor.step(dt, c6, env);
  });
  std::printf("usv 3-DOF: %.0f steps/s, usv Nomoto: %.0f, girona500: %.0f, aColor: %.0f (dt %.3f s, %.0f s simulated)\n",
              r_usv, r_nomoto, r_g500, r_acolor, dt, seconds);
  std::printf(
      "{\"dt\": %.3f, \"steps_per_s_usv\": %.0f, \"rtf_usv\": %.0f, \"rtf_usv_nomoto\": %.0f, \"rtf_girona500\": %.0f, "
      "\"rtf_acolor\": %.0f}\n",
      dt, r_usv, r_usv * dt, r_nomoto * dt, r_g500 * dt, r_acolor * dt);
  return 0;
}
