#pragma once
// The intermediate level of the USV (thesis 4.3.1, Publication III Fig. 11), formerly the CCPilot display
// computer: autonomy commands go to the waterjet control units at a fixed rate; manual joystick / steering
// wheel frames seen on the bus win and silence autonomy; a watchdog sends the neutral command when autonomy
// goes quiet. GatewayPolicy is the pure logic (time given by the caller); CanGateway runs it on a SocketCan.
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "offshore_gnc/can/nmea2000.h"
#include "offshore_gnc/can/socket_can.h"
#include "offshore_gnc/can/waterjet_protocol.h"
#include "offshore_gnc/common/counters.h"

namespace offshore_gnc {
namespace can {

// Source / priority values as in offshore_gnc/JoystickCommand (kept ROS-free here).
enum Source : std::uint8_t { kAutonomy = 0, kWatchdog = 1, kRemote = 2, kJoystick = 3, kSteeringWheel = 4 };

struct GatewayConfig {
  double period = 0.05;            // s between command frames (20 Hz)
  double watchdog_timeout = 0.5;   // s without autonomy commands before neutral is sent
  double manual_hold = 0.3;        // s a manual frame keeps autonomy silenced
  jet::Addresses addresses;
  void validate() const;           // throws ConfigError naming the field
};

enum class Mode { kAutonomy, kManual, kWatchdog };
const char* toString(Mode m);

class GatewayPolicy {
 public:
  GatewayPolicy(GatewayConfig config, Counters& counters);
  // Autonomy command from the controller; false (counted) when non-finite or outside [-1, 1].
  bool onAutonomy(double surge, double sway, double yaw, double now);
  // A manual frame decoded from the bus.
  void onManual(const jet::Command& c, double now);
  // Frame to send now (nullopt while manual is active). Call every `period`.
  std::optional<CanFrame> tick(double now);
  Mode mode(double now) const;
  const GatewayConfig& config() const { return cfg_; }
  const jet::Command& lastManual() const { return manual_; }

 private:
  GatewayConfig cfg_;
  Counters& counters_;
  jet::Command autonomy_, manual_;
  double autonomy_at_ = -1e9, manual_at_ = -1e9;
  Mode last_mode_ = Mode::kWatchdog;
  bool first_tick_ = true;
  std::uint8_t counter_ = 0;
};

// Everything decoded from the bus that the ROS side publishes. Called from spinOnce() under the gateway's
// lock: publish and return, never call back into the CanGateway.
struct GatewayOutputs {
  std::function<void(const n2k::PositionRapid&, std::uint8_t source)> position;
  std::function<void(const n2k::VesselHeading&, std::uint8_t source)> heading;
  std::function<void(const n2k::CogSogRapid&, std::uint8_t source)> cog_sog;
  std::function<void(const jet::Status&)> status;
  std::function<void(const jet::Command&)> manual;
};

class CanGateway {
 public:
  using Clock = std::function<double()>;
  CanGateway(SocketCanOptions bus, GatewayConfig config, Counters& counters);
  // On any bus and clock (tests: a scripted bus and a simulated clock).
  CanGateway(std::unique_ptr<BusInterface> bus, GatewayConfig config, Counters& counters, Clock clock);
  // One iteration: waits up to max_wait_s for frames, handles them, sends the periodic command when due.
  void spinOnce(double max_wait_s, const GatewayOutputs& out);
  // Thread-safe: the ROS callbacks call these while another thread spins.
  bool onAutonomy(double surge, double sway, double yaw);
  Mode mode() const;
  BusState state() const;
  static double monotonic();  // seconds

 private:
  void handle(const CanFrame& f, double t, const GatewayOutputs& out);

  Counters& counters_;
  std::unique_ptr<BusInterface> bus_;
  Clock now_;
  GatewayPolicy policy_;
  jet::CounterCheck counters_check_;
  double next_tick_ = 0.0;
  mutable std::mutex mutex_;  // policy_ and bus_ state between the spinning thread and callers
};

}  // namespace can
}  // namespace offshore_gnc
