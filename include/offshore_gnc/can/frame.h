#pragma once
// A CAN frame independent of the kernel headers, so that codecs, the candump parser and the fuzz targets
// build and run anywhere; socket_can.cpp converts to struct can_frame / canfd_frame at the edge.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace offshore_gnc {
namespace can {

struct CanFrame {
  std::uint32_t id = 0;   // 11-bit or 29-bit identifier; for error frames the CAN_ERR_* class bits
  bool extended = true;   // 29-bit id
  bool fd = false;        // CAN FD frame (up to 64 bytes)
  bool rtr = false;       // remote request
  bool error = false;     // error frame from the controller (data holds the CAN_ERR_* detail bytes)
  std::uint8_t len = 0;   // payload length in bytes
  std::array<std::uint8_t, 64> data{};
};

// One candump log line, `(1700000000.123456) can0 09F80102#0011223344556677` (candump -L); also accepts
// `can0 09F80102#...` without timestamp, FD frames `id##<flags><data>` and `id#R`.
struct CandumpLine {
  double stamp = 0.0;  // seconds; 0 when the line has none
  std::string iface;
  CanFrame frame;
};
// Returns nullopt and sets `error` (when given) on a malformed line.
std::optional<CandumpLine> parseCandump(const std::string& line, std::string* error = nullptr);
// The `id#data` part (cansend syntax).
std::string formatCansend(const CanFrame& f);

// Little-endian field access for NMEA 2000 and our waterjet payloads (bounds are the caller's job).
inline std::uint16_t getU16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
inline std::int16_t getI16(const std::uint8_t* p) { return static_cast<std::int16_t>(getU16(p)); }
inline std::uint32_t getU32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
inline std::int32_t getI32(const std::uint8_t* p) { return static_cast<std::int32_t>(getU32(p)); }
inline void putU16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
inline void putU32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

}  // namespace can
}  // namespace offshore_gnc
