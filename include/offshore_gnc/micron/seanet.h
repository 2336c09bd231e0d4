#pragma once
// Tritech SeaNet serial protocol as the Micron (DST) imaging sonar speaks it. ROS-free.
//
// Every packet:  '@' | 4 ASCII hex digits L | uint16 LE L | tx node | rx node | byte count | type | sequence |
//                node | body ... | LF (0x0A)
// L counts the bytes from the binary length word to the last body byte (the packet is L + 6 bytes long); the
// byte count is the number of bytes from `type` to the last body byte (0 in mtHeadData, which does not use it).
// The PC is node 0xFF, the sonar node 2. Multi-byte fields are little-endian. Angles are in 1/16 gradian
// (6400 per turn, 0.05625 deg).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace micron {

enum MsgType : std::uint8_t {
  mtVersionData = 1, mtHeadData = 2, mtAlive = 4, mtBBUserData = 6, mtReBoot = 16, mtHeadCommand = 19,
  mtSendVersion = 23, mtSendBBUser = 24, mtSendData = 25, mtFpgaVersionData = 57
};
const char* typeName(std::uint8_t type);

constexpr std::uint8_t kPcNode = 0xFF, kSonarNode = 0x02;
constexpr std::size_t kHeaderBytes = 13;     // '@' .. node
constexpr std::size_t kMaxPacket = 2048;     // 1500 bins of head data fit; anything longer is garbage
constexpr int kAngleUnitsPerTurn = 6400;     // 1/16 gradian

// HdCtrl bits (mtHeadCommand, echoed in mtHeadData).
enum HdCtrl : std::uint16_t {
  kAdc8On = 1u << 0, kCont = 1u << 1, kScanRight = 1u << 2, kInvert = 1u << 3, kMotOff = 1u << 4,
  kTxOff = 1u << 5, kChan2 = 1u << 7, kRaw = 1u << 8, kHasMot = 1u << 9, kApplyOffset = 1u << 10,
  kPingPong = 1u << 11, kStareLLim = 1u << 12, kReplyAsl = 1u << 13, kReplyThr = 1u << 14, kIgnoreSensor = 1u << 15
};
// HeadInf bits (mtAlive).
enum HeadInf : std::uint8_t {
  kInCentre = 1u << 0, kCentred = 1u << 1, kMotoring = 1u << 2, kMotorOn = 1u << 3, kDir = 1u << 4,
  kInScan = 1u << 5, kNoParams = 1u << 6, kSentCfg = 1u << 7
};
// Head status bits (mtHeadData).
enum HeadStatus : std::uint8_t { kHdPwrLoss = 1u << 0, kMotErr = 1u << 1, kDataRange8 = 1u << 4, kMsgAppended = 1u << 7 };
// Sweep code (mtHeadData).
enum SweepCode : std::uint8_t { kScanning = 0, kAtLeftLimit = 1, kAtRightLimit = 2, kAtCentre = 5 };

struct Alive {
  std::uint8_t spare = 0;          // body byte 13 (0x80 while the head has no parameters on some firmware)
  std::uint32_t head_time_ms = 0;  // head clock, ms since midnight
  std::uint16_t motor_position = 0;
  std::uint8_t head_inf = 0;
};

struct VersionData {
  std::uint8_t software_version = 0, info_bits = 0;
  std::uint16_t uid = 0;
  std::uint32_t program_length = 0;
  std::uint16_t checksum = 0;
  std::uint8_t extra = 0;  // last body byte, not described in the public documentation
};

// mtHeadCommand parameters (the 66-byte form without the dual-channel "V3B" block, as single-channel heads
// like the Micron take it).
struct HeadCommand {
  std::uint8_t v3b = 0x01;       // 0x01: no V3B block; 0x1D: a 16-byte V3B block follows (dual channel)
  std::uint16_t hd_ctrl = kAdc8On | kRaw | kHasMot | kReplyAsl | kScanRight;
  std::uint8_t head_type = 0x11;  // 0x11 = DST (Micron); 0x02 = analogue imaging sonar
  std::uint8_t txn_ch1[4] = {0, 0, 0, 0}, txn_ch2[4] = {0, 0, 0, 0}, rxn_ch1[4] = {0, 0, 0, 0}, rxn_ch2[4] = {0, 0, 0, 0};
  std::uint16_t tx_pulse_len = 0;
  std::uint16_t range_scale = 100;  // decimetres in the low 14 bits, units code (0 = metres) in the top 2
  std::uint16_t left_limit = 2400, right_limit = 4000;
  std::uint8_t ad_span = 255, ad_low = 0;
  std::uint8_t igain_ch1 = 84, igain_ch2 = 84;  // 0..210 = 0..100 %
  std::uint16_t slope_ch1 = 0, slope_ch2 = 0;
  std::uint8_t mo_time = 25;       // motor step delay [10 us]
  std::uint8_t step_angle = 32;    // [1/16 gradian]: 32 = 1.8 deg
  std::uint16_t ad_interval = 104; // sampling interval [640 ns]
  std::uint16_t nbins = 200;
  std::uint16_t max_ad_buf = 500, lockout = 100, minor_axis = 1600;
  std::uint8_t major_axis = 1, ctl2 = 0;
  std::uint16_t scan_z = 0;
  std::vector<std::uint8_t> v3b_block;  // 16 bytes when v3b == 0x1D
};

struct SendData {
  std::uint32_t time_ms = 0;  // PC clock, ms since midnight
};

// How 4-bit data (adc8on off: two bins a byte) is unpacked. The public descriptions disagree: two public drivers
// take the first (nearer) bin from the high nibble (and leave the levels 0..15), another takes the low nibble first
// and scales by 17. This driver takes the high nibble first, as the two do and as the byte reads (first bin, first
// nibble on the wire); it scales by 17 so that level 15 is 255, the top of the 8-bit mode's 0..80 dB like the level it
// stands for (by 16 it was 240). Both are parameters (`four_bit_order`, `four_bit_scale`): check them on a capture
// of your head with adc8on off (docs/hardware.md). The driver asks for 8-bit data, so this matters for such a head.
struct FourBitFormat {
  std::string order = "high_first";  // high_first | low_first
  int scale = 17;                    // 16 or 17 (level 15 -> 240 or 255)
  static const ParamTable<FourBitFormat>& table();
};

struct HeadData {
  std::uint16_t byte_count = 0;  // body word at 13: bytes from 13 to the last data byte
  std::uint8_t device_type = 0x11, head_status = 0, sweep_code = kScanning;
  std::uint16_t hd_ctrl = 0;
  std::uint16_t range_scale = 0;
  std::uint8_t txn[4] = {0, 0, 0, 0};
  std::uint8_t gain = 0;
  std::uint16_t slope = 0;
  std::uint8_t ad_span = 0, ad_low = 0;
  std::uint16_t heading_offset = 0, ad_interval = 0, left_limit = 0, right_limit = 0;
  std::uint8_t step_angle = 0;
  std::uint16_t bearing = 0;         // [1/16 gradian], 0..6399
  std::vector<std::uint8_t> data;    // the dbytes as sent (4-bit packed when adc8on is off)
  // Echo amplitude per bin, 0..255; 4-bit data (adc8on off) unpacked as `four_bit` says.
  std::vector<std::uint8_t> bins(const FourBitFormat& four_bit = {}) const;
  double rangeScaleM() const { return (range_scale & 0x3FFF) / 10.0; }
  int rangeUnits() const { return range_scale >> 14; }
};

struct Command {  // a packet with no body: mtReBoot, mtSendVersion, mtSendBBUser
  std::uint8_t type = 0;
};
struct Other {  // a well-framed packet of a type this driver does not interpret (mtBBUserData, mtFpgaVersionData, ...)
  std::uint8_t type = 0;
  std::vector<std::uint8_t> body;
};

using Body = std::variant<Alive, VersionData, HeadCommand, SendData, HeadData, Command, Other>;

struct Message {
  std::uint8_t tx = kPcNode, rx = kSonarNode, node = kSonarNode, sequence = 0x80;
  Body body;
  std::uint8_t type() const;
};

// Encodes one packet (header, body, LF). tx/rx/node come from the message.
std::string encode(const Message& m);
// The usual PC -> sonar and sonar -> PC messages.
Message fromPc(Body b);
Message fromSonar(Body b);
// Parses a complete packet (as the StreamDecoder frames it). On failure returns nullopt and sets `reason`.
std::optional<Message> decodePacket(const std::uint8_t* p, std::size_t n, std::string& reason);

// Incremental framing of a byte stream: resynchronises on '@' after garbage or a damaged packet. Counters:
// packets, garbage_bytes, bad_hex_length, length_mismatch, too_long, bad_terminator, bad_body (with the per
// type reason in the event), multipacket.
class StreamDecoder {
 public:
  struct Event {
    std::optional<Message> message;
    std::string reason;                 // why the packet was rejected (empty when message is set)
    std::vector<std::uint8_t> raw;      // the packet's bytes (or the rejected candidate's first bytes)
  };
  void feed(const std::uint8_t* data, std::size_t n, std::vector<Event>& out);
  // Bytes not yet framed (a packet still arriving).
  std::size_t pending() const { return buf_.size(); }
  const Counters& counters() const { return counters_; }

 private:
  void reject(const std::string& reason, std::size_t bytes, std::vector<Event>& out);
  std::vector<std::uint8_t> buf_;
  Counters counters_;
};

// Angle conversions (1/16 gradian <-> radians).
double unitsToRad(int units);
int radToUnits(double rad);  // rounded, wrapped to 0..6399

}  // namespace micron
}  // namespace offshore_gnc
