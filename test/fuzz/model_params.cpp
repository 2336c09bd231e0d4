// libFuzzer target: arbitrary text through the model parameter loaders (USV, AUV, environment; the first byte
// picks which). Parameters are accepted, build a model and give a finite state over 20 s of full commands, or
// are refused with a ConfigError; any other exception, a non-finite state or a crash is a finding. Built and run
// by `scripts/fuzz model_params SECONDS`.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/auv.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/models/usv.h"

using namespace offshore_gnc;
using namespace offshore_gnc::models;

namespace {
[[noreturn]] void violated(const std::string& what) {
  std::fprintf(stderr, "model parameter invariant violated: %s\n", what.c_str());
  std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const int which = data[0] % 3;
  try {
    if (which == 0) {
      UsvParams p;
      try {
        p = usvParamsFromYaml(text, "fuzz");
      } catch (const ConfigError&) {
        return 0;
      }
      UsvModel m(p);  // accepted parameters must make a model
      const Environment env;
      for (int i = 0; i < 200; ++i) m.step(0.1, UsvCommand{1.0, 0.0, i < 100 ? 1.0 : -1.0}, env);
      if (!isFinite(m.state())) violated("accepted USV parameters give a non-finite state");
    } else if (which == 1) {
      AuvParams p;
      try {
        p = auvParamsFromYaml(text, "fuzz");
      } catch (const ConfigError&) {
        return 0;
      }
      AuvModel m(p);
      const Environment env;
      const Eigen::VectorXd cmd = Eigen::VectorXd::Ones(m.thrusters());
      for (int i = 0; i < 200; ++i) m.step(0.1, cmd, env);
      if (!isFinite(m.state())) violated("accepted AUV parameters give a non-finite state");
    } else {
      EnvironmentParams p;
      try {
        p = environmentParamsFromYaml(text, "fuzz");
      } catch (const ConfigError&) {
        return 0;
      }
      const Environment env(p);
      VehicleState s;
      s.position = {3.0, -4.0, 2.0};
      for (double t = 0; t < 600; t += 7.3) {
        const WaveMotion w = env.wave(t, s, Hull());
        if (!env.current(t).allFinite() || !env.wind(t).allFinite() || !w.displacement.allFinite() ||
            !w.rate.allFinite() || !std::isfinite(w.roll + w.pitch + w.yaw) || !env.driftForce(0.3, Hull()).allFinite())
          violated("accepted environment parameters give non-finite forcing");
      }
    }
  } catch (const ConfigError& e) {
    violated(std::string("parameters the loader accepted were refused by the model: ") + e.what());
  } catch (const std::exception& e) {
    violated(std::string("an exception other than ConfigError escaped: ") + e.what());
  }
  return 0;
}
