#pragma once
// NMEA 2000 single-frame PGNs of the GPS-compass (thesis 4.3.1) and the ISO 11783 29-bit id layout:
//   bits 26..28 priority, 25 reserved (EDP), 24 data page, 16..23 PDU format (PF), 8..15 PDU specific (PS),
//   0..7 source address. PF < 240 (PDU1): PS is the destination and not part of the PGN; else (PDU2) PS is.
// Field layout and resolution per the NMEA 2000 definitions (documented in docs/can-protocol.md).
// Decoders return nullopt for a frame they cannot use (wrong PGN or length); "not available" fields
// (all ones) become std::nullopt members, never NaN.
#include <cstdint>
#include <optional>

#include "offshore_gnc/can/frame.h"

namespace offshore_gnc {
namespace can {
namespace n2k {

constexpr std::uint32_t kPgnPositionRapid = 129025;
constexpr std::uint32_t kPgnVesselHeading = 127250;
constexpr std::uint32_t kPgnCogSogRapid = 129026;
constexpr std::uint8_t kBroadcast = 255;

struct IsoId {
  std::uint8_t priority = 6;   // 0 (highest) .. 7
  std::uint32_t pgn = 0;       // 18 bits
  std::uint8_t source = 0;
  std::uint8_t destination = kBroadcast;  // only for PDU1 PGNs
};
IsoId decodeId(std::uint32_t id29);
std::uint32_t encodeId(const IsoId& id);

struct PositionRapid {  // PGN 129025
  std::optional<double> lat_deg, lon_deg;
};
struct VesselHeading {  // PGN 127250
  std::uint8_t sid = 255;
  std::optional<double> heading_rad;    // [0, 2 pi), clockwise from north
  std::optional<double> deviation_rad;
  std::optional<double> variation_rad;
  std::uint8_t reference = 0;           // 0 true, 1 magnetic, 2 error, 3 null
};
struct CogSogRapid {  // PGN 129026
  std::uint8_t sid = 255;
  std::uint8_t reference = 0;           // 0 true, 1 magnetic
  std::optional<double> cog_rad;        // [0, 2 pi)
  std::optional<double> sog_mps;
};

std::optional<PositionRapid> decodePositionRapid(const CanFrame& f);
std::optional<VesselHeading> decodeVesselHeading(const CanFrame& f);
std::optional<CogSogRapid> decodeCogSogRapid(const CanFrame& f);

// Encoders clamp to the field range; an empty optional is sent as "not available".
CanFrame encodePositionRapid(const PositionRapid& v, std::uint8_t source, std::uint8_t priority = 2);
CanFrame encodeVesselHeading(const VesselHeading& v, std::uint8_t source, std::uint8_t priority = 2);
CanFrame encodeCogSogRapid(const CogSogRapid& v, std::uint8_t source, std::uint8_t priority = 2);

}  // namespace n2k
}  // namespace can
}  // namespace offshore_gnc
