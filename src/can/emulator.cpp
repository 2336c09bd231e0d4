#include "offshore_gnc/can/emulator.h"

#include <algorithm>
#include <cmath>

#include "offshore_gnc/can/nmea2000.h"

namespace offshore_gnc {
namespace can {

WaterjetEmulator::WaterjetEmulator(const models::UsvParams& jets, double command_timeout, jet::Addresses addresses,
                                   Counters& counters)
    : command_timeout_(command_timeout),
      a_(addresses),
      counters_(counters),
      allocation_(jets),
      model_(jets),
      commanded_(JetAllocation::neutral(kWatchdog)),
      applied_(model_.commands()) {
  for (std::uint8_t i = 0; i < 2; ++i) status_[i].jet = i;
}

void WaterjetEmulator::command(int jet, const jet::Setpoint& s, double now) {
  commanded_[jet] = s;
  command_at_[jet] = now;
}

void WaterjetEmulator::onFrame(const CanFrame& f, double now) {
  const jet::Decoded d = jet::decode(f, a_);
  using K = jet::Decoded::Kind;
  if (d.kind == K::kNone) {
    if (d.error != jet::Error::kNotOurs) counters_.increment(jet::toString(d.error));
    return;  // GPS frames: not for the units
  }
  if (d.kind == K::kStatus) return;  // the other unit's
  const bool per_jet = d.kind == K::kSetpoint, manual = d.kind == K::kManual;
  if (!check_.accept(f.id, per_jet ? d.setpoint.counter : d.command.counter))
    counters_.increment("counter_jumps");  // a gap: still act on it
  if (!manual && now - manual_at_ <= command_timeout_) return;  // manual controls own the jets
  if (manual) manual_at_ = now;
  if (per_jet) {
    command(d.setpoint.jet, d.setpoint, now);
    return;
  }
  const auto both = allocation_.allocate(d.command.surge, d.command.sway, d.command.yaw, d.command.source);
  for (int i = 0; i < 2; ++i) command(i, both[i], now);
}

std::vector<CanFrame> WaterjetEmulator::step(double now) {
  const double dt = last_step_ < 0.0 ? 0.0 : std::clamp(now - last_step_, 0.0, 1.0);
  std::array<bool, 2> stale;
  for (int i = 0; i < 2; ++i) {
    stale[i] = now - command_at_[i] > command_timeout_;
    const jet::Setpoint s = stale[i] ? JetAllocation::neutral(kWatchdog)[i] : commanded_[i];
    applied_[i] = allocation_.toModel(s);
    source_[i] = s.source;
  }
  model_.setCommands(applied_);
  if (dt > 0.0) model_.step(last_step_, dt);
  last_step_ = now;
  std::vector<CanFrame> out;
  for (int i = 0; i < 2; ++i) {
    const models::JetState& m = model_.state()[i];
    const jet::Setpoint w = allocation_.toWire({m.rpm, m.nozzle, m.bucket}, static_cast<std::uint8_t>(i), 0);
    jet::Status& s = status_[i];
    s.rpm = w.rpm;
    s.nozzle = w.nozzle;
    s.bucket = w.bucket;
    s.faults = stale[i] ? 8 /* WaterjetStatus::FAULT_COMMS */ : 0;
    s.counter = counter_;
    if (!silent_[i]) out.push_back(jet::encodeStatus(s, a_));
  }
  counter_ = static_cast<std::uint8_t>((counter_ + 1) & 0x0F);
  return out;
}

const ParamTable<EmulatorConfig>& EmulatorConfig::table() {
  using C = EmulatorConfig;
  static const ParamTable<C> t =
      ParamTable<C>()
          .number("rate", &C::rate, 1.0, 100.0, "Hz", "status and GPS-compass frames per second")
          .number("waterjet/command_timeout", &C::command_timeout, 0.05, 10.0, "s",
                  "a unit without commands for this long goes neutral and raises FAULT_COMMS")
          .integer("address/gps", &C::gps_address, 0, 253, "source address of the GPS-compass")
          .nest("address/", &C::addresses, jet::Addresses::table())
          .string("interface", &C::interface, "the SocketCAN interface the emulated units are on")
          .string("model_params", &C::model_params, "the jets' model (config/models/; empty: the built-in one)");
  return t;
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
