#pragma once
// The models' joystick allocation (models/joystick_allocation.h, the CCPilot's role) in the units of the per-jet
// set-point frame (docs/can-protocol.md): the gateway allocates the autonomy command with it, the emulated units
// the joystick-level frames they act on (the bridge's manual joystick). Also one jet's set-point between the
// wire (nozzle normalised, + = starboard) and the model (P_nozzle, < 0 turns to starboard: eq. 3.25's sign).
#include <array>
#include <cstdint>

#include "offshore_gnc/can/waterjet_protocol.h"
#include "offshore_gnc/models/joystick_allocation.h"

namespace offshore_gnc {
namespace can {

class JetAllocation {
 public:
  explicit JetAllocation(const models::UsvParams& jets);  // validates (ConfigError)
  // Both jets' set-points for joystick axes in [-1, 1] (callers refuse anything else). A request beyond the
  // jets' limits is scaled down on all three axes together, so its direction is kept (lastScale() < 1).
  std::array<jet::Setpoint, 2> allocate(double surge, double sway, double yaw, std::uint8_t source) const;
  double lastScale() const { return allocation_.lastScale(); }
  // Neutral for both jets: engines idle (rpm 0 on the wire: the unit idles), nozzles centred, buckets neutral.
  static std::array<jet::Setpoint, 2> neutral(std::uint8_t source);
  // Wire -> model, clamped to the jet's ranges (an rpm below idle idles); model -> wire.
  models::JetCommand toModel(const jet::Setpoint& s) const;
  jet::Setpoint toWire(const models::JetCommand& c, std::uint8_t jet, std::uint8_t source) const;
  const models::UsvParams& params() const { return p_; }

 private:
  models::UsvParams p_;
  models::JoystickAllocation allocation_;
};

}  // namespace can
}  // namespace offshore_gnc
