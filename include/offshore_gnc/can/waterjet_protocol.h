#pragma once
// Our waterjet command bus (the real one is proprietary): ids, byte layout, scaling, rolling counter and
// CRC are specified in docs/can-protocol.md; this file is its one implementation.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>

#include "offshore_gnc/can/frame.h"
#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace can {

// The frames' source field: the values of offshore_gnc/JoystickCommand's SOURCE_* (kept ROS-free here).
enum Source : std::uint8_t { kAutonomy = 0, kWatchdog = 1, kRemote = 2, kJoystick = 3, kSteeringWheel = 4 };

namespace jet {

// Proprietary-B PGNs (PDU2, data page 0), so they share the bus with NMEA 2000 without clashing.
constexpr std::uint32_t kPgnCommand = 0xFF10;  // autonomy command, from the gateway
constexpr std::uint32_t kPgnManual = 0xFF11;   // manual joystick / steering wheel, from the bridge
constexpr std::uint32_t kPgnStatus = 0xFF20;   // one per waterjet control unit
// Per-jet set-points, from the gateway to one jet: Proprietary A (PDU1), so the identifier carries the jet's
// address as its destination.
constexpr std::uint32_t kPgnSetpoint = 0xEF00;
constexpr double kFullScale = 32000.0;         // raw value of a deflection of 1
constexpr int kMaxRpm = 6000;

struct Addresses {
  int gateway = 0x20;   // source address of the autonomy commands
  int bridge = 0x10;    // display computer that forwards the manual controls
  int jet_base = 0x30;  // port jet; starboard = jet_base + 1
  static const ParamTable<Addresses>& table();  // parameters address/{gateway,bridge,jet_base}
};

struct Command {
  double surge = 0.0, sway = 0.0, yaw = 0.0;  // [-1, 1]
  std::uint8_t source = 0;                    // JoystickCommand::SOURCE_*
  std::uint8_t counter = 0;                   // 4-bit rolling counter
};

struct Status {
  std::uint8_t jet = 0;  // 0 port, 1 starboard
  double rpm = 0.0;
  double nozzle = 0.0, bucket = 0.0;  // [-1, 1]
  std::uint8_t faults = 0;            // WaterjetStatus::FAULT_* (4 bits)
  std::uint8_t counter = 0;
};

// One jet's set-points (the per-jet frame): what the gateway's joystick allocation asks of that jet.
struct Setpoint {
  std::uint8_t jet = 0;         // 0 port, 1 starboard (the frame's destination is jet_base + jet)
  double rpm = 0.0;             // engine speed [rev/min], 0..kMaxRpm; below the unit's idle it idles
  double nozzle = 0.0;          // [-1, 1], + = starboard, as Status::nozzle
  double bucket = 0.0;          // [-1, 1], +1 full ahead, -1 full astern
  std::uint8_t source = 0;      // JoystickCommand::SOURCE_*
  std::uint8_t counter = 0;     // 4-bit rolling counter
};

enum class Error { kNone, kNotOurs, kLength, kChecksum, kRange };
const char* toString(Error e);

// CRC-8 SAE J1850 over the low byte of `ps` and payload bytes 0..6, ps being the identifier's PDU-specific
// field: a broadcast PGN's low byte, the destination of a per-jet frame (so a payload on the wrong id fails).
std::uint8_t crc(std::uint32_t ps, const std::uint8_t* payload7);
std::uint8_t crc8(const std::uint8_t* data, std::size_t n);  // plain CRC-8 SAE J1850

CanFrame encodeCommand(const Command& c, bool manual, const Addresses& a = {});
CanFrame encodeStatus(const Status& s, const Addresses& a = {});
CanFrame encodeSetpoint(const Setpoint& s, const Addresses& a = {});
// kNotOurs for frames of other protocols (unknown ids); other errors mean a broken frame of ours.
Error decodeCommand(const CanFrame& f, Command& out, bool* manual = nullptr);
Error decodeStatus(const CanFrame& f, Status& out, const Addresses& a = {});
// kNotOurs also for Proprietary A frames addressed to another device than the two jets.
Error decodeSetpoint(const CanFrame& f, Setpoint& out, const Addresses& a = {});

// Any frame of ours, whichever kind: `kind` says which member holds it; kNone with `error` when the frame is
// not ours (kNotOurs) or broken (the first error of the decoder its id belongs to).
struct Decoded {
  enum class Kind { kNone, kCommand, kManual, kStatus, kSetpoint } kind = Kind::kNone;
  Error error = Error::kNotOurs;
  Command command;    // kCommand (the gateway's 3-axis frame), kManual (the bridge's)
  Status status;      // kStatus
  Setpoint setpoint;  // kSetpoint
};
Decoded decode(const CanFrame& f, const Addresses& a = {});

// Rolling-counter check per sender: the first frame and each successor (mod 16) pass; a jump fails once and
// resynchronises, so a single lost frame costs one frame, not the stream.
class CounterCheck {
 public:
  bool accept(std::uint32_t key, std::uint8_t counter);
  void reset() { last_.clear(); }

 private:
  std::map<std::uint32_t, std::uint8_t> last_;
};

}  // namespace jet
}  // namespace can
}  // namespace offshore_gnc
