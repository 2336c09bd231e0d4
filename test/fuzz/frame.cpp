// libFuzzer target: arbitrary frames (4 bytes id + flags, 1 byte length, payload) through the NMEA 2000 and
// waterjet decoders (3-axis commands, per-jet set-points, status), the bus-state monitor, the gateway policy
// (both command framings) and the waterjet emulator on the USV model's jets. Outputs must stay finite and in
// range. Built by `scripts/fuzz frame`.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "offshore_gnc/can/emulator.h"
#include "offshore_gnc/can/gateway.h"
#include "offshore_gnc/can/nmea2000.h"
#include "offshore_gnc/can/socket_can.h"

using namespace offshore_gnc;
using namespace offshore_gnc::can;

namespace {
void check(bool ok) {
  if (!ok) __builtin_trap();
}
bool finiteIn(const std::optional<double>& v, double lo, double hi) { return !v || (std::isfinite(*v) && *v >= lo && *v <= hi); }
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Counters counters;
  static const models::UsvParams jets;
  static WaterjetEmulator emu(jets, 0.5, {}, counters);
  static GatewayPolicy policy(GatewayConfig{}, jets, counters);
  static GatewayPolicy joystick_policy(
      [] {
        GatewayConfig c;
        c.command_frames = "joystick";
        return c;
      }(),
      jets, counters);
  static BusMonitor monitor(counters);
  static double t = 0.0;
  if (size < 5) return 0;
  CanFrame f;
  std::uint32_t head;
  std::memcpy(&head, data, 4);
  f.extended = head & 0x80000000U;
  f.error = head & 0x20000000U;
  f.fd = head & 0x40000000U;
  f.id = head & (f.extended ? 0x1FFFFFFFU : 0x7FFU);
  f.len = static_cast<std::uint8_t>(std::min<std::size_t>({data[4], size - 5, f.fd ? 64U : 8U}));
  std::memcpy(f.data.data(), data + 5, f.len);
  t += 0.01;
  if (auto p = n2k::decodePositionRapid(f)) check(finiteIn(p->lat_deg, -90, 90) && finiteIn(p->lon_deg, -180, 180));
  if (auto h = n2k::decodeVesselHeading(f))
    check(finiteIn(h->heading_rad, 0, 2 * M_PI) && finiteIn(h->deviation_rad, -M_PI, M_PI) &&
          finiteIn(h->variation_rad, -M_PI, M_PI));
  if (auto c = n2k::decodeCogSogRapid(f)) check(finiteIn(c->cog_rad, 0, 2 * M_PI) && finiteIn(c->sog_mps, 0, 655.35));
  jet::Command cmd;
  bool manual = false;
  if (jet::decodeCommand(f, cmd, &manual) == jet::Error::kNone) {
    check(std::abs(cmd.surge) <= 1 && std::abs(cmd.sway) <= 1 && std::abs(cmd.yaw) <= 1 && cmd.source <= 4);
    for (GatewayPolicy* p : {&policy, &joystick_policy}) {
      if (manual) p->onManual(cmd, t);
      else check(p->onAutonomy(cmd.surge, cmd.sway, cmd.yaw, t));
    }
  }
  jet::Status st;
  if (jet::decodeStatus(f, st) == jet::Error::kNone) {
    check(st.rpm >= 0 && st.rpm <= jet::kMaxRpm && std::abs(st.nozzle) <= 1 && std::abs(st.bucket) <= 1);
    policy.onStatus(st, t);
  }
  jet::Setpoint sp;
  if (jet::decodeSetpoint(f, sp) == jet::Error::kNone)
    check(sp.jet <= 1 && sp.rpm >= 0 && sp.rpm <= jet::kMaxRpm && std::abs(sp.nozzle) <= 1 && std::abs(sp.bucket) <= 1 &&
          sp.source <= 4);
  if (f.error) monitor.onErrorFrame(f);
  emu.onFrame(f, t);
  for (const auto& out : emu.step(t)) check(jet::decodeStatus(out, st) == jet::Error::kNone && std::isfinite(st.rpm));
  for (const auto& c : emu.applied())
    check(std::isfinite(c.rpm) && std::abs(c.nozzle) <= jets.nozzle_max && std::abs(c.bucket) <= 1);
  for (const auto& out : policy.tick(t)) check(jet::decodeSetpoint(out, sp) == jet::Error::kNone);
  for (const auto& out : joystick_policy.tick(t)) check(jet::decodeCommand(out, cmd) == jet::Error::kNone);
  return 0;
}
