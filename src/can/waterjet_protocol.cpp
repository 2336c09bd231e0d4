#include "offshore_gnc/can/waterjet_protocol.h"

#include <algorithm>
#include <boost/crc.hpp>
#include <cmath>

#include "offshore_gnc/can/nmea2000.h"

namespace offshore_gnc {
namespace can {
namespace jet {
namespace {

constexpr std::int16_t kRawLimit = static_cast<std::int16_t>(kFullScale);

std::uint16_t toRaw(double v) {
  if (!std::isfinite(v)) v = 0.0;  // callers validate; never put garbage on the bus
  return static_cast<std::uint16_t>(static_cast<std::int16_t>(std::lround(std::clamp(v, -1.0, 1.0) * kFullScale)));
}
bool fromRaw(const std::uint8_t* p, double& v) {
  const std::int16_t raw = getI16(p);
  if (raw < -kRawLimit || raw > kRawLimit) return false;
  v = raw / kFullScale;
  return true;
}
std::uint8_t psOf(std::uint32_t id) { return static_cast<std::uint8_t>(id >> 8); }
CanFrame frame(std::uint32_t pgn, std::uint8_t priority, std::uint8_t source,
               std::uint8_t destination = n2k::kBroadcast) {
  CanFrame f;
  f.extended = true;
  f.len = 8;
  n2k::IsoId id;
  id.pgn = pgn;
  id.priority = priority;
  id.source = source;
  id.destination = destination;
  f.id = n2k::encodeId(id);
  return f;
}
bool isPgn(const CanFrame& f, std::uint32_t pgn) {
  return f.extended && !f.error && !f.rtr && n2k::decodeId(f.id).pgn == pgn;
}
// Length and CRC of a frame of ours (the PGN already matched).
Error check(const CanFrame& f) {
  if (f.len != 8) return Error::kLength;
  if (crc(psOf(f.id), f.data.data()) != f.data[7]) return Error::kChecksum;
  return Error::kNone;
}
Error check(const CanFrame& f, std::uint32_t pgn) { return isPgn(f, pgn) ? check(f) : Error::kNotOurs; }
// Bytes 6 and 7 of every frame of ours: the rolling counter, 3 or 4 more bits, then the CRC.
void seal(CanFrame& f, std::uint8_t counter, std::uint8_t high_bits) {
  f.data[6] = static_cast<std::uint8_t>((counter & 0x0F) | (high_bits << 4));
  f.data[7] = crc(psOf(f.id), f.data.data());
}
// Bytes 0..5 shared by the status and the per-jet set-point: rpm, nozzle, bucket; false when out of range.
bool getJet(const std::uint8_t* p, double& rpm, double& nozzle, double& bucket) {
  const std::uint16_t raw = getU16(p);
  if (raw > kMaxRpm || !fromRaw(p + 2, nozzle) || !fromRaw(p + 4, bucket)) return false;
  rpm = raw;
  return true;
}
// Byte 6 of a command: counter and source (JoystickCommand::SOURCE_*, 0..4); false when the source is not one.
bool getCounterSource(std::uint8_t b6, std::uint8_t& counter, std::uint8_t& source) {
  counter = b6 & 0x0F;
  source = (b6 >> 4) & 0x07;
  return source <= 4 && !(b6 & 0x80);
}
void putJet(std::uint8_t* p, double rpm, double nozzle, double bucket) {
  rpm = std::isfinite(rpm) ? std::clamp(rpm, 0.0, static_cast<double>(kMaxRpm)) : 0.0;
  putU16(p, static_cast<std::uint16_t>(std::lround(rpm)));
  putU16(p + 2, toRaw(nozzle));
  putU16(p + 4, toRaw(bucket));
}

}  // namespace

const char* toString(Error e) {
  switch (e) {
    case Error::kNone: return "ok";
    case Error::kNotOurs: return "unknown_id";
    case Error::kLength: return "wrong_dlc";
    case Error::kChecksum: return "bad_checksum";
    case Error::kRange: return "out_of_range";
  }
  return "?";
}

std::uint8_t crc8(const std::uint8_t* data, std::size_t n) {
  boost::crc_optimal<8, 0x1D, 0xFF, 0xFF, false, false> c;  // SAE J1850
  c.process_bytes(data, n);
  return c.checksum();
}

std::uint8_t crc(std::uint32_t ps, const std::uint8_t* payload7) {
  std::uint8_t buf[8] = {static_cast<std::uint8_t>(ps & 0xFF)};
  std::copy(payload7, payload7 + 7, buf + 1);
  return crc8(buf, sizeof buf);
}

CanFrame encodeCommand(const Command& c, bool manual, const Addresses& a) {
  const std::uint32_t pgn = manual ? kPgnManual : kPgnCommand;
  // Manual controls win arbitration too (priority 2 < 3).
  CanFrame f = frame(pgn, manual ? 2 : 3, static_cast<std::uint8_t>(manual ? a.bridge : a.gateway));
  putU16(&f.data[0], toRaw(c.surge));
  putU16(&f.data[2], toRaw(c.sway));
  putU16(&f.data[4], toRaw(c.yaw));
  seal(f, c.counter, c.source & 0x07);
  return f;
}

CanFrame encodeStatus(const Status& s, const Addresses& a) {
  CanFrame f = frame(kPgnStatus, 4, static_cast<std::uint8_t>(a.jet_base + (s.jet & 1)));
  putJet(&f.data[0], s.rpm, s.nozzle, s.bucket);
  seal(f, s.counter, s.faults & 0x0F);
  return f;
}

CanFrame encodeSetpoint(const Setpoint& s, const Addresses& a) {
  // Priority 3, as the autonomy command it replaces: the bridge's manual frames (2) still win arbitration.
  CanFrame f = frame(kPgnSetpoint, 3, static_cast<std::uint8_t>(a.gateway),
                     static_cast<std::uint8_t>(a.jet_base + (s.jet & 1)));
  putJet(&f.data[0], s.rpm, s.nozzle, s.bucket);
  seal(f, s.counter, s.source & 0x07);
  return f;
}

Error decodeCommand(const CanFrame& f, Command& out, bool* manual) {
  Error e = check(f, kPgnCommand);
  bool is_manual = false;
  if (e == Error::kNotOurs) {
    e = check(f, kPgnManual);
    is_manual = true;
  }
  if (e != Error::kNone) return e;
  Command c;
  if (!fromRaw(&f.data[0], c.surge) || !fromRaw(&f.data[2], c.sway) || !fromRaw(&f.data[4], c.yaw))
    return Error::kRange;
  if (!getCounterSource(f.data[6], c.counter, c.source)) return Error::kRange;
  out = c;
  if (manual) *manual = is_manual;
  return Error::kNone;
}

Error decodeStatus(const CanFrame& f, Status& out, const Addresses& a) {
  const Error e = check(f, kPgnStatus);
  if (e != Error::kNone) return e;
  const std::uint8_t sa = n2k::decodeId(f.id).source;
  if (sa != a.jet_base && sa != a.jet_base + 1) return Error::kNotOurs;
  Status s;
  s.jet = static_cast<std::uint8_t>(sa - a.jet_base);
  if (!getJet(&f.data[0], s.rpm, s.nozzle, s.bucket)) return Error::kRange;
  s.counter = f.data[6] & 0x0F;
  s.faults = (f.data[6] >> 4) & 0x0F;
  out = s;
  return Error::kNone;
}

Error decodeSetpoint(const CanFrame& f, Setpoint& out, const Addresses& a) {
  if (!isPgn(f, kPgnSetpoint)) return Error::kNotOurs;
  const int da = n2k::decodeId(f.id).destination;
  if (da != a.jet_base && da != a.jet_base + 1) return Error::kNotOurs;  // Proprietary A for another device
  const Error e = check(f);
  if (e != Error::kNone) return e;
  Setpoint s;
  s.jet = static_cast<std::uint8_t>(da - a.jet_base);
  if (!getJet(&f.data[0], s.rpm, s.nozzle, s.bucket)) return Error::kRange;
  if (!getCounterSource(f.data[6], s.counter, s.source)) return Error::kRange;
  out = s;
  return Error::kNone;
}

Decoded decode(const CanFrame& f, const Addresses& a) {
  Decoded d;
  bool manual = false;
  using K = Decoded::Kind;
  if ((d.error = decodeCommand(f, d.command, &manual)) == Error::kNone) d.kind = manual ? K::kManual : K::kCommand;
  else if (d.error == Error::kNotOurs && (d.error = decodeStatus(f, d.status, a)) == Error::kNone) d.kind = K::kStatus;
  else if (d.error == Error::kNotOurs && (d.error = decodeSetpoint(f, d.setpoint, a)) == Error::kNone) d.kind = K::kSetpoint;
  return d;
}

const ParamTable<Addresses>& Addresses::table() {
  static const ParamTable<Addresses> t = ParamTable<Addresses>()
      .integer("gateway", &Addresses::gateway, 0, 253, "source address of the gateway's commands")
      .integer("bridge", &Addresses::bridge, 0, 253, "source address of the bridge's manual joystick and steering wheel")
      .integer("jet_base", &Addresses::jet_base, 0, 252, "port jet's address; the starboard jet's is one more");
  return t;
}

bool CounterCheck::accept(std::uint32_t key, std::uint8_t counter) {
  counter &= 0x0F;
  auto it = last_.find(key);
  const bool ok = it == last_.end() || counter == ((it->second + 1) & 0x0F);
  last_[key] = counter;
  return ok;
}

}  // namespace jet
}  // namespace can
}  // namespace offshore_gnc
