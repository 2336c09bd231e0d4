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
CanFrame frame(std::uint32_t pgn, std::uint8_t priority, std::uint8_t source) {
  CanFrame f;
  f.extended = true;
  f.len = 8;
  n2k::IsoId id;
  id.pgn = pgn;
  id.priority = priority;
  id.source = source;
  f.id = n2k::encodeId(id);
  return f;
}
Error check(const CanFrame& f, std::uint32_t pgn) {
  if (!f.extended || f.error || f.rtr || n2k::decodeId(f.id).pgn != pgn) return Error::kNotOurs;
  if (f.len != 8) return Error::kLength;
  if (crc(pgn, f.data.data()) != f.data[7]) return Error::kChecksum;
  return Error::kNone;
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

std::uint8_t crc(std::uint32_t pgn, const std::uint8_t* payload7) {
  std::uint8_t buf[8] = {static_cast<std::uint8_t>(pgn & 0xFF)};
  std::copy(payload7, payload7 + 7, buf + 1);
  return crc8(buf, sizeof buf);
}

CanFrame encodeCommand(const Command& c, bool manual, const Addresses& a) {
  const std::uint32_t pgn = manual ? kPgnManual : kPgnCommand;
  // Manual controls win arbitration too (priority 2 < 3).
  CanFrame f = frame(pgn, manual ? 2 : 3, manual ? a.bridge : a.gateway);
  putU16(&f.data[0], toRaw(c.surge));
  putU16(&f.data[2], toRaw(c.sway));
  putU16(&f.data[4], toRaw(c.yaw));
  f.data[6] = static_cast<std::uint8_t>((c.counter & 0x0F) | ((c.source & 0x07) << 4));
  f.data[7] = crc(pgn, f.data.data());
  return f;
}

CanFrame encodeStatus(const Status& s, const Addresses& a) {
  CanFrame f = frame(kPgnStatus, 4, static_cast<std::uint8_t>(a.jet_base + (s.jet & 1)));
  const double rpm = std::isfinite(s.rpm) ? std::clamp(s.rpm, 0.0, static_cast<double>(kMaxRpm)) : 0.0;
  putU16(&f.data[0], static_cast<std::uint16_t>(std::lround(rpm)));
  putU16(&f.data[2], toRaw(s.nozzle));
  putU16(&f.data[4], toRaw(s.bucket));
  f.data[6] = static_cast<std::uint8_t>((s.counter & 0x0F) | ((s.faults & 0x0F) << 4));
  f.data[7] = crc(kPgnStatus, f.data.data());
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
  c.counter = f.data[6] & 0x0F;
  c.source = (f.data[6] >> 4) & 0x07;
  if (c.source > 4 || (f.data[6] & 0x80)) return Error::kRange;
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
  const std::uint16_t rpm = getU16(&f.data[0]);
  if (rpm > kMaxRpm || !fromRaw(&f.data[2], s.nozzle) || !fromRaw(&f.data[4], s.bucket)) return Error::kRange;
  s.rpm = rpm;
  s.counter = f.data[6] & 0x0F;
  s.faults = (f.data[6] >> 4) & 0x0F;
  out = s;
  return Error::kNone;
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
