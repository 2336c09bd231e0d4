#include "offshore_gnc/can/nmea2000.h"

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/angles.h"

namespace offshore_gnc {
namespace can {
namespace n2k {
namespace {

constexpr double kAngleRes = 1e-4;   // rad per bit (127250, 129026)
constexpr double kLatLonRes = 1e-7;  // deg per bit (129025)
constexpr double kSpeedRes = 1e-2;   // m/s per bit (129026)
// NMEA 2000 reserves the top values of each field: all ones = not available, one less = out of range.
constexpr std::int32_t kI32Na = 0x7FFFFFFF;
constexpr std::uint16_t kU16Na = 0xFFFF;
constexpr std::int16_t kI16Na = 0x7FFF;

bool isPgn(const CanFrame& f, std::uint32_t pgn) {
  return f.extended && !f.error && !f.rtr && f.len == 8 && decodeId(f.id).pgn == pgn;
}

std::optional<double> u16Field(const std::uint8_t* p, double res) {
  const std::uint16_t raw = getU16(p);
  if (raw >= kU16Na - 2) return std::nullopt;  // 0xFFFD..0xFFFF: reserved / out of range / not available
  return raw * res;
}
std::optional<double> i16Field(const std::uint8_t* p, double res) {
  const std::int16_t raw = getI16(p);
  if (raw >= kI16Na - 2) return std::nullopt;
  return raw * res;
}
std::uint16_t toU16(const std::optional<double>& v, double res) {
  if (!v || !std::isfinite(*v)) return kU16Na;
  return static_cast<std::uint16_t>(std::clamp(std::lround(*v / res), 0L, static_cast<long>(kU16Na - 3)));
}
std::uint16_t toI16(const std::optional<double>& v, double res) {
  if (!v || !std::isfinite(*v)) return static_cast<std::uint16_t>(kI16Na);
  return static_cast<std::uint16_t>(
      static_cast<std::int16_t>(std::clamp(std::lround(*v / res), -32767L, static_cast<long>(kI16Na - 3))));
}
// Angles are sent in [0, 2 pi): 2 pi - half a bit rounds up to 2 pi and must become 0.
std::uint16_t angleRaw(const std::optional<double>& a) {
  if (!a || !std::isfinite(*a)) return kU16Na;
  const long raw = std::lround(wrapTwoPi(*a) / kAngleRes);
  return static_cast<std::uint16_t>(raw >= std::lround(2.0 * kPi / kAngleRes) ? 0 : raw);
}

CanFrame frameFor(std::uint32_t pgn, std::uint8_t source, std::uint8_t priority) {
  CanFrame f;
  f.extended = true;
  f.len = 8;
  f.data.fill(0xFF);
  IsoId id;
  id.pgn = pgn;
  id.source = source;
  id.priority = priority;
  f.id = encodeId(id);
  return f;
}

}  // namespace

IsoId decodeId(std::uint32_t id29) {
  IsoId id;
  id.priority = static_cast<std::uint8_t>((id29 >> 26) & 0x7);
  id.source = static_cast<std::uint8_t>(id29 & 0xFF);
  const std::uint32_t pf = (id29 >> 16) & 0xFF;
  const std::uint32_t dp = (id29 >> 24) & 0x3;  // EDP + DP
  if (pf < 240) {
    id.destination = static_cast<std::uint8_t>((id29 >> 8) & 0xFF);
    id.pgn = (dp << 16) | (pf << 8);
  } else {
    id.pgn = (dp << 16) | (pf << 8) | ((id29 >> 8) & 0xFF);
  }
  return id;
}

std::uint32_t encodeId(const IsoId& id) {
  std::uint32_t pgn = id.pgn & 0x3FFFF;
  const std::uint32_t pf = (pgn >> 8) & 0xFF;
  if (pf < 240) pgn = (pgn & 0x3FF00) | id.destination;
  return (static_cast<std::uint32_t>(id.priority & 0x7) << 26) | (pgn << 8) | id.source;
}

std::optional<PositionRapid> decodePositionRapid(const CanFrame& f) {
  if (!isPgn(f, kPgnPositionRapid)) return std::nullopt;
  PositionRapid v;
  const std::int32_t lat = getI32(&f.data[0]), lon = getI32(&f.data[4]);
  // Out-of-range values (a corrupted or uninitialised sender) count as not available.
  if (lat < kI32Na - 2 && std::abs(static_cast<double>(lat) * kLatLonRes) <= 90.0) v.lat_deg = lat * kLatLonRes;
  if (lon < kI32Na - 2 && std::abs(static_cast<double>(lon) * kLatLonRes) <= 180.0) v.lon_deg = lon * kLatLonRes;
  return v;
}

std::optional<VesselHeading> decodeVesselHeading(const CanFrame& f) {
  if (!isPgn(f, kPgnVesselHeading)) return std::nullopt;
  VesselHeading v;
  v.sid = f.data[0];
  v.heading_rad = u16Field(&f.data[1], kAngleRes);
  if (v.heading_rad && *v.heading_rad >= 2.0 * kPi) v.heading_rad.reset();
  // The field can carry up to 3.2766 rad; beyond pi it is a broken sender, not an angle.
  v.deviation_rad = i16Field(&f.data[3], kAngleRes);
  if (v.deviation_rad && std::abs(*v.deviation_rad) > kPi) v.deviation_rad.reset();
  v.variation_rad = i16Field(&f.data[5], kAngleRes);
  if (v.variation_rad && std::abs(*v.variation_rad) > kPi) v.variation_rad.reset();
  v.reference = f.data[7] & 0x3;
  return v;
}

std::optional<CogSogRapid> decodeCogSogRapid(const CanFrame& f) {
  if (!isPgn(f, kPgnCogSogRapid)) return std::nullopt;
  CogSogRapid v;
  v.sid = f.data[0];
  v.reference = f.data[1] & 0x3;
  v.cog_rad = u16Field(&f.data[2], kAngleRes);
  if (v.cog_rad && *v.cog_rad >= 2.0 * kPi) v.cog_rad.reset();
  v.sog_mps = u16Field(&f.data[4], kSpeedRes);
  return v;
}

CanFrame encodePositionRapid(const PositionRapid& v, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = frameFor(kPgnPositionRapid, source, priority);
  auto deg = [](const std::optional<double>& d, double lim) -> std::uint32_t {
    if (!d || !std::isfinite(*d)) return static_cast<std::uint32_t>(kI32Na);
    return static_cast<std::uint32_t>(static_cast<std::int32_t>(std::llround(std::clamp(*d, -lim, lim) / kLatLonRes)));
  };
  putU32(&f.data[0], deg(v.lat_deg, 90.0));
  putU32(&f.data[4], deg(v.lon_deg, 180.0));
  return f;
}

CanFrame encodeVesselHeading(const VesselHeading& v, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = frameFor(kPgnVesselHeading, source, priority);
  f.data[0] = v.sid;
  putU16(&f.data[1], angleRaw(v.heading_rad));
  putU16(&f.data[3], toI16(v.deviation_rad, kAngleRes));
  putU16(&f.data[5], toI16(v.variation_rad, kAngleRes));
  f.data[7] = static_cast<std::uint8_t>(0xFC | (v.reference & 0x3));
  return f;
}

CanFrame encodeCogSogRapid(const CogSogRapid& v, std::uint8_t source, std::uint8_t priority) {
  CanFrame f = frameFor(kPgnCogSogRapid, source, priority);
  f.data[0] = v.sid;
  f.data[1] = static_cast<std::uint8_t>(0xFC | (v.reference & 0x3));
  putU16(&f.data[2], angleRaw(v.cog_rad));
  putU16(&f.data[4], toU16(v.sog_mps, kSpeedRes));
  return f;
}

}  // namespace n2k
}  // namespace can
}  // namespace offshore_gnc
