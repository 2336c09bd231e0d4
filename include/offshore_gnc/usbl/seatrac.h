#pragma once
// SeaTrac (Blueprint Subsea X100 series) serial protocol: framing, CRC and the messages this stack uses.
// ROS-free. Frames are ASCII lines: '#' (command) or '$' (reply), CID and payload as uppercase hex pairs
// (multi-byte fields little-endian), CRC-16/ARC of the binary CID + payload as 4 hex chars (little-endian),
// CR LF. docs/usbl.md says which structures were checked against which public source.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "offshore_gnc/common/counters.h"

namespace offshore_gnc {
namespace usbl {

enum Cid : std::uint8_t {
  CID_SYS_INFO = 0x02,
  CID_STATUS = 0x10,
  CID_SETTINGS_GET = 0x15,
  CID_XCVR_USBL = 0x38,
  CID_XCVR_FIX = 0x39,
  CID_PING_SEND = 0x40,
  CID_PING_REQ = 0x41,
  CID_PING_RESP = 0x42,
  CID_PING_ERROR = 0x43,
  CID_DAT_SEND = 0x60,
  CID_DAT_RECEIVE = 0x61,
  CID_DAT_ERROR = 0x63,
};
// Name of a CID ("PING_RESP"), or "" for one this codec does not know.
const char* cidName(std::uint8_t cid);

enum MsgType : std::uint8_t {
  MSG_OWAY = 0, MSG_OWAYU = 1, MSG_REQ = 2, MSG_RESP = 3, MSG_REQU = 4, MSG_RESPU = 5, MSG_REQX = 6, MSG_RESPX = 7
};
constexpr std::uint8_t kStatusOk = 0x00;
constexpr std::uint8_t kStatusXcvrRespTimeout = 0x34;
constexpr std::uint8_t kMaxUsblChannels = 4;
constexpr std::size_t kMaxDataPacket = 31;  // DAT_SEND payload limit of the X100 series

// CRC-16/ARC (poly 0xA001 reflected, init 0). check("123456789") == 0xBB3D.
std::uint16_t crc16(const std::uint8_t* data, std::size_t n);

// The acoustic fix structure (ACOFIX_T) carried by PING_RESP, XCVR_FIX, DAT_RECEIVE. Raw units in the
// comments; use the accessors for SI.
struct AcoFix {
  enum Flags : std::uint8_t { RANGE = 1, USBL = 2, POSITION = 4, ENHANCED = 8, FILTER_ERROR = 16 };
  std::uint8_t dest_id = 0, src_id = 0, flags = 0, msg_type = 0;
  std::int16_t yaw = 0, pitch = 0, roll = 0;  // local attitude, 0.1 deg
  std::uint16_t depth_local = 0;              // 0.1 m
  std::uint16_t vos = 0;                      // speed of sound, 0.1 m/s
  std::int16_t rssi = 0;                      // 0.1 dB
  // RANGE
  std::uint32_t range_count = 0;
  std::int32_t range_time = 0;  // one-way travel time, 100 ns
  std::uint16_t range_dist = 0; // 0.1 m
  // USBL
  std::vector<std::int16_t> usbl_rssi;  // per channel, 0.1 dB (at most kMaxUsblChannels)
  std::int16_t azimuth = 0, elevation = 0;  // 0.1 deg
  std::int16_t fit_error = 0;               // 0.01
  // POSITION
  std::int16_t east = 0, north = 0, depth = 0;  // 0.1 m

  bool has(Flags f) const { return (flags & f) != 0; }
  double rangeM() const { return range_dist * 0.1; }
  double rangeTimeS() const { return range_time * 1e-7; }
  double azimuthRad() const;
  double elevationRad() const;
  double fitError() const { return fit_error * 0.01; }
  bool operator==(const AcoFix& o) const;
};

// Status-only replies (PING_SEND/DAT_SEND acknowledgement, PING_ERROR, DAT_ERROR).
struct StatusReply {
  std::uint8_t cid = 0, status = 0, beacon_id = 0;
  bool operator==(const StatusReply& o) const { return cid == o.cid && status == o.status && beacon_id == o.beacon_id; }
};
// PING_SEND command.
struct PingSend {
  std::uint8_t dest_id = 0, msg_type = MSG_REQU;
  bool operator==(const PingSend& o) const { return dest_id == o.dest_id && msg_type == o.msg_type; }
};
// PING_RESP / XCVR_FIX: one fix.
struct FixMessage {
  std::uint8_t cid = CID_PING_RESP;
  AcoFix fix;
  bool operator==(const FixMessage& o) const { return cid == o.cid && fix == o.fix; }
};
// DAT_SEND command: up to kMaxDataPacket bytes to a remote beacon.
struct DatSend {
  std::uint8_t dest_id = 0, msg_type = MSG_OWAY;
  std::vector<std::uint8_t> data;
  bool operator==(const DatSend& o) const { return dest_id == o.dest_id && msg_type == o.msg_type && data == o.data; }
};
// DAT_RECEIVE: data from a remote beacon with the fix of its signal.
struct DatReceive {
  AcoFix fix;
  bool ack = false;
  std::vector<std::uint8_t> data;
  bool operator==(const DatReceive& o) const { return fix == o.fix && ack == o.ack && data == o.data; }
};
// A known CID whose payload this codec leaves undecoded (SYS_INFO, STATUS, SETTINGS_GET, XCVR_USBL, PING_REQ).
struct Opaque {
  std::uint8_t cid = 0;
  std::vector<std::uint8_t> payload;
  bool operator==(const Opaque& o) const { return cid == o.cid && payload == o.payload; }
};

using Body = std::variant<PingSend, StatusReply, FixMessage, DatSend, DatReceive, Opaque>;
struct Message {
  bool command = false;  // '#' (to the beacon) or '$' (from it)
  Body body;
};

// Binary payload (CID first) <-> message. decodePayload returns nullopt and sets `reason` on error.
std::optional<Message> decodePayload(bool command, const std::uint8_t* data, std::size_t n, std::string* reason);
std::vector<std::uint8_t> encodePayload(const Message& m);
// Full frame: sync char, hex, CRC, CR LF.
std::string encodeFrame(const Message& m);
std::string encodeFrameRaw(bool command, const std::vector<std::uint8_t>& payload);

// Fix payload helpers (shared by every message embedding an ACOFIX).
void appendFix(std::vector<std::uint8_t>& out, const AcoFix& f);
// Parses an ACOFIX at data[pos]; advances pos. False (with reason) when truncated or invalid.
bool parseFix(const std::uint8_t* data, std::size_t n, std::size_t& pos, AcoFix& f, std::string* reason);

// Incremental decoder: feed arbitrary chunks; complete messages and rejections come out in order.
// Resynchronises on the next '#'/'$' after garbage; lines longer than max_line are dropped.
class StreamDecoder {
 public:
  struct Event {
    std::optional<Message> message;  // set when a frame decoded
    std::string reason;              // set when a frame was rejected (counter name)
    std::string line;                // the frame text (without CR LF), for logs
  };
  explicit StreamDecoder(std::size_t max_line = 600) : max_line_(max_line) {}
  // Appends events to `out`.
  void feed(const std::uint8_t* data, std::size_t n, std::vector<Event>& out);
  void feed(const std::string& s, std::vector<Event>& out) {
    feed(reinterpret_cast<const std::uint8_t*>(s.data()), s.size(), out);
  }
  // Counters: frames_ok and one per rejection reason (bad_crc, odd_hex_length, non_hex, unknown_cid,
  // bad_length, too_many_channels, line_too_long, garbage_bytes).
  const Counters& counters() const { return counters_; }
  Counters& counters() { return counters_; }

 private:
  void finishLine(std::vector<Event>& out);
  std::size_t max_line_;
  std::string line_;
  bool in_frame_ = false;
  bool overflow_ = false;
  Counters counters_;
};

}  // namespace usbl
}  // namespace offshore_gnc
