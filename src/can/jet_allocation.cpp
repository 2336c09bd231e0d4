#include "offshore_gnc/can/jet_allocation.h"

#include <algorithm>
#include <cmath>

namespace offshore_gnc {
namespace can {

namespace {
// Validated before JoystickAllocation builds its thrust table from them (a bad range would not stop it).
const models::UsvParams& validated(const models::UsvParams& p) {
  p.validate();
  return p;
}
}  // namespace

JetAllocation::JetAllocation(const models::UsvParams& jets) : p_(validated(jets)), allocation_(p_) {}

std::array<jet::Setpoint, 2> JetAllocation::allocate(double surge, double sway, double yaw,
                                                     std::uint8_t source) const {
  const models::JetCommands c = allocation_.allocate({surge, sway, yaw});
  return {toWire(c[0], 0, source), toWire(c[1], 1, source)};
}

std::array<jet::Setpoint, 2> JetAllocation::neutral(std::uint8_t source) {
  std::array<jet::Setpoint, 2> n;
  for (std::uint8_t i = 0; i < 2; ++i) {
    n[i].jet = i;
    n[i].source = source;
  }
  return n;
}

models::JetCommand JetAllocation::toModel(const jet::Setpoint& s) const {
  return {std::clamp(s.rpm, p_.rpm_min, p_.rpm_max), std::clamp(-s.nozzle, -1.0, 1.0) * p_.nozzle_max,
          std::clamp(s.bucket, -1.0, 1.0)};
}

jet::Setpoint JetAllocation::toWire(const models::JetCommand& c, std::uint8_t jet, std::uint8_t source) const {
  jet::Setpoint s;
  s.jet = jet;
  s.rpm = c.rpm;
  s.nozzle = -c.nozzle / p_.nozzle_max;
  s.bucket = c.bucket;
  s.source = source;
  return s;
}

}  // namespace can
}  // namespace offshore_gnc
