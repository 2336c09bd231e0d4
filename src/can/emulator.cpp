#include "offshore_gnc/can/emulator.h"

#include <algorithm>
#include <cmath>

#include "offshore_gnc/can/nmea2000.h"

namespace offshore_gnc {
namespace can {

WaterjetEmulator::WaterjetEmulator(WaterjetModel model, jet::Addresses addresses, Counters& counters)
    : m_(model), a_(addresses), counters_(counters) {
  for (std::uint8_t i = 0; i < 2; ++i) {
    jets_[i].jet = i;
    jets_[i].rpm = m_.idle_rpm;
  }
}

void WaterjetEmulator::onFrame(const CanFrame& f, double now) {
  jet::Command c;
  bool manual = false;
  const jet::Error e = jet::decodeCommand(f, c, &manual);
  if (e == jet::Error::kNotOurs) return;  // GPS, status frames: not for the units
  if (e != jet::Error::kNone) {
    counters_.increment(jet::toString(e));
    return;
  }
  if (!check_.accept(f.id, c.counter)) counters_.increment("counter_jumps");  // a gap: still act on it
  if (!manual && now - manual_at_ <= m_.command_timeout) return;  // manual controls own the jets
  if (manual) manual_at_ = now;
  applied_ = c;
  command_at_ = now;
}

std::vector<CanFrame> WaterjetEmulator::step(double now) {
  const double dt = last_step_ < 0.0 ? 0.0 : std::clamp(now - last_step_, 0.0, 1.0);
  last_step_ = now;
  const bool stale = now - command_at_ > m_.command_timeout;
  jet::Command c = applied_;
  if (stale) c = jet::Command{};
  std::vector<CanFrame> out;
  for (auto& j : jets_) {
    // Both jets share surge; yaw and sway both steer the nozzles (a twin-jet hull has no separate sway).
    const double nozzle_ref = std::clamp(c.yaw + c.sway, -1.0, 1.0);
    const double rpm_ref = m_.idle_rpm + std::abs(c.surge) * (m_.max_rpm - m_.idle_rpm);
    j.rpm += (rpm_ref - j.rpm) * (1.0 - std::exp(-dt / m_.rpm_time_constant));
    const double max_move = m_.nozzle_rate * dt;
    j.nozzle += std::clamp(nozzle_ref - j.nozzle, -max_move, max_move);
    j.bucket += std::clamp((c.surge >= 0.0 ? 1.0 : -1.0) * (std::abs(c.surge) > 0.02 ? 1.0 : 0.0) - j.bucket,
                           -max_move, max_move);
    j.faults = stale ? 8 /* WaterjetStatus::FAULT_COMMS */ : 0;
    j.counter = counter_;
    out.push_back(jet::encodeStatus(j, a_));
  }
  counter_ = static_cast<std::uint8_t>((counter_ + 1) & 0x0F);
  return out;
}

std::vector<CanFrame> GpsCompassEmulator::frames(const GpsCompassSample& s) {
  n2k::PositionRapid p;
  if (std::isfinite(s.lat_deg) && std::isfinite(s.lon_deg)) {
    p.lat_deg = s.lat_deg;
    p.lon_deg = s.lon_deg;
  }
  n2k::VesselHeading h;
  h.sid = sid_;
  if (std::isfinite(s.heading_rad)) h.heading_rad = s.heading_rad;
  n2k::CogSogRapid c;
  c.sid = sid_;
  if (std::isfinite(s.cog_rad)) c.cog_rad = s.cog_rad;
  if (std::isfinite(s.sog_mps)) c.sog_mps = std::max(0.0, s.sog_mps);
  sid_ = static_cast<std::uint8_t>((sid_ + 1) % 253);  // SID 253..255 are reserved
  return {n2k::encodePositionRapid(p, source_), n2k::encodeVesselHeading(h, source_),
          n2k::encodeCogSogRapid(c, source_)};
}

}  // namespace can
}  // namespace offshore_gnc
