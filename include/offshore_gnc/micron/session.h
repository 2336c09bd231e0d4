#pragma once
// Micron sonar driver logic, ROS-free: the bring-up sequence (mtReBoot -> mtAlive -> mtSendVersion ->
// mtVersionData -> mtHeadCommand -> mtAlive without NoParams), then one mtSendData outstanding at a time, each
// mtHeadData turned into a beam (SonarBeam.msg conventions: bearing clockwise from the vehicle's forward axis in
// [0, 2pi), head status bits). Recovers by itself: a reply timeout resends the request, repeated timeouts
// resend the head command, an mtAlive with NoParams (head power-cycled) restarts the bring-up, reset() (serial
// reopened) starts over. Time is given by the caller (monotonic seconds), so tests run without a clock.
#include <cstdint>
#include <string>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/micron/seanet.h"

namespace offshore_gnc {
namespace micron {

// Where the head's angle scale points on the vehicle: the head angle (1/16 gradian) that looks along the
// vehicle's x axis, and whether the head is mounted inverted (boot down: head angles run anticlockwise).
struct HeadGeometry {
  double forward_offset = kPi;  // [rad] head angle of "forward" (3200 units; SeaNet's ahead)
  bool inverted = false;
  double bearingOf(int head_units) const;  // -> clockwise from forward, [0, 2pi)
  int unitsOf(double bearing) const;       // inverse, rounded to the 1/16 gradian
  static const ParamTable<HeadGeometry>& table();  // forward_offset_deg, inverted
};

// What the driver asks of the head. The defaults are the paper's configuration (10 m range, 90 degree forward
// sector, 1.8 degree step); the names and ranges are table()'s, validate() adds the rules across fields.
struct SonarSettings {
  double range = 10.0;               // [m]
  double sector = deg2rad(90.0);     // [rad] centred on forward; 2 pi = continuous rotation
  double step = deg2rad(1.8);        // [rad] motor step per ping (0.45, 0.9, 1.8, 3.6 deg are the documented ones)
  int bins = 200;                    // samples per beam
  double gain = 0.4;                 // initial receiver gain, 0..1 (0..80 dB)
  double ad_low = 0.0, ad_span = 80.0;  // [dB] mapped to intensity 0 and 255
  double sound_speed = 1500.0;       // [m/s]
  double beam_width = deg2rad(3.0);  // [rad] horizontal beam of the Micron (not in the protocol)
  HeadGeometry geometry;
  FourBitFormat four_bit;            // only with a head that sends 4-bit data (the driver asks for 8-bit)
  int head_type = 0x11;     // 0x11 = DST (Micron)
  int mo_time = 25;                  // motor step delay [10 us]
  bool reboot_on_start = true;
  double reply_timeout = 1.0;        // [s] for mtHeadData after mtSendData
  double command_retry = 2.0;        // [s] between mtSendVersion / mtHeadCommand attempts
  double alive_timeout = 3.0;        // [s] without any packet: the head is reported silent
  int max_data_timeouts = 5;         // consecutive reply timeouts before the head command is sent again
  static const ParamTable<SonarSettings>& table();
  void validate() const;             // throws ConfigError naming the parameter
  HeadCommand headCommand() const;
  int stepUnits() const;
  double binSize(std::uint16_t ad_interval) const;  // [m] range covered by one sample
};

struct Beam {
  double bearing = 0.0, beam_width = 0.0, range_resolution = 0.0, range_offset = 0.0;
  std::uint16_t status = 0;  // SonarBeam.msg STATUS_* bits
  std::vector<std::uint8_t> intensities;
  std::uint8_t head_status = 0, sweep_code = 0;  // raw, for diagnostics
};
// SonarBeam.msg status bits, repeated so the core does not include generated messages.
enum BeamStatus : std::uint16_t { kHeadReady = 1, kMotorOnBit = 2, kCentring = 4, kScanCw = 8, kSectorReverse = 16, kFault = 32 };

// The MicronSonar driver's parameters (config/micron/micron.yaml): the line, the frames, the head's mount and
// what the driver asks of the head.
struct DriverConfig {
  std::string port = "/dev/ttyUSB1";
  int baud = 115200;
  double reconnect_period = 1.0;  // [s] between reopen attempts of a vanished device
  double device_wait = 3.0;       // [s] the device must appear within this at start
  std::string frame_id = "auv/sonar", base_frame = "auv/base_link";
  std::vector<double> mount{0.6, 0.0, -0.2};  // [m] head in the body frame (FRD)
  bool publish_mount_tf = true;
  SonarSettings sonar;
  static const ParamTable<DriverConfig>& table();
};

class Session {
 public:
  enum class State { Start, AwaitAlive, AwaitVersion, Configuring, Scanning };
  explicit Session(const SonarSettings& s);

  // Bytes from the head: packets decoded, beams appended to `beams`.
  void feed(const std::uint8_t* data, std::size_t n, double now, std::vector<Beam>& beams);
  // What to send to the head now (possibly empty). Call every few tens of ms and after feed().
  // `time_of_day_ms` goes into mtSendData (the head echoes nothing of it; SeaNet sends the PC clock).
  std::string poll(double now, std::uint32_t time_of_day_ms = 0);
  // The serial line was (re)opened: start the bring-up again.
  void reset();

  State state() const { return state_; }
  static const char* stateName(State s);
  bool silent(double now) const { return now - last_packet_ > settings_.alive_timeout; }
  bool everHeard() const { return heard_; }
  const Alive& lastAlive() const { return alive_; }
  const VersionData& version() const { return version_; }
  const SonarSettings& settings() const { return settings_; }
  // beams, data_requests, data_timeouts, reconfigures, head_resets, motor_errors, power_loss, empty_beams, ...
  const Counters& counters() const { return counters_; }
  const Counters& decoderCounters() const { return decoder_.counters(); }

 private:
  void handle(const Message& m, double now, std::vector<Beam>& beams);
  void enter(State s);
  SonarSettings settings_;
  HeadCommand command_;
  StreamDecoder decoder_;
  std::vector<StreamDecoder::Event> events_;
  State state_ = State::Start;
  double last_sent_ = -1e9, last_packet_ = 0.0;
  bool heard_ = false, awaiting_ = false;
  int timeouts_in_row_ = 0;
  Alive alive_;
  VersionData version_;
  bool have_prev_ = false;
  double prev_bearing_ = 0.0;
  int direction_ = 0;
  Counters counters_;
};

}  // namespace micron
}  // namespace offshore_gnc
