#include "offshore_gnc/sim/simulator_params.h"

namespace offshore_gnc {
namespace sim {

const ParamTable<RunParams>& RunParams::table() {
  using P = RunParams;
  static const ParamTable<P> t = ParamTable<P>()
      .string("scenario", &P::scenario, "the scenario file (required; its origin must be the site's)")
      .number("rate", &P::rate, 0.0, 10000.0, "", "simulated time per real time (0: as fast as the CPU allows)")
      .flag("lockstep", &P::lockstep, "step only when asked on `sim/step` (tests that must see every step)")
      .number("dt", &P::dt, 1e-4, 0.1, "s", "simulation step")
      .integer("seed", &P::seed, 0, 1 << 30, "the sensors' random seed");
  return t;
}

const ParamTable<UsvSimNodeParams>& UsvSimNodeParams::table() {
  using P = UsvSimNodeParams;
  static const ParamTable<P> t = ParamTable<P>()
      .string("model_params", &P::model_params, "the USV's model file (config/models/; empty: the built-in one)")
      .choice("model", &P::model, {"dynamic", "nomoto"}, "3-DOF dynamics or the identified Nomoto/surge TFs")
      .number("manual_timeout", &P::manual_timeout, 0.05, 60.0, "s", "a joystick command older than this: released")
      .string("command_topic", &P::command_topic, "the joystick commands the USV follows")
      .string("jet_command_topic", &P::jet_command_topic,
              "per-jet set-points behind the CAN gateway and emulator (empty: none)")
      .string("base_frame", &P::base_frame, "the USV's body frame");
  return t;
}

const ParamTable<AuvSimNodeParams>& AuvSimNodeParams::table() {
  using P = AuvSimNodeParams;
  static const ParamTable<P> t = ParamTable<P>()
      .flag("odom/enabled", &P::odom_enabled,
            "publish the INS-like /auv/odom + TF (false: the navigation nodelet does)")
      .choice("vehicle_model", &P::vehicle_model, {"girona500", "acolor"}, "the built-in AUV model")
      .string("model_params", &P::model_params, "an AUV model file (config/models/) over it; empty: none")
      .string("base_frame", &P::base_frame, "the AUV's body frame");
  return t;
}

}  // namespace sim
}  // namespace offshore_gnc
